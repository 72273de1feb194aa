// The golden-versus-new picture of a gate report: the two runs' paths and
// events overlaid, the first divergence marked, and the error over time per
// channel below.
#pragma once

#include "compare.h"
#include "scene.h"
#include "trajectory.h"

#include <string>

namespace impulse::harness {

// Golden and new paths overlaid, and the error over time per channel.
std::string render_comparison_svg(const Scene* scene, const Trajectory& gold,
                                  const Trajectory& value, const Comparison& comparison);

} // namespace impulse::harness
