// The seed's time of collision (docs/physics.md, "The simulation loop of the
// seed", item 2): halve the bracket [lo, hi] until it is at most toi_tolerance
// wide and the offending pair is within contact_tolerance of touching at lo.
#include "toi_trials.h"

namespace impulse {

namespace {

// One loop for the world's trials and one pair's (toi_trials.h).
template <class Trials> TimeOfImpact bisect(World& world, Trials& trials, double h) {
    const SolverSettings& solver = world.solver;
    TimeOfImpact toi;
    double lo = 0.0; // known free of interpenetration
    double hi = h;   // known interpenetrating
    for (;;) {
        if (hi - lo <= solver.toi_tolerance &&
            trials.separation_at_lo() <= solver.contact_tolerance) {
            toi.converged = true;
            break;
        }
        const double mid = lo + 0.5 * (hi - lo);
        // A bracket that no longer shrinks means the tolerance is below the
        // spacing of doubles at this time: stop rather than loop forever.
        if (toi.iterations == solver.max_search_iterations || mid <= lo || mid >= hi) {
            break;
        }
        ++toi.iterations;
        ++world.work.toi_iterations;
        if (trials.interpenetrates_at(mid)) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    toi.time = lo;
    toi.pair = trials.pair();
    return toi;
}

} // namespace

TimeOfImpact bisect_time_of_impact(World& world, const Configuration& start, double h,
                                   int pair_at_h, Configuration& at_impact) {
    WorldTrials trials(world, start, pair_at_h, at_impact);
    return bisect(world, trials, h);
}

TimeOfImpact bisect_pair_time_of_impact(World& world, const PairMotion& motion, double h,
                                        BodyState& at_a, BodyState& at_b) {
    PairTrials trials(world, motion, at_a, at_b);
    return bisect(world, trials, h);
}

} // namespace impulse
