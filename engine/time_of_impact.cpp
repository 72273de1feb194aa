#include "time_of_impact.h"

namespace impulse {

TimeOfImpact time_of_impact(World& world, const Configuration& start, double h,
                            const Configuration& at_h, int pair_at_h, Configuration& at_impact) {
    switch (world.solver.toi) {
    case TimeOfImpactMethod::bisection:
        return bisect_time_of_impact(world, start, h, pair_at_h, at_impact);
    case TimeOfImpactMethod::secant:
        return secant_time_of_impact(world, start, h, at_h, pair_at_h, at_impact);
    }
    return bisect_time_of_impact(world, start, h, pair_at_h, at_impact);
}

TimeOfImpact bisect_time_of_impact(World& world, const Configuration& start, double h,
                                   int pair_at_h, Configuration& at_impact) {
    const SolverSettings& solver = world.solver;
    TimeOfImpact toi;
    toi.pair = pair_at_h;
    double lo = 0.0; // known free of interpenetration
    double hi = h;   // known interpenetrating
    at_impact = start;
    Configuration trial;
    for (;;) {
        if (hi - lo <= solver.toi_tolerance &&
            pair_separation(world, at_impact, world.pairs[toi.pair]) <= solver.contact_tolerance) {
            toi.converged = true;
            break;
        }
        const double mid = lo + 0.5 * (hi - lo);
        // A bracket that no longer shrinks means the tolerance is below the
        // spacing of doubles at this time: stop rather than loop forever.
        if (toi.iterations == solver.max_halvings || mid <= lo || mid >= hi) {
            break;
        }
        ++toi.iterations;
        ++world.work.toi_iterations;
        // The seed throws the trial away and integrates again from the last good state.
        advance_all(world, start, mid, trial);
        const int pair = first_interpenetrating_pair(world, trial);
        if (pair >= 0) {
            hi = mid;
            toi.pair = pair;
        } else {
            lo = mid;
            at_impact.swap(trial);
        }
    }
    toi.time = lo;
    return toi;
}

} // namespace impulse
