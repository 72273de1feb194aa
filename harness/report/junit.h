// The gate's checks as JUnit XML for CI: one testcase per scene, a <failure>
// for a physics mismatch and an <error> for input that could not be checked.
#pragma once

#include "scene_check.h"

#include <string>
#include <vector>

namespace impulse::harness {

std::string junit_xml(const std::vector<SceneCheck>& checks);

} // namespace impulse::harness
