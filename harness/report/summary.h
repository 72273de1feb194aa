// The gate's checks as Markdown fit for a pull-request comment: the verdict,
// a table of scenes, and each failure's message and details.
#pragma once

#include "scene_check.h"

#include <string>
#include <vector>

namespace impulse::harness {

std::string summary_markdown(const std::vector<SceneCheck>& checks);

} // namespace impulse::harness
