// The gate's checks as Markdown fit for a pull-request comment (at most
// 60,000 characters, under GitHub's 65,536): the totals first, the command
// that accepts the change, a pointer to the full report, causes shared by
// several scenes, a table of the failed scenes, the passed ones folded, and
// each failure's details folded; what does not fit is counted, never cut
// mid-row.
#pragma once

#include "scene_check.h"

#include <string>
#include <vector>

namespace impulse::harness {

std::string summary_markdown(const std::vector<SceneCheck>& checks);

} // namespace impulse::harness
