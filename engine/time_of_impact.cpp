#include "time_of_impact.h"

#include "integrator.h"
#include "manifold.h"

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

void pair_state_at(World& world, const PairMotion& motion, double u, BodyState& a, BodyState& b) {
    const auto at = [&](int index, const BodyState& from, double offset) {
        const Body& body = world.bodies[static_cast<std::size_t>(index)];
        // Not integrated over zero time either: that could turn a -0.0 into +0.0.
        if (body.is_static() || offset + u == 0.0) {
            return from;
        }
        ++world.work.body_advances;
        return advance(world.solver.integrator, from, world.gravity, body.rotates(), offset + u);
    };
    a = at(motion.pair.a, motion.from_a, motion.offset_a);
    b = at(motion.pair.b, motion.from_b, motion.offset_b);
}

double pair_separation(World& world, const Pair& pair, const BodyState& a, const BodyState& b) {
    ++world.work.narrow_phase_queries;
    return separation(world.bodies[static_cast<std::size_t>(pair.a)].shape, transform_of(a),
                      world.bodies[static_cast<std::size_t>(pair.b)].shape, transform_of(b));
}

TimeOfImpact pair_time_of_impact(World& world, const PairMotion& motion, double h, double s_h,
                                 BodyState& at_a, BodyState& at_b) {
    switch (world.solver.toi) {
    case TimeOfImpactMethod::bisection:
        return bisect_pair_time_of_impact(world, motion, h, at_a, at_b);
    case TimeOfImpactMethod::secant:
        return secant_pair_time_of_impact(world, motion, h, s_h, at_a, at_b);
    }
    return bisect_pair_time_of_impact(world, motion, h, at_a, at_b);
}

// bisect_time_of_impact() for one pair: the same bracket, the same trials and
// the same tests, so a world of one pair gives the same bits either way.
TimeOfImpact bisect_pair_time_of_impact(World& world, const PairMotion& motion, double h,
                                        BodyState& at_a, BodyState& at_b) {
    const SolverSettings& solver = world.solver;
    TimeOfImpact toi;
    double lo = 0.0;
    double hi = h;
    pair_state_at(world, motion, 0.0, at_a, at_b);
    double s_lo = pair_separation(world, motion.pair, at_a, at_b);
    BodyState trial_a;
    BodyState trial_b;
    for (;;) {
        if (hi - lo <= solver.toi_tolerance && s_lo <= solver.contact_tolerance) {
            toi.converged = true;
            break;
        }
        const double mid = lo + 0.5 * (hi - lo);
        if (toi.iterations == solver.max_halvings || mid <= lo || mid >= hi) {
            break;
        }
        ++toi.iterations;
        ++world.work.toi_iterations;
        pair_state_at(world, motion, mid, trial_a, trial_b);
        const double s = pair_separation(world, motion.pair, trial_a, trial_b);
        if (s < 0.0) {
            hi = mid;
        } else {
            lo = mid;
            s_lo = s;
            at_a = trial_a;
            at_b = trial_b;
        }
    }
    toi.time = lo;
    return toi;
}

} // namespace impulse
