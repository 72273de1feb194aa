#include "contact_resting.h"

#include "contact_problem.h"
#include "lcp.h"
#include "manifold.h"
#include "narrow_phase_query.h"
#include "restitution.h"
#include "world.h"

#include <algorithm>
#include <cmath>

namespace impulse {

double rest_speed(const World& world) {
    return std::sqrt(2.0 * length(world.gravity) * world.solver.contact_tolerance);
}

namespace {

// The event model's v_rest. Explicit Euler moves a body by its velocity at
// the step's start, so a body that comes to a stop on the ground gains g h
// of approach in its next step before it moves at all, and every bounce
// reaches the ground again at about that speed: with e < 1 the bounces never
// fall below sqrt(2 g d), and a disc dropped at e = 0.3 hopped at 0.1 m/s for
// 60 s (an outside review). An approach within 2 g h of rest is below what
// that integrator resolves, so it ends in rest like one below sqrt(2 g d).
double event_rest_speed(const World& world) {
    const double v_rest = rest_speed(world);
    return world.solver.integrator == Integrator::euler
               ? v_rest + 2.0 * length(world.gravity) * world.step_dt
               : v_rest;
}

} // namespace

double effective_restitution(const World& world, const Body& a, const Body& b,
                             const Contact& contact) {
    if (!world.solver.resting) {
        return world.restitution;
    }
    const double vn = relative_normal_velocity(a, b, contact.point, contact.normal);
    return -vn <= event_rest_speed(world) ? 0.0 : world.restitution;
}

namespace {

// A resting point may separate at up to this fraction of v_rest and still be
// held: rounding, not motion. Held for 60 s at 1e-6 v_rest (1.4e-10 m/s under
// 9.81 m/s^2 and d = 1e-9 m) it rises at most 8.4e-9 m.
constexpr double resting_speed_bound = 1e-6;

// The touching points of every resting pair at the bodies' current states;
// marks those pairs in world.resting_contacts.pair_resting.
std::vector<ContactPoint> resting_points(World& world) {
    RestingContacts& rc = world.resting_contacts;
    const double v_rest = event_rest_speed(world);
    const double v_hold = resting_speed_bound * rest_speed(world);
    const double tolerance = world.solver.contact_tolerance;

    std::vector<ContactPoint> points;
    for (std::size_t p = 0; p < world.pairs.size(); ++p) {
        const Pair& pair = world.pairs[p];
        const Body& a = world.bodies[static_cast<std::size_t>(pair.a)];
        const Body& b = world.bodies[static_cast<std::size_t>(pair.b)];
        const Transform xa = transform_of(a.state);
        const Transform xb = transform_of(b.state);
        if (pair_separation(world, pair, xa, xb) > tolerance) {
            continue;
        }
        // The points of the pair just measured: one query with its separation.
        const Manifold m = collide(a.shape, xa, b.shape, xb, tolerance, world.solver.vertex_normal);
        // Resting: no point approaches faster than v_rest (faster is a
        // collision) and none separates faster than v_hold (faster must be
        // left to separate: holding it would lift the body for free).
        bool rests = m.point_count > 0;
        double vn[2] = {0.0, 0.0};
        for (int i = 0; i < m.point_count; ++i) {
            const Contact& c = m.points[static_cast<std::size_t>(i)];
            vn[i] = relative_normal_velocity(a, b, c.point, c.normal); // Eqs. 1, 2
            rests = rests && vn[i] >= -v_rest && vn[i] <= v_hold;
        }
        if (!rests) {
            continue;
        }
        rc.pair_resting[p] = 1;
        for (int i = 0; i < m.point_count; ++i) {
            points.push_back(contact_point(world, static_cast<int>(p),
                                           m.points[static_cast<std::size_t>(i)], vn[i]));
        }
    }
    return points;
}

// First the velocities: whatever the resting points still approach with
// (below v_rest: rounding, or a bounce too small to see) is taken out by an
// inelastic impulse (e = 0: q = v-), so the forces hold them at rest. It can
// only remove energy; it is no collision and records no event. False when the
// impulse LCP has no solution.
bool stop_approaching(World& world, const std::vector<ContactPoint>& points,
                      const std::vector<double>& A) {
    const std::size_t n = points.size();
    std::vector<double> q(n);
    bool approaching = false;
    for (std::size_t i = 0; i < n; ++i) {
        q[i] = points[i].vn;
        approaching = approaching || q[i] < 0.0;
    }
    if (!approaching) {
        return true;
    }
    const LcpSolution impulses = solve_lcp(A, q);
    if (!impulses.solved) {
        return false;
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (impulses.lambda[i] > 0.0) {
            const ContactPoint& pt = points[i];
            apply_impulse(world.bodies[static_cast<std::size_t>(pt.a)],
                          world.bodies[static_cast<std::size_t>(pt.b)], pt.contact.point,
                          pt.contact.normal, impulses.lambda[i]);
        }
    }
    return true;
}

// Then the forces: w = A f + q >= 0, f >= 0, f w = 0, where q is the relative
// normal acceleration without contact forces, gravity on each dynamic body
// (static bodies do not accelerate). Terms in omega^2 are left out: resting
// bodies do not spin. Fills world.resting_contacts; false when the force LCP
// has no solution.
bool hold(World& world, const std::vector<ContactPoint>& points, const std::vector<double>& A) {
    RestingContacts& rc = world.resting_contacts;
    const std::size_t n = points.size();
    const auto gravity_of = [&](int body) {
        return world.bodies[static_cast<std::size_t>(body)].is_static() ? Vec2{} : world.gravity;
    };
    std::vector<double> q(n);
    for (std::size_t i = 0; i < n; ++i) {
        q[i] = dot(gravity_of(points[i].a) - gravity_of(points[i].b), points[i].contact.normal);
    }
    const LcpSolution forces = solve_lcp(A, q);
    if (!forces.solved) {
        return false;
    }

    rc.any = true;
    rc.accelerations.assign(world.bodies.size(), Acceleration{});
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
        rc.accelerations[i].linear = gravity_of(static_cast<int>(i));
    }
    // +f n on a and -f n on b at the point, as an impulse is applied (Eqs. 8a,
    // 8b), each force its own term so mirror-image torques cancel exactly.
    for (std::size_t i = 0; i < n; ++i) {
        const ContactPoint& pt = points[i];
        const double f = forces.lambda[i];
        if (f == 0.0) {
            continue;
        }
        const Body& a = world.bodies[static_cast<std::size_t>(pt.a)];
        const Body& b = world.bodies[static_cast<std::size_t>(pt.b)];
        Acceleration& acc_a = rc.accelerations[static_cast<std::size_t>(pt.a)];
        Acceleration& acc_b = rc.accelerations[static_cast<std::size_t>(pt.b)];
        const Vec2 fn = f * pt.contact.normal;
        acc_a.linear += a.inv_mass * fn;
        acc_a.angular += pt.rn_a * f * a.inv_inertia;
        acc_b.linear -= b.inv_mass * fn;
        acc_b.angular -= pt.rn_b * f * b.inv_inertia;
    }
    return true;
}

} // namespace

bool find_resting_contacts(World& world, int& body_a, int& body_b) {
    RestingContacts& rc = world.resting_contacts;
    rc.any = false;
    rc.pair_resting.assign(world.pairs.size(), 0);
    const std::vector<ContactPoint> points = resting_points(world);
    if (points.empty()) {
        return true;
    }
    const std::vector<double> A = delassus_matrix(world, points);
    if (!stop_approaching(world, points, A) || !hold(world, points, A)) {
        body_a = points.front().a;
        body_b = points.front().b;
        return false;
    }
    return true;
}

} // namespace impulse
