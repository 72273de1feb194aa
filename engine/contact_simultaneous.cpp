#include "contact_simultaneous.h"

#include "contact_problem.h"
#include "contact_resting.h"
#include "lcp.h"
#include "narrow_phase_query.h"
#include "restitution.h"

#include <cstddef>

namespace impulse {

// The problem (docs/engine.md, "Simultaneous contact"). At the collision
// instant every pair within contact_tolerance gives its manifold's points;
// the points whose bodies approach (v-_i = v1_AB . n < 0) or merely touch
// (v-_i = 0) take part. Find impulses lambda_i >= 0 along n_i with
//
//     w = A lambda + q >= 0,   lambda_i w_i = 0,
//     q_i = (1 + e) v-_i  where v-_i < 0,   q_i = v-_i (= 0) where v-_i = 0,
//
// A = J M^-1 J^T (delassus()). Since A lambda is the change of each point's
// relative normal velocity, w_i = v+_i + e v-_i at an approaching point and
// w_i = v+_i at a touching one: every point that takes an impulse ends with
// Newton's law, v+_i = -e v-_i (Eq. 3), every other point ends no closer than
// the law allows, and none ends approaching.
//
// Points already separating (v-_i > 0) are left out. Holding one to v+_i >= 0
// would let the contact push on a point that moves away, which does positive
// work lambda_i v-_i / 2 and can raise the energy even with e = 1 (a box flat
// on the ground, one corner coming down and the other going up). Without them
// the energy change is sum_i lambda_i (v-_i - q_i / 2) = sum over approaching
// points of lambda_i (1 - e) v-_i / 2 <= 0: nothing is gained, and with e = 1
// nothing is lost. If the impulses turn such a point around, it is a new
// collision at the same instant, which the step finds and resolves as any other.
SimultaneousResult resolve_simultaneous_contacts(World& world, double time,
                                                 std::vector<CollisionEvent>& events) {
    std::vector<ContactPoint> points;
    int first_approaching = -1;
    for (std::size_t p = 0; p < world.pairs.size(); ++p) {
        const Pair& pair = world.pairs[p];
        const Body& a = world.bodies[static_cast<std::size_t>(pair.a)];
        const Body& b = world.bodies[static_cast<std::size_t>(pair.b)];
        const Manifold m = pair_manifold(world, pair);
        for (int k = 0; k < m.point_count; ++k) {
            const Contact& c = m.points[static_cast<std::size_t>(k)];
            const double vn = relative_normal_velocity(a, b, c.point, c.normal); // Eqs. 1, 2
            if (vn > 0.0) {
                continue; // separating: left out (see above)
            }
            if (vn < 0.0 && first_approaching < 0) {
                first_approaching = static_cast<int>(points.size());
            }
            points.push_back(contact_point(world, static_cast<int>(p), c, vn));
        }
    }
    if (first_approaching < 0) {
        return {SimultaneousOutcome::none_approaching, -1, -1};
    }

    const std::size_t n = points.size();
    const std::vector<double> A = delassus_matrix(world, points);
    std::vector<double> q(n);
    for (std::size_t i = 0; i < n; ++i) {
        const ContactPoint& p = points[i];
        // Eq. 3: the target is v+ = -e v-, with e = 0 below the rest speed when resting.
        const double e =
            effective_restitution(world, world.bodies[static_cast<std::size_t>(p.a)],
                                  world.bodies[static_cast<std::size_t>(p.b)], p.contact);
        q[i] = p.vn < 0.0 ? (1.0 + e) * p.vn : p.vn;
    }
    const LcpSolution solution = solve_lcp(A, q);
    if (!solution.solved) {
        const ContactPoint& named = points[static_cast<std::size_t>(first_approaching)];
        return {SimultaneousOutcome::unsolved, named.a, named.b};
    }

    // Each impulse enters the velocities as its own term (Eqs. 8a, 8b), in
    // point order, so two mirror-image points add torques x and -x: exactly 0.
    for (std::size_t i = 0; i < n; ++i) {
        if (solution.lambda[i] > 0.0) {
            const ContactPoint& p = points[i];
            apply_impulse(world.bodies[static_cast<std::size_t>(p.a)],
                          world.bodies[static_cast<std::size_t>(p.b)], p.contact.point,
                          p.contact.normal, solution.lambda[i]);
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (solution.lambda[i] > 0.0) {
            const ContactPoint& p = points[i];
            const double vn_after = relative_normal_velocity(
                world.bodies[static_cast<std::size_t>(p.a)],
                world.bodies[static_cast<std::size_t>(p.b)], p.contact.point, p.contact.normal);
            events.push_back({time, p.a, p.b, p.contact.point, p.contact.normal, solution.lambda[i],
                              p.vn, vn_after});
        }
    }
    return {SimultaneousOutcome::resolved, -1, -1};
}

} // namespace impulse
