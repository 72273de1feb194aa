// Grid settings an engine under study does not act on. An outside engine
// gets the sweep's integrator and time-of-impact tolerance as solver keys it
// may ignore (docs/engine-protocol.md, "Overrides"); when it does, every such
// point repeats one run and the table and plot show copies of one point. The
// sweep sees it in its first time step's runs: identical trajectories.
#pragma once

#include "sweep.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace impulse::harness {

// The grid of the first time step, in engine_points' order (integrator
// outer, tolerance inner), with the digest of each point's trajectory (0
// where the point was not measured).
struct FirstStepRuns {
    std::size_t integrators = 0;
    std::size_t tolerances = 0;
    std::vector<std::uint64_t> digests; // integrators * tolerances
};

struct IgnoredOverrides {
    bool integrator = false;    // every integrator gave the same trajectory
    bool toi_tolerance = false; // every tolerance gave the same trajectory
};

// What the first time step's runs show: a setting is ignored when it has at
// least two values and, for every value of the other, all of its points were
// measured and their trajectories are identical. A refusal or failure at any
// of them means the engine tells the values apart.
IgnoredOverrides ignored_overrides(const FirstStepRuns& runs);

// Marks every point that repeats another skipped, its reason naming the
// setting: those with another integrator than the grid's first when the
// integrator is ignored, likewise the tolerance. Points already measured
// (the first time step's) are kept measured only for the first values.
void skip_repeated_points(std::vector<SweepPoint>& points, const SweepConfig& config,
                          const IgnoredOverrides& ignored);

} // namespace impulse::harness
