// The gate's checks as JUnit XML for CI: one testcase per scene, a <failure>
// for a physics mismatch and an <error> for input that could not be checked;
// with `impulse check --compare`, the reference comparison as a second
// <testsuite> (impulse.compare) of the same document.
#pragma once

#include "engine_comparison.h"
#include "scene_check.h"

#include <string>
#include <vector>

namespace impulse::harness {

std::string junit_xml(const std::vector<SceneCheck>& checks);
// The gate's suite, then comparison_junit's suite; <testsuites> counts both.
std::string junit_xml(const std::vector<SceneCheck>& checks, const ComparisonReport& comparison);

} // namespace impulse::harness
