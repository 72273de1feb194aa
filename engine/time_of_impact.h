// When does the first collision in a step happen? The seed's answer: a binary
// search of the step (PHYSICS.md, "The simulation loop of the seed", item 2).
#pragma once

#include "configuration.h"

namespace impulse {

struct TimeOfImpact {
    double time = 0.0; // seconds after the start: the latest instant known free of interpenetration
    int pair = -1;     // index into world.pairs of the pair interpenetrating just after it
    int halvings = 0;
    bool converged = false;
};

// Searches [0, h] after `start`, given that pair `pair_at_h` interpenetrates at
// h. Converged means the bracket is at most solver.toi_tolerance wide and the
// pair is within solver.contact_tolerance of touching; the configuration at
// the returned time is left in at_impact.
TimeOfImpact bisect_time_of_impact(World& world, const Configuration& start, double h,
                                   int pair_at_h, Configuration& at_impact);

} // namespace impulse
