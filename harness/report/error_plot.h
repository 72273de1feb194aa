// The error over time, golden versus new: per frame and per frame channel
// (position, angle, velocity, angular velocity) the largest |new - gold| over
// the bodies, drawn on a log scale.
#pragma once

#include "compare.h"
#include "trajectory.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace impulse::harness::picture {

// The frame channels come first in Channel (tolerance.h): these four.
inline constexpr std::size_t frame_channel_count = 4;
inline constexpr std::array<const char*, frame_channel_count> channel_colours = {
    "#1f77b4", "#e8710a", "#2ca02c", "#9467bd"};
inline constexpr std::array<const char*, frame_channel_count> channel_dashes = {"", "7 3", "2 2",
                                                                                "9 3 2 3"};
// The channel's name for people: "angular velocity".
std::string channel_label(std::size_t channel);

struct ErrorSeries {
    std::vector<double> t;
    // per frame channel: max |new - gold| over columns
    std::array<std::vector<double>, frame_channel_count> error;
};

// The frames both runs have; a NaN difference counts as infinite.
ErrorSeries error_series(const Trajectory& gold, const Trajectory& value);

// Time on x, |new - gold| on a log y axis from 1e-18 up, and a dashed line at
// the first divergence; returns the panel's bottom.
double draw_error_panel(std::string& out, const ErrorSeries& series, double left, double top,
                        double width, double height, const Divergence* first);

} // namespace impulse::harness::picture
