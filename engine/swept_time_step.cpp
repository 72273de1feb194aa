#include "swept_time_step.h"

#include "contact_resting.h"
#include "continuous_collision.h"
#include "shape.h"

#include <algorithm>
#include <utility>

namespace impulse {

namespace {

// How deep a pair may go along the swept motion before it counts as a
// crossing: half the thinner body's inradius. A held contact ends each step
// within the contact tolerance and dips between the ends by at most the
// sagitta of a turn (R theta^2 / 8: 1.3 mm for a 0.35 m box turning 0.17 rad
// in a step), far less than any body's half inradius in the piles measured;
// a body passing through another goes at least as deep as the thinner one's
// inradius (a disc through a wall: its radius plus the wall's half width).
double crossing_depth(const Shape& a, const Shape& b) {
    return 0.5 * std::min(inradius(a), inradius(b));
}

} // namespace

std::optional<StepError> swept_crossing(World& world, const TimeSteppingScratch& s, double t0,
                                        double h) {
    const std::size_t n = world.bodies.size();
    // The step's paths as one interval of constant accelerations, the form
    // the sweep integrates (advance_body under resting contact forces).
    Configuration paths(s.start);
    RestingContacts motion;
    motion.any = true;
    motion.accelerations.assign(n, Acceleration{world.gravity, 0.0});
    for (int i = 0; i < s.islands.count(); ++i) {
        if (s.island_pushed[static_cast<std::size_t>(i)] == 0) {
            continue; // its bodies took their free flight
        }
        const int first = s.islands.body_offsets[static_cast<std::size_t>(i)];
        const int last = s.islands.body_offsets[static_cast<std::size_t>(i) + 1];
        for (int k = first; k < last; ++k) {
            const std::size_t b =
                static_cast<std::size_t>(s.islands.bodies[static_cast<std::size_t>(k)]);
            const BodyState& end = world.bodies[b].state;
            paths[b].velocity = (1.0 / h) * (end.position - s.start[b].position);
            paths[b].angular_velocity =
                world.bodies[b].rotates() ? (end.angle - s.start[b].angle) / h : 0.0;
            motion.accelerations[b] = Acceleration{Vec2{0.0, 0.0}, 0.0};
        }
    }
    std::vector<Pair> pairs;
    std::vector<double> depth;
    pairs.reserve(s.pairs.size());
    depth.reserve(s.pairs.size());
    for (const CandidatePair& candidate : s.pairs) {
        Pair pair{candidate.a, candidate.b};
        if (world.bodies[static_cast<std::size_t>(pair.a)].is_static()) {
            std::swap(pair.a, pair.b); // the sweep's pairs have a dynamic
        }
        pairs.push_back(pair);
        depth.push_back(crossing_depth(world.bodies[static_cast<std::size_t>(pair.a)].shape,
                                       world.bodies[static_cast<std::size_t>(pair.b)].shape));
    }
    // The bodies stay at the step's end; only the sweep's samples move.
    std::swap(world.resting_contacts, motion);
    const SweptContact found = first_swept_crossing(world, paths, pairs, depth, h);
    std::swap(world.resting_contacts, motion);
    if (!found.converged) {
        const Pair& stalled = pairs[static_cast<std::size_t>(found.stalled_pair)];
        return StepError{StepFailure::sweep_not_converged, t0, stalled.a, stalled.b};
    }
    if (found.pair < 0) {
        return std::nullopt;
    }
    const Pair& crossed = pairs[static_cast<std::size_t>(found.pair)];
    return StepError{StepFailure::swept_crossing, t0 + found.time, crossed.a, crossed.b};
}

} // namespace impulse
