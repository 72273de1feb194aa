// The picture of one run: the scene's bodies drawn at key frames, every
// dynamic body's path, and every event's contact point and normal.
#pragma once

#include "scene.h"
#include "trajectory.h"

#include <string>

namespace impulse::harness {

std::string render_svg(const Scene& scene, const Trajectory& trajectory);

// Without the scene the shapes are unknown: paths, contact points and normals only.
std::string render_svg(const Trajectory& trajectory);

} // namespace impulse::harness
