// When does the first collision in a step happen? The seed's answer is a binary
// search of the step (docs/physics.md, "The simulation loop of the seed", item
// 2; toi_bisection.cpp); the secant search finds the same instant in fewer
// iterations (toi_secant.cpp). Each method is one function here and one case
// in time_of_impact(), and one loop shared by the world search and local
// stepping's search of one pair (toi_trials.h).
#pragma once

#include "configuration.h"

namespace impulse {

struct TimeOfImpact {
    double time = 0.0; // seconds after the start: the latest instant known free of interpenetration
    int pair = -1;     // index into world.pairs of the pair interpenetrating just after it
    int iterations = 0; // trials integrated (halvings, for the bisection)
    bool converged = false;
};

// Every method searches [0, h] after `start`, given that pair `pair_at_h`
// interpenetrates in `at_h`, the configuration at h. It keeps a bracket
// [lo, hi]: nothing interpenetrates at lo, the offending pair does at hi.
// Converged means the bracket is at most solver.toi_tolerance wide and the
// pair is within solver.contact_tolerance of touching at lo; the configuration
// at the returned time lo is left in at_impact. At most
// solver.max_search_iterations iterations, each counted in
// world.work.toi_iterations; not converged (StepFailure::toi_not_converged)
// when they run out or the bracket stops shrinking, whatever the method.
TimeOfImpact time_of_impact(World& world, const Configuration& start, double h,
                            const Configuration& at_h, int pair_at_h, Configuration& at_impact);

// The seed: halve the bracket until it converges (toi_bisection.cpp).
TimeOfImpact bisect_time_of_impact(World& world, const Configuration& start, double h,
                                   int pair_at_h, Configuration& at_impact);

// Safeguarded regula falsi (Anderson-Bjorck, an Illinois variant) on the
// offending pair's signed separation s(t), halving when the chord would not
// shrink the bracket (toi_secant.cpp).
TimeOfImpact secant_time_of_impact(World& world, const Configuration& start, double h,
                                   const Configuration& at_h, int pair_at_h,
                                   Configuration& at_impact);

// Local stepping searches one pair alone, each body on its own clock: u
// seconds into the search body a is at advance(from_a, offset_a + u) (static
// bodies stay put), so a body restarted later in the step starts its search
// where its clock is. With both offsets 0 this is, trial for trial, what the
// world search does for a world of that one pair.
struct PairMotion {
    Pair pair;
    BodyState from_a;
    BodyState from_b;
    double offset_a = 0.0;
    double offset_b = 0.0;
};

// The same contract as time_of_impact() for one pair over [0, h], given its
// separation s_h < 0 at h; `pair` in the result is unused (-1). The states at
// the returned time are left in at_a and at_b.
TimeOfImpact pair_time_of_impact(World& world, const PairMotion& motion, double h, double s_h,
                                 BodyState& at_a, BodyState& at_b);
TimeOfImpact bisect_pair_time_of_impact(World& world, const PairMotion& motion, double h,
                                        BodyState& at_a, BodyState& at_b);
TimeOfImpact secant_pair_time_of_impact(World& world, const PairMotion& motion, double h,
                                        double s_h, BodyState& at_a, BodyState& at_b);

} // namespace impulse
