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
// Pose numbers (x, y, angle per body per frame) per run at most, about 5 MB
// of page: a run of many bodies gets fewer frames (never fewer than
// replay_min_frames).
inline constexpr std::size_t replay_value_budget = 600'000;
inline constexpr std::size_t replay_min_frames = 100;

// The frames per run shown for `bodies` bodies under `budget` frames.
std::size_t replay_frames_for(std::size_t bodies, std::size_t budget);

// Empty when the check lacks a golden or a new run, or one has no frame.
std::string replay_json(const SceneCheck& check, std::size_t budget = replay_frame_budget);

} // namespace impulse::harness
