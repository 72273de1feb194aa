// The gate's results for a terminal (impulse check): one row per scene, the
// details of each failure, causes shared by several scenes and the totals;
// or, quiet, only the rows of the scenes that failed or could not be checked
// and the totals, for a CI log.
#pragma once

#include "scene_check.h"

#include <string>
#include <vector>

namespace impulse::harness {

std::string check_table(const std::vector<SceneCheck>& checks, bool quiet);

// The totals line the table ends with: "3 scenes: 2 passed, 1 failed, 0 errors".
std::string check_totals_line(const std::vector<SceneCheck>& checks);

} // namespace impulse::harness
