// Stepping a world with ccd while checking, between the steps' samples, that
// nothing went deeper than the contact tolerance: shared by the ccd tests.
#pragma once

#include "configuration.h"
#include "narrow_phase_query.h"
#include "world.h"

#include <catch2/catch.hpp>
#include <optional>
#include <vector>

namespace impulse::test {

// The deepest interpenetration of pair 0 along the free motion from `from`
// over u in [0, span] (span < 0: backward, from the end of a step), at n + 1
// evenly spaced instants. Zero gravity: every integrator moves uniformly, so
// integrating backward retraces the motion.
inline double deepest(World& world, const Configuration& from, double span, int n) {
    double lowest = 0.0;
    Configuration at;
    for (int k = 0; k <= n; ++k) {
        advance_all(world, from, span * k / n, at);
        const double s = pair_separation(world, at, world.pairs[0]);
        lowest = s < lowest ? s : lowest;
    }
    return lowest;
}

struct SweptRun {
    std::vector<CollisionEvent> events;
    std::optional<StepError> error;
};

// Steps `world` `steps` times by h with ccd, checking each step's free
// stretches (from its start to its first collision, and from its last
// collision to its end) at n + 1 instants: never deeper than the contact
// tolerance. Stops at the first error.
inline SweptRun run_checking_free_stretches(World& world, double h, int steps, int n) {
    const double tolerance = world.solver.contact_tolerance;
    SweptRun run;
    for (int k = 0; k < steps; ++k) {
        const Configuration start = configuration_of(world);
        const std::size_t before = run.events.size();
        run.error = step(world, k * h, h, run.events);
        if (run.error) {
            break;
        }
        const double t0 = k * h;
        const bool hit = run.events.size() > before;
        const double first = hit ? run.events[before].time - t0 : h;
        const double last = hit ? run.events.back().time - t0 : h;
        INFO("step " << k);
        CHECK(deepest(world, start, first, n) >= -tolerance * (1.0 + 1e-6));
        CHECK(deepest(world, configuration_of(world), last - h, n) >= -tolerance * (1.0 + 1e-6));
    }
    return run;
}

// The first t in (0, limit] at which gap(t) < 0, from a scan every 1e-6 s
// bisected to 1e-16 s (the last time before it, lo, is returned), or -1 when
// there is none: the closed-form touch of a motion written out by hand.
template <class Gap> double first_negative(Gap gap, double limit) {
    constexpr double scan = 1e-6;
    for (double k = 1.0; k * scan <= limit; k += 1.0) {
        if (gap(k * scan) < 0.0) {
            double lo = (k - 1.0) * scan;
            double hi = k * scan;
            while (hi - lo > 1e-16) {
                const double mid = 0.5 * (lo + hi);
                (gap(mid) < 0.0 ? hi : lo) = mid;
            }
            return lo;
        }
    }
    return -1.0;
}

} // namespace impulse::test
