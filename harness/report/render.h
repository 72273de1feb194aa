// SVG pictures of motion: bodies at key frames with their paths, contact
// points and normals; and golden-versus-new pictures for gate reports.
#pragma once

#include "compare.h"
#include "scene.h"
#include "trajectory.h"

#include <string>

namespace impulse::harness {

// The scene's bodies drawn at key frames, every dynamic body's path, and every
// event's contact point and normal.
std::string render_svg(const Scene& scene, const Trajectory& trajectory);

// Without the scene the shapes are unknown: paths, contact points and normals only.
std::string render_svg(const Trajectory& trajectory);

// Golden and new paths overlaid, and the error over time per channel.
std::string render_comparison_svg(const Scene* scene, const Trajectory& gold,
                                  const Trajectory& value, const Comparison& comparison);

// The earliest of comparison.first_divergences by golden time (a frame value
// before an event at the same time, then column order); nullptr when none.
const Divergence* first_divergence(const Comparison& comparison);

} // namespace impulse::harness
