// The report page's plots over time, as JSON for its script: each diverging
// channel (golden, new and |new - golden|) and each run's conserved totals
// (energy, momentum, angular momentum).
#pragma once

#include "compare.h"
#include "scene.h"
#include "trajectory.h"

#include <cstddef>
#include <string>
#include <vector>

namespace impulse::harness {

// Channels shown per scene: the earliest to diverge; the page says how many
// more there are (a gas can have sixty).
inline constexpr std::size_t max_plotted_channels = 6;

// {"list": [{"name", "t", "gold", "new", "diff"}...], "more": N}: the frame
// columns that diverge, earliest first (then in column order), at `frames`,
// which both runs must have. The difference is taken here at full precision
// and only then shortened, so a 1-ULP difference stays a 1-ULP difference.
std::string channel_series_json(const Trajectory& gold, const Trajectory& value,
                                const Comparison& comparison,
                                const std::vector<std::size_t>& frames);

// {"t", "E", "px", "py", "L"} at `frames` (docs/physics.md's totals, the
// ones the conservation expectations check), or null when the scene is not
// known or the run lacks a body's columns.
std::string totals_json(const Scene* scene, const Trajectory& run,
                        const std::vector<std::size_t>& frames);

} // namespace impulse::harness
