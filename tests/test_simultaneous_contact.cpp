// Simultaneous contact (contacts: simultaneous) and its LCP solver, against
// answers derived by hand (docs/engine.md, "Simultaneous contact").
#include "contact_simultaneous.h"
#include "lcp.h"
#include "support.h"
#include "support/contact_problems.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

using namespace impulse;
using impulse::test::close_relative;
using impulse::test::Drop;
using impulse::test::dynamic_body;
using impulse::test::log_uniform;
using impulse::test::static_body;
using impulse::test::uniform;
using impulse::test::contact_problems::row_major;

namespace {

SolverSettings simultaneous_verlet() {
    SolverSettings s;
    s.integrator = Integrator::verlet;
    s.contacts = ContactMode::simultaneous;
    return s;
}

double kinetic_energy(const World& world) {
    double energy = 0.0;
    for (const Body& b : world.bodies) {
        if (b.is_static()) {
            continue;
        }
        energy += 0.5 * dot(b.state.velocity, b.state.velocity) / b.inv_mass;
        if (b.rotates()) {
            energy += 0.5 * b.state.angular_velocity * b.state.angular_velocity / b.inv_inertia;
        }
    }
    return energy;
}

Vec2 momentum(const World& world) {
    Vec2 p;
    for (const Body& b : world.bodies) {
        if (!b.is_static()) {
            p += (1.0 / b.inv_mass) * b.state.velocity;
        }
    }
    return p;
}

// The sum of |m v| over the bodies: the scale momentum's rounding is relative to.
double momentum_scale(const World& world) {
    double s = 0.0;
    for (const Body& b : world.bodies) {
        if (!b.is_static()) {
            s += length(b.state.velocity) / b.inv_mass;
        }
    }
    return s;
}

// Angular momentum about the origin: m (x cross v) + I omega.
double angular_momentum(const World& world) {
    double l = 0.0;
    for (const Body& b : world.bodies) {
        if (b.is_static()) {
            continue;
        }
        l += cross(b.state.position, b.state.velocity) / b.inv_mass;
        if (b.rotates()) {
            l += b.state.angular_velocity / b.inv_inertia;
        }
    }
    return l;
}

// A row of equal balls of radius 0.1 on the x axis, centres 0.2 apart and
// touching exactly (the centres -0.2 k are exact multiples of one double, so
// every gap computes to 0); the first, the striker, moves at +v.
World cradle(int balls, double mass, double v) {
    std::vector<Body> bodies;
    for (int k = 0; k < balls; ++k) {
        const double x = 0.2 * static_cast<double>(k - balls / 2);
        bodies.push_back(
            dynamic_body(make_circle(0.1), mass, {x, 0.0}, 0.0, k == 0 ? Vec2{v, 0.0} : Vec2{}));
    }
    SolverSettings s = simultaneous_verlet();
    return make_world(bodies, {0.0, 0.0}, 1.0, s);
}

} // namespace

TEST_CASE("A box landing flat stays flat, bitwise, under simultaneous contact",
          "[unit][simultaneous]") {
    // Box 1 x 0.5 (hx 0.5, hy 0.25), 1 kg, 1 m above static ground, e = 0.8.
    // Both bottom corners touch at once and the problem is symmetric under
    // swapping them, so the two impulses are equal bit for bit, their torques
    // are x and -x, and omega stays exactly 0: the box bounces like a point
    // mass, on the exact drop answers (docs/physics.md, "Exact answers").
    const Drop drop{1.0, 9.81, 0.8};
    const double dt = 1.0 / 60.0;
    const int impacts = 5;
    const auto steps = static_cast<long long>(std::ceil(drop.duration(impacts) / dt));
    const auto make = [](ContactMode contacts) {
        SolverSettings s = simultaneous_verlet();
        s.contacts = contacts;
        return make_world({static_body(make_box(50.0, 0.5), {0.0, -0.5}),
                           dynamic_body(make_box(0.5, 0.25), 1.0, {0.0, 1.25})},
                          {0.0, -9.81}, 0.8, s);
    };

    SECTION("simultaneous: angle and omega exactly 0 in every step") {
        World world = make(ContactMode::simultaneous);
        std::vector<CollisionEvent> events;
        for (long long k = 0; k < steps; ++k) {
            INFO("step " << k);
            REQUIRE_FALSE(step(world, static_cast<double>(k) * dt, dt, events));
            const BodyState& s = world.bodies[1].state;
            REQUIRE(s.angle == 0.0);
            REQUIRE(s.angular_velocity == 0.0);
            REQUIRE(s.velocity.x == 0.0);
        }
        REQUIRE(events.size() == 2 * static_cast<std::size_t>(impacts));
        double rebound = drop.v1();
        for (int n = 1; n <= impacts; ++n) {
            INFO("impact " << n);
            const CollisionEvent& left = events[2 * static_cast<std::size_t>(n - 1)];
            const CollisionEvent& right = events[2 * static_cast<std::size_t>(n - 1) + 1];
            rebound *= drop.e;
            CHECK(left.time == right.time);
            CHECK(left.impulse == right.impulse);
            CHECK(left.point.x == -right.point.x);
            CHECK(close_relative(left.time, drop.impact_time(n), 1e-9));
            CHECK(close_relative(left.vn_after, rebound, 1e-9));
            CHECK(close_relative(right.vn_after, rebound, 1e-9));
            // Each corner takes half of the point-mass impulse (1 + e) v M.
            CHECK(close_relative(left.impulse, 0.5 * (1.0 + drop.e) * rebound / drop.e, 1e-9));
        }
    }

    SECTION("single (the seed's): one corner first, so the box spins") {
        World world = make(ContactMode::single);
        std::vector<CollisionEvent> events;
        const auto first = static_cast<long long>(std::ceil(drop.t1() / dt));
        for (long long k = 0; k < first; ++k) {
            REQUIRE_FALSE(step(world, static_cast<double>(k) * dt, dt, events));
        }
        REQUIRE_FALSE(events.empty());
        CHECK(world.bodies[1].state.angular_velocity != 0.0);
    }
}

TEST_CASE("Newton's cradle: the touching balls leave together (the LCP model)",
          "[unit][simultaneous]") {
    // N equal balls of mass m in a touching row, the first at v, e = 1. The
    // N - 1 points form A = tridiag(-1, 2, -1) / m, q = (-2 v, 0, ..., 0): the
    // first point approaches, the others touch. (T^-1)_{i1} = (N - i) / N for
    // T = tridiag(-1, 2, -1) of size N - 1, so lambda_i = 2 v m (N - i) / N > 0
    // at every point, and the velocities after are
    //     striker  v - lambda_1 / m = v (2 - N) / N,
    //     ball k   (lambda_{k-1} - lambda_k) / m = 2 v / N  (k = 2 .. N),
    // the 1D elastic collision of m with the row as one body of mass (N - 1) m.
    // Momentum: v (2 - N) / N + (N - 1) 2 v / N = v. Energy: ((N - 2)^2 +
    // 4 (N - 1)) / N^2 = 1, conserved. N = 3: -v/3, 2v/3, 2v/3 (lambda = 4v/3,
    // 2v/3 m); N = 5: -3v/5, then 2v/5 four times. Not the textbook cradle
    // (striker stops, last ball leaves at v), which sequential impacts give.
    const double m = 0.17;
    const double v = 1.0;
    for (const int balls : {3, 5}) {
        INFO(balls << " balls");
        World world = cradle(balls, m, v);
        const double energy_before = kinetic_energy(world);
        std::vector<CollisionEvent> events;
        const SimultaneousResult r = resolve_simultaneous_contacts(world, 0.0, events);
        REQUIRE(r.outcome == SimultaneousOutcome::resolved);
        const double N = balls;
        CHECK(std::fabs(world.bodies[0].state.velocity.x - v * (2.0 - N) / N) <= 1e-12);
        for (int k = 1; k < balls; ++k) {
            CHECK(std::fabs(world.bodies[k].state.velocity.x - 2.0 * v / N) <= 1e-12);
        }
        for (const Body& b : world.bodies) {
            CHECK(b.state.velocity.y == 0.0);
            CHECK(b.state.angular_velocity == 0.0);
        }
        REQUIRE(events.size() == static_cast<std::size_t>(balls - 1));
        for (int i = 1; i < balls; ++i) {
            const CollisionEvent& ev = events[static_cast<std::size_t>(i - 1)];
            CHECK(ev.body_a == i - 1);
            CHECK(ev.body_b == i);
            CHECK(close_relative(ev.impulse, 2.0 * v * m * (N - i) / N, 1e-12));
            CHECK(ev.vn_before == (i == 1 ? -v : 0.0));
            CHECK(std::fabs(ev.vn_after - (i == 1 ? v : 0.0)) <= 1e-12);
        }
        CHECK(std::fabs(momentum(world).x - m * v) <= 1e-14 * m * v);
        CHECK(close_relative(kinetic_energy(world), energy_before, 1e-12));
    }
}

TEST_CASE("A ball landing in a V of two balls: mirror-image outcome, bit for bit",
          "[unit][simultaneous]") {
    // Striker (mass Ms = 2) at (0, 0.5) falling at v onto two balls (m = 1) at
    // (-0.375, 0) and (0.375, 0), all of radius 0.3125: a 3-4-5 triangle, so
    // both gaps are exactly 0 and the normals are (+-0.6, 0.8) = (+-s, c).
    // A = [[1/Ms + 1/m, (c^2 - s^2)/Ms], [(c^2 - s^2)/Ms, 1/Ms + 1/m]] (circles:
    // no lever arm), q = -(1 + e) v c at both, so lambda = (1 + e) v c / (1/Ms +
    // 1/m + (c^2 - s^2)/Ms) at both; vy' = -v + 2 lambda c / Ms for the
    // striker, -lambda (+-s, c) / m for the balls.
    const double Ms = 2.0;
    const double m = 1.0;
    const double v = 3.0;
    const double r = 0.3125;
    for (const double e : {1.0, 0.6}) {
        INFO("e = " << e);
        SolverSettings s = simultaneous_verlet();
        World world = make_world({dynamic_body(make_circle(r), Ms, {0.0, 0.5}, 0.0, {0.0, -v}),
                                  dynamic_body(make_circle(r), m, {-0.375, 0.0}),
                                  dynamic_body(make_circle(r), m, {0.375, 0.0})},
                                 {0.0, 0.0}, e, s);
        const double energy_before = kinetic_energy(world);
        std::vector<CollisionEvent> events;
        REQUIRE(resolve_simultaneous_contacts(world, 0.0, events).outcome ==
                SimultaneousOutcome::resolved);
        REQUIRE(events.size() == 2);
        const BodyState& striker = world.bodies[0].state;
        const BodyState& left = world.bodies[1].state;
        const BodyState& right = world.bodies[2].state;
        CHECK(events[0].impulse == events[1].impulse);
        CHECK(striker.velocity.x == 0.0);
        CHECK(striker.angular_velocity == 0.0);
        CHECK(left.velocity.x == -right.velocity.x);
        CHECK(left.velocity.y == right.velocity.y);
        CHECK(left.angular_velocity == -right.angular_velocity);

        const double c = 0.8;
        const double sn = 0.6;
        const double lambda = (1.0 + e) * v * c / (1.0 / Ms + 1.0 / m + (c * c - sn * sn) / Ms);
        CHECK(close_relative(events[0].impulse, lambda, 1e-12));
        CHECK(close_relative(striker.velocity.y, -v + 2.0 * lambda * c / Ms, 1e-12, v));
        CHECK(close_relative(left.velocity.x, -lambda * sn / m, 1e-12));
        CHECK(close_relative(left.velocity.y, -lambda * c / m, 1e-12));
        for (const CollisionEvent& ev : events) {
            CHECK(std::fabs(ev.vn_after + e * ev.vn_before) <= 1e-12 * v); // Eq. 3
        }
        CHECK(std::fabs(momentum(world).y + Ms * v) <= 1e-14 * Ms * v);
        if (e == 1.0) {
            CHECK(close_relative(kinetic_energy(world), energy_before, 1e-12));
        } else {
            CHECK(kinetic_energy(world) < energy_before);
        }
    }
}

TEST_CASE("A corner moving away is left out: no energy is gained at e = 1",
          "[unit][simultaneous]") {
    // Box hx = 1, hy = 0.25, M = 1 (I = (4 + 0.25) / 12) flat on static ground
    // with vy = -0.2, omega = 0.5: the left corner comes down at
    // -0.2 - 0.5 = -0.7, the right one goes up at +0.3. Holding the right
    // corner to v+ >= 0 as well would push on a point moving away: that LCP
    // gives lambda = (0.4255, 0.1245) and raises the energy from 0.0643 to
    // 0.0829 J. Left out, the left corner alone takes
    //     lambda_L = 2 * 0.7 / (1/M + hx^2 / I),
    // and the right corner then moves at 0.3 + (1/M - hx^2 / I) lambda_L < 0:
    // a second collision at the same instant, which resolves it alone.
    const double I = (4.0 + 0.25) / 12.0;
    SolverSettings s = simultaneous_verlet();
    World world =
        make_world({static_body(make_box(50.0, 0.5), {0.0, -0.5}),
                    dynamic_body(make_box(1.0, 0.25), 1.0, {0.0, 0.25}, 0.0, {0.0, -0.2}, 0.5)},
                   {0.0, 0.0}, 1.0, s);
    world.bodies[1].inv_inertia = 1.0 / I;
    const double energy_before = kinetic_energy(world);

    std::vector<CollisionEvent> events;
    REQUIRE(resolve_simultaneous_contacts(world, 0.0, events).outcome ==
            SimultaneousOutcome::resolved);
    REQUIRE(events.size() == 1);
    const double lambda_left = 2.0 * 0.7 / (1.0 + 1.0 / I);
    CHECK(events[0].point.x == -1.0);
    CHECK(close_relative(events[0].impulse, lambda_left, 1e-12));
    CHECK(close_relative(events[0].vn_after, 0.7, 1e-12));
    CHECK(close_relative(kinetic_energy(world), energy_before, 1e-12));
    const BodyState& box = world.bodies[1].state;
    const double right_after = box.velocity.y + box.angular_velocity * 1.0;
    CHECK(close_relative(right_after, 0.3 + (1.0 - 1.0 / I) * lambda_left, 1e-12));
    REQUIRE(right_after < 0.0);

    // The second collision: the right corner alone, the left one now separating.
    REQUIRE(resolve_simultaneous_contacts(world, 0.0, events).outcome ==
            SimultaneousOutcome::resolved);
    REQUIRE(events.size() == 2);
    CHECK(events[1].point.x == 1.0);
    CHECK(close_relative(events[1].impulse, -2.0 * right_after / (1.0 + 1.0 / I), 1e-12));
    CHECK(close_relative(kinetic_energy(world), energy_before, 1e-12));
    CHECK(resolve_simultaneous_contacts(world, 0.0, events).outcome ==
          SimultaneousOutcome::none_approaching);
}

TEST_CASE("One touching point: simultaneous contact gives single contact's bits",
          "[unit][simultaneous]") {
    // With one point the LCP is lambda = -q / A_11 = -(1 + e) vn / k, Eq. 9's
    // operations in Eq. 9's order, so the two modes agree bit for bit.
    const auto run = [](ContactMode contacts, const Body& body) {
        SolverSettings s = simultaneous_verlet();
        s.contacts = contacts;
        World world =
            make_world({static_body(make_box(50.0, 0.5), {0.0, -0.5}), body}, {0.0, -9.81}, 0.7, s);
        return test::run_steps(world, 1.0 / 60.0, 60);
    };
    for (const Body& body : {dynamic_body(make_circle(0.5), 2.0, {0.0, 1.5}),
                             dynamic_body(make_box(0.5, 0.25), 1.0, {0.3, 1.5}, 0.4)}) {
        const std::vector<CollisionEvent> single = run(ContactMode::single, body);
        const std::vector<CollisionEvent> simultaneous = run(ContactMode::simultaneous, body);
        REQUIRE_FALSE(single.empty());
        REQUIRE(single.size() == simultaneous.size());
        for (std::size_t i = 0; i < single.size(); ++i) {
            CHECK(single[i].time == simultaneous[i].time);
            CHECK(single[i].impulse == simultaneous[i].impulse);
            CHECK(single[i].vn_after == simultaneous[i].vn_after);
            CHECK(single[i].point == simultaneous[i].point);
        }
    }
}

TEST_CASE("Random multi-contact problems: momentum exact, energy never gained, Eq. 3 holds",
          "[unit][simultaneous]") {
    // A box of random mass lying across two boxes side by side, all three
    // moving at random (up to four points, free space: momentum and angular
    // momentum are conserved); the same with static ground under the lower two
    // (up to eight points); and the top box alone across two static platforms
    // (four points on two freedoms, vy and omega: A is singular, the redundant
    // points share). Every gap is exactly 0 (dyadic coordinates, angle 0).
    std::mt19937_64 rng(20240611);
    int resolved = 0;
    int many_points = 0;
    for (int trial = 0; trial < 200; ++trial) {
        INFO("trial " << trial);
        const int kind = trial % 3; // 0 free, 1 on the ground, 2 on static platforms
        const double e = uniform(rng, 0.0, 1.0);
        const double top_x = std::floor(uniform(rng, -8.0, 8.0)) / 16.0;
        const auto random_body = [&](const Shape& shape, Vec2 position) {
            return dynamic_body(shape, log_uniform(rng, 0.1, 10.0), position, 0.0,
                                {uniform(rng, -2.0, 2.0), uniform(rng, -2.0, 2.0)},
                                uniform(rng, -2.0, 2.0));
        };
        std::vector<Body> bodies;
        bodies.push_back(random_body(make_box(1.25, 0.25), {top_x, 0.75}));
        if (kind == 2) {
            bodies.push_back(static_body(make_box(0.75, 0.5), {-1.0, 0.0}));
            bodies.push_back(static_body(make_box(0.75, 0.5), {1.0, 0.0}));
        } else {
            bodies.push_back(random_body(make_box(0.75, 0.5), {-1.0, 0.0}));
            bodies.push_back(random_body(make_box(0.75, 0.5), {1.0, 0.0}));
        }
        if (kind == 1) {
            bodies.push_back(static_body(make_box(50.0, 0.5), {0.0, -1.0}));
        }
        World world = make_world(bodies, {0.0, 0.0}, e, simultaneous_verlet());
        const Vec2 p_before = momentum(world);
        const double l_before = angular_momentum(world);
        const double energy_before = kinetic_energy(world);
        const double scale = momentum_scale(world);

        std::vector<CollisionEvent> events;
        const SimultaneousResult r = resolve_simultaneous_contacts(world, 0.0, events);
        REQUIRE(r.outcome != SimultaneousOutcome::unsolved);
        if (r.outcome == SimultaneousOutcome::none_approaching) {
            REQUIRE(events.empty());
            continue;
        }
        ++resolved;
        many_points += events.size() > 2 ? 1 : 0;
        double impulses = 0.0;
        for (const CollisionEvent& ev : events) {
            CHECK(ev.impulse > 0.0);
            impulses += ev.impulse;
            // Newton's law at every point that took an impulse (Eq. 3).
            CHECK(std::fabs(ev.vn_after + e * ev.vn_before) <= 1e-9 * (1.0 + scale));
        }
        CHECK(kinetic_energy(world) <= energy_before * (1.0 + 1e-12));
        if (kind == 0) {
            // Each impulse enters as +j n on one body and -j n on the other;
            // what remains is the rounding of m (j n / m) against j n.
            const Vec2 p_after = momentum(world);
            CHECK(std::fabs(p_after.x - p_before.x) <= 1e-12 * (scale + impulses));
            CHECK(std::fabs(p_after.y - p_before.y) <= 1e-12 * (scale + impulses));
            CHECK(std::fabs(angular_momentum(world) - l_before) <=
                  1e-12 * (scale + impulses) * 4.0);
        }
    }
    CHECK(resolved >= 100);
    CHECK(many_points >= 50);
}

TEST_CASE("The LCP solver on small hand-made problems", "[unit][simultaneous]") {
    SECTION("diagonal A: each point on its own") {
        // lambda_i = max(0, -q_i / A_ii): (2/2, 0, 3/1); w = (0, 4, 0).
        const LcpSolution s = solve_lcp(row_major({{2, 0, 0}, {0, 4, 0}, {0, 0, 1}}), {-2, 4, -3});
        REQUIRE(s.solved);
        CHECK(s.lambda == std::vector<double>{1.0, 0.0, 3.0});
        CHECK(s.w == std::vector<double>{0.0, 4.0, 0.0});
        CHECK(s.pivots == 0);
    }
    SECTION("a P-matrix where a point starts active and drops out") {
        // Both q < 0, but [[2, 1], [1, 2]] lambda = (4, 1) gives (7/3, -2/3):
        // point 1 would pull. Alone, point 0 takes 4/2 = 2, and w_1 = 2 - 1 = 1 > 0.
        const LcpSolution s = solve_lcp(row_major({{2, 1}, {1, 2}}), {-4, -1});
        REQUIRE(s.solved);
        CHECK(s.lambda == std::vector<double>{2.0, 0.0});
        CHECK(s.w[0] == 0.0);
        CHECK(s.w[1] == 1.0);
        CHECK(s.pivots == 1);
    }
    SECTION("a P-matrix where a touching point must join (the 3-ball cradle)") {
        // [[2, -1], [-1, 2]], q = (-2, 0): point 0 alone (lambda 1) would make
        // w_1 = -1; both: lambda = (4/3, 2/3).
        const LcpSolution s = solve_lcp(row_major({{2, -1}, {-1, 2}}), {-2, 0});
        REQUIRE(s.solved);
        CHECK(s.lambda[0] == Approx(4.0 / 3.0).epsilon(1e-15));
        CHECK(s.lambda[1] == Approx(2.0 / 3.0).epsilon(1e-15));
        CHECK(std::fabs(s.w[0]) <= 1e-15);
        CHECK(std::fabs(s.w[1]) <= 1e-15);
        CHECK(s.pivots == 1);
    }
    SECTION("singular A, consistent: redundant points share (minimum norm)") {
        // Two copies of one point: lambda_0 + lambda_1 = 1, minimum norm (1/2, 1/2).
        const LcpSolution s = solve_lcp(row_major({{1, 1}, {1, 1}}), {-1, -1});
        REQUIRE(s.solved);
        CHECK(s.lambda[0] == Approx(0.5).epsilon(1e-15));
        CHECK(s.lambda[1] == Approx(0.5).epsilon(1e-15));
        CHECK(std::fabs(s.w[0]) <= 1e-15);
        CHECK(std::fabs(s.w[1]) <= 1e-15);
    }
    SECTION("singular A, inconsistent for the starting set: the fallback finds the answer") {
        // Both copies want lambda_0 + lambda_1 to be 2 and 1 at once, which no
        // lambda gives; the solution is lambda = (2, 0), w = (0, 1) (lambda_1 > 0
        // would need lambda_0 + lambda_1 = 1 < 2).
        const LcpSolution s = solve_lcp(row_major({{1, 1}, {1, 1}}), {-2, -1});
        REQUIRE(s.solved);
        CHECK(s.enumerated > 0);
        CHECK(s.lambda[0] == Approx(2.0).epsilon(1e-15));
        CHECK(s.lambda[1] == 0.0);
        CHECK(s.w[1] == Approx(1.0).epsilon(1e-15));
    }
    SECTION("three redundant points and an independent one") {
        // Points 0-2 are one point three times (A block of ones), point 3 is
        // independent: lambda_0..2 share 3 equally, lambda_3 = 2 / 2.
        const LcpSolution s = solve_lcp(
            row_major({{1, 1, 1, 0}, {1, 1, 1, 0}, {1, 1, 1, 0}, {0, 0, 0, 2}}), {-3, -3, -3, -2});
        REQUIRE(s.solved);
        for (int i = 0; i < 3; ++i) {
            CHECK(s.lambda[static_cast<std::size_t>(i)] == Approx(1.0).epsilon(1e-14));
        }
        CHECK(s.lambda[3] == Approx(1.0).epsilon(1e-15));
    }
    SECTION("no solution: two points that push each other's way") {
        // [[1, -1], [-1, 1]]: w_0 = lambda_0 - lambda_1 - 1 and w_1 = lambda_1 -
        // lambda_0 - 1 cannot both be >= 0.
        const LcpSolution s = solve_lcp(row_major({{1, -1}, {-1, 1}}), {-1, -1});
        CHECK_FALSE(s.solved);
    }
    SECTION("nothing approaches: lambda = 0") {
        const LcpSolution s = solve_lcp(row_major({{2, 1}, {1, 2}}), {0, 3});
        REQUIRE(s.solved);
        CHECK(s.lambda == std::vector<double>{0.0, 0.0});
        CHECK(s.w == std::vector<double>{0.0, 3.0});
    }
}
