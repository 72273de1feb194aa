// Tunnelling caught (solver.ccd; docs/engine.md, "Tunnelling"). The seed tests
// for interpenetration only at the end of a step, so a body that crosses a
// thin one within a step is never seen. With ccd every pair's motion over the
// step is swept by conservative advancement: from a free instant, step forward
// by as long as the pair's distance, padded by the contact tolerance, cannot
// be closed at the fastest the pair can approach; each sample is where the
// seed's test is made.
#pragma once

#include "configuration.h"

namespace impulse {

struct SweptContact {
    int pair = -1;         // index into world.pairs of the pair found interpenetrating, or -1: none
    double time = 0;       // when, after `start`: a sample at which it interpenetrates
    bool converged = true; // false: a pair needed more than solver.max_halvings samples
    int stalled_pair = -1; // then, which one
};

// The earliest sample over [0, h] after `start` at which some pair
// interpenetrates. Between samples no pair can interpenetrate by more than
// solver.contact_tolerance, so nothing passes through anything unseen.
SweptContact first_swept_contact(World& world, const Configuration& start, double h);

} // namespace impulse
