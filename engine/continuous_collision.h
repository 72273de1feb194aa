// Tunnelling caught (solver.ccd; docs/engine.md, "Tunnelling"). The seed tests
// for interpenetration only at the end of a step, so a body that crosses a
// thin one within a step is never seen. With ccd every pair's motion over the
// step is swept by conservative advancement (conservative_advancement.h):
// from a free sample, step forward by as long as the pair's gap, padded by
// the contact tolerance, cannot be closed; each sample is where the seed's
// test is made.
#pragma once

#include "configuration.h"

#include <vector>

namespace impulse {

struct SweptContact {
    int pair = -1;         // index into world.pairs of the pair found interpenetrating, or -1: none
    double time = 0;       // when, after `start`: a sample at which it interpenetrates
    bool converged = true; // false: a pair needed more than solver.max_search_iterations samples
    int stalled_pair = -1; // then, which one
};

// The earliest sample over (0, h] after `start` at which some pair
// interpenetrates (the seed's test, as first_interpenetrating_pair() makes it,
// of the poses advance_all() gives: the trial the time-of-impact search
// integrates there is the sample to the bit), ties going to the lower pair
// index; time = h and pair = -1 when none does. Between a pair's samples it
// cannot interpenetrate by more than solver.contact_tolerance past that test,
// so nothing passes through anything unseen. Each sample is one narrow-phase
// query and one body advance per dynamic body of its pair. Not converged when
// a pair needed more than solver.max_search_iterations samples before the earliest
// contact found (a pair that stalls only later does not matter: the step
// resolves that contact first and sweeps again from there).
SweptContact first_swept_contact(World& world, const Configuration& start, double h);

// The same sweep for time-stepping (docs/engine.md, "Tunnelling"): the
// earliest sample over (0, h] at which one of `pairs` (a dynamic, as in
// world.pairs) is deeper than its `depth`, its bodies moved from `start` as
// advance_body() moves them; `pair` indexes `pairs`. Deeper than its depth
// at no sample, a pair is nowhere deeper than depth + contact_tolerance.
SweptContact first_swept_crossing(World& world, const Configuration& start,
                                  const std::vector<Pair>& pairs, const std::vector<double>& depth,
                                  double h);

} // namespace impulse
