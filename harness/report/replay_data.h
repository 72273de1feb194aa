// A failed scene's data for the report page's replay and plots, as one JSON
// object its script reads: the view, the bodies' shapes, the static bodies,
// golden and new poses and collisions at the frames shown, the first
// divergence, the diverging channels and the conserved totals over time.
#pragma once

#include "scene_check.h"

#include <cstddef>
#include <string>

namespace impulse::harness {

// Frames per run the page carries at most; a longer run is shown every k-th
// frame (the first divergence's frame and the last always kept), and the
// page says so.
inline constexpr std::size_t replay_frame_budget = 2000;

// Empty when the check lacks a golden or a new run, or one has no frame.
std::string replay_json(const SceneCheck& check, std::size_t budget = replay_frame_budget);

} // namespace impulse::harness
