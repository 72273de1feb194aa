// Comparing a new trajectory with a golden: exact (every bit, -0.0 and +0.0
// told apart) or within per-channel tolerances.
#pragma once

#include "tolerance.h"
#include "trajectory.h"

#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

// One value that differs.
struct Divergence {
    std::string column; // "box.vy", or "events[3].impulse"
    Channel channel = Channel::position;
    std::size_t frame = 0; // frame index (or event index for event fields)
    double t = 0.0;        // the frame's or the event's golden time
    double gold = 0.0;
    double value = 0.0;
    double abs_diff = 0.0;
    // Both at the scale of the channel: abs_diff / max(|gold|, scale) and
    // ULPs at max(|gold|, |new|, scale) (scaled_difference.h), where scale
    // is the golden's largest |value| in this column or event field.
    double rel_diff = 0.0;
    std::uint64_t ulp = 0;
};

struct ChannelSummary {
    std::size_t compared = 0;
    std::size_t differing = 0;
    double max_abs = 0.0;
    double max_rel = 0.0;
    std::uint64_t max_ulp = 0;
};

struct Comparison {
    bool identical = true; // bit-for-bit, in every frame and event
    bool passed = true;    // identical in exact mode; within tolerance in tolerance mode
    // Differences in shape that make values incomparable (columns, frame
    // count, event count or event bodies); each one sentence.
    std::vector<std::string> structural;
    // The first divergent frame of every column that diverges, in column order;
    // then the first divergent field of the first divergent event.
    std::vector<Divergence> first_divergences;
    std::array<ChannelSummary, channel_count> channels{};
    // How far an event's golden time may be from a frame's and still be
    // that frame's collision (trajectory_columns.h), for first_divergence.h.
    double event_time_slack = 0.0;
};

// exact when tolerances is empty.
Comparison compare(const Trajectory& gold, const Trajectory& value,
                   const std::optional<Tolerances>& tolerances);

// Human-readable report of a failed comparison: the first divergent frame per
// body and channel (time, golden, new, absolute, relative and ULP difference),
// then per channel how many values differ and the largest differences.
std::string describe(const Comparison& comparison);

} // namespace impulse::harness
