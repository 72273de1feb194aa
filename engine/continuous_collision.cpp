#include "continuous_collision.h"

#include "conservative_advancement.h"
#include "integrator.h"
#include "narrow_phase_query.h"

namespace impulse {

namespace {

struct PairSweep {
    enum class Outcome { free, found, stalled } outcome = Outcome::free;
    double time = 0.0; // found: the sample that interpenetrates; stalled: the last free one
};

// Samples `pair` from `start` until its separation falls below `floor`, or up
// to `end`. With `strict`, another pair was found at `end` already, so a
// sample there could not be earlier and is not taken; otherwise the last
// sample is at exactly end = h, where the seed's end-of-step test looks.
PairSweep sweep_pair(World& world, const Configuration& start, const Pair& pair, double floor,
                     double end, bool strict) {
    const std::size_t ia = static_cast<std::size_t>(pair.a);
    const std::size_t ib = static_cast<std::size_t>(pair.b);
    const SweepMotion motion = sweep_motion_of(world, start, pair);
    BodyState at_a = start[ia];
    BodyState at_b = start[ib];
    double u = 0.0;
    double s = pair_separation(world, pair, at_a, at_b);
    int samples = 1;
    for (;;) {
        double next = u + safe_advance(world, pair, motion, u, s, floor, at_a, at_b, end);
        const bool last = !(next < end);
        if (last) {
            if (strict) {
                return {};
            }
            next = end;
        }
        if (samples >= world.solver.max_search_iterations) {
            return {PairSweep::Outcome::stalled, u};
        }
        at_a = advance_body(world, ia, start[ia], next);
        at_b = advance_body(world, ib, start[ib], next);
        s = pair_separation(world, pair, at_a, at_b);
        ++samples;
        if (s < floor) {
            return {PairSweep::Outcome::found, next};
        }
        if (last) {
            return {};
        }
        u = next;
    }
}

// The earliest sample over pairs(0..count) (pair_at(p), floor_at(p)), as
// first_swept_contact says.
template <class PairAt, class FloorAt>
SweptContact earliest(World& world, const Configuration& start, std::size_t count, PairAt pair_at,
                      FloorAt floor_at, double h) {
    SweptContact swept;
    int stalled = -1;
    double stalled_at = 0.0;
    for (std::size_t p = 0; p < count; ++p) {
        // Once a pair is found, later pairs need only be swept to before its
        // time: at the same time the lower index wins.
        const bool strict = swept.pair >= 0;
        const PairSweep r =
            sweep_pair(world, start, pair_at(p), floor_at(p), strict ? swept.time : h, strict);
        if (r.outcome == PairSweep::Outcome::found) {
            swept.pair = static_cast<int>(p);
            swept.time = r.time;
        } else if (r.outcome == PairSweep::Outcome::stalled &&
                   (stalled < 0 || r.time < stalled_at)) {
            stalled = static_cast<int>(p);
            stalled_at = r.time;
        }
    }
    // A pair that stalled only after the earliest contact does not matter: the
    // step resolves that contact and sweeps again from there.
    if (stalled >= 0 && (swept.pair < 0 || stalled_at < swept.time)) {
        swept.converged = false;
        swept.stalled_pair = stalled;
    }
    if (swept.pair < 0) {
        swept.time = h;
    }
    return swept;
}

} // namespace

SweptContact first_swept_contact(World& world, const Configuration& start, double h) {
    return earliest(
        world, start, world.pairs.size(), [&](std::size_t p) { return world.pairs[p]; },
        [&](std::size_t p) { return interpenetration_floor(world, p); }, h);
}

SweptContact first_swept_crossing(World& world, const Configuration& start,
                                  const std::vector<Pair>& pairs, const std::vector<double>& depth,
                                  double h) {
    return earliest(
        world, start, pairs.size(), [&](std::size_t p) { return pairs[p]; },
        [&](std::size_t p) { return -depth[p]; }, h);
}

} // namespace impulse
