// The gate's checks as a self-contained HTML page (index.html) with a picture
// per scene, and each failed scene's picture again as its own SVG file.
#pragma once

#include "scene_check.h"

#include <string>
#include <utility>
#include <vector>

namespace impulse::harness {

// (file name, content) for each failed scene's SVG, in scene order, then
// index.html; the names are plain file names to put in the report's folder.
std::vector<std::pair<std::string, std::string>>
html_report_files(const std::vector<SceneCheck>& checks);

} // namespace impulse::harness
