// Reading a trajectory by body: where a body's values sit in a frame, and
// which events involve it. Shared by the exact answers, the expectations and
// the Box2D observables.
#pragma once

#include "trajectory.h"

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

// A dynamic body's six channels, in column order: column "NAME.x" and so on
// (docs/design.md, trajectory format). Spelled here once.
inline constexpr std::array<const char*, 6> body_channel_suffixes = {".x",  ".y",  ".angle",
                                                                     ".vx", ".vy", ".omega"};

// Where one body's six values sit in a frame (docs/design.md, trajectory format).
struct BodyColumns {
    std::size_t x = 0, y = 0, angle = 0, vx = 0, vy = 0, omega = 0;
};

// Empty when the trajectory lacks one of the body's columns.
std::optional<BodyColumns> body_columns(const Trajectory& trajectory, const std::string& body);

// A frame's value; a short frame (a broken trajectory) reads as NaN, which
// fails every check.
double value_at(const std::vector<double>& frame, std::size_t column);
double frame_time(const std::vector<double>& frame);

// How far an event's time may be from a frame's and still be that frame's
// collision: 1e-9 of the step between the first two frames (0 with fewer, or
// without a t column). An engine stamps a collision with its step's end,
// t0 + dt, which may differ from the frame's k dt in the last bits (Box2D
// does); the observables and the first divergence both read it this way.
double event_time_slack(const Trajectory& trajectory);

bool involves(const TrajectoryEvent& event, const std::string& body);
// The indices of the events that involve `body`, in order.
std::vector<std::size_t> events_of(const Trajectory& trajectory, const std::string& body);

} // namespace impulse::harness
