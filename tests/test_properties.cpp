// Conservation laws over many seeded random collisions (docs/physics.md, exact answers).
#include "restitution.h"
#include "support.h"
#include "trig.h"

#include <catch2/catch.hpp>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::log_uniform;
using impulse::test::uniform;

namespace {

struct Totals {
    Vec2 momentum;
    double angular_momentum = 0.0; // about the origin
    double energy = 0.0;
};

Totals totals(const World& world) {
    Totals t;
    for (const Body& body : world.bodies) {
        if (body.is_static()) {
            continue;
        }
        const double m = 1.0 / body.inv_mass;
        const BodyState& s = body.state;
        t.momentum += m * s.velocity;
        t.angular_momentum += m * cross(s.position, s.velocity);
        t.energy += 0.5 * m * length_squared(s.velocity);
        if (body.rotates()) {
            const double inertia = 1.0 / body.inv_inertia;
            t.angular_momentum += inertia * s.angular_velocity;
            t.energy += 0.5 * inertia * s.angular_velocity * s.angular_velocity;
        }
    }
    return t;
}

Shape random_shape(std::mt19937_64& rng) {
    if (rng() % 2 == 0) {
        return make_circle(uniform(rng, 0.1, 1.0));
    }
    return make_box(uniform(rng, 0.1, 1.0), uniform(rng, 0.1, 1.0));
}

} // namespace

TEST_CASE("Free collisions conserve momentum; energy only at e = 1, never gained", "[properties]") {
    std::mt19937_64 rng(31415);
    int collided = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const double e = trial % 4 == 0 ? 1.0 : uniform(rng, 0.0, 1.0);
        // Two bodies aimed roughly at each other, off-centre, spinning, masses 1e-2..1e2.
        const double ma = log_uniform(rng, 1e-2, 1e2), mb = log_uniform(rng, 1e-2, 1e2);
        const Vec2 pa{-3.0, uniform(rng, -0.8, 0.8)}, pb{3.0, uniform(rng, -0.8, 0.8)};
        World world = make_world(
            {dynamic_body(random_shape(rng), ma, pa, uniform(rng, -3, 3),
                          {uniform(rng, 1, 10), uniform(rng, -0.5, 0.5)}, uniform(rng, -2, 2)),
             dynamic_body(random_shape(rng), mb, pb, uniform(rng, -3, 3),
                          {-uniform(rng, 1, 10), uniform(rng, -0.5, 0.5)}, uniform(rng, -2, 2))},
            {0, 0}, e, SolverSettings{});
        const Totals before = totals(world);
        const std::vector<CollisionEvent> events = test::run_steps(world, 1.0 / 60.0, 120);
        if (events.empty()) {
            continue;
        }
        ++collided;
        const Totals after = totals(world);
        const double p_scale = ma * length(world.bodies[0].state.velocity) +
                               mb * length(world.bodies[1].state.velocity) +
                               length(before.momentum);
        INFO("trial " << trial << " e " << e << " events " << events.size());
        CHECK(length(after.momentum - before.momentum) <= 1e-12 * p_scale);
        CHECK(std::fabs(after.angular_momentum - before.angular_momentum) <=
              1e-12 * (std::fabs(before.angular_momentum) + 10.0 * p_scale));
        CHECK(after.energy <= before.energy * (1.0 + 1e-12));
        if (e == 1.0) {
            CHECK(after.energy == Approx(before.energy).epsilon(1e-12));
        }
        // Eq. 3 holds to rounding of the velocities involved (up to ~10 m/s here),
        // also for the tiny re-contacts of a slow inelastic pair.
        const double v_scale = 20.0;
        for (const CollisionEvent& ev : events) {
            CHECK(ev.vn_before < 0.0);
            CHECK(ev.vn_after == Approx(-e * ev.vn_before).epsilon(1e-12).margin(1e-13 * v_scale));
            CHECK(ev.impulse >= 0.0);
        }
    }
    CHECK(collided > 200);
}

TEST_CASE("Single impulses: Eq. 3 holds and momentum is exact for random contacts",
          "[properties]") {
    std::mt19937_64 rng(2718);
    for (int trial = 0; trial < 1000; ++trial) {
        const double e = uniform(rng, 0.0, 1.0);
        Body a =
            dynamic_body(make_box(uniform(rng, 0.1, 2), uniform(rng, 0.1, 2)),
                         log_uniform(rng, 1e-3, 1e3), {uniform(rng, -1, 1), 1}, uniform(rng, -3, 3),
                         {uniform(rng, -5, 5), uniform(rng, -5, 5)}, uniform(rng, -5, 5));
        Body b = dynamic_body(make_circle(uniform(rng, 0.1, 2)), log_uniform(rng, 1e-3, 1e3),
                              {uniform(rng, -1, 1), -1}, 0.0,
                              {uniform(rng, -5, 5), uniform(rng, -5, 5)}, uniform(rng, -5, 5));
        const double theta = uniform(rng, -0.7, 0.7);
        const Vec2 n{sine(theta), cosine(theta)};
        const Vec2 P{uniform(rng, -1, 1), uniform(rng, -0.2, 0.2)};
        const double vn = relative_normal_velocity(a, b, P, n);
        if (vn >= 0.0) {
            continue;
        }
        const Vec2 p0 =
            (1.0 / a.inv_mass) * a.state.velocity + (1.0 / b.inv_mass) * b.state.velocity;
        const Impulse impulse = resolve_collision(a, b, {P, n, 0.0}, e);
        const Vec2 p1 =
            (1.0 / a.inv_mass) * a.state.velocity + (1.0 / b.inv_mass) * b.state.velocity;
        const double scale = length((1.0 / a.inv_mass) * a.state.velocity) +
                             length((1.0 / b.inv_mass) * b.state.velocity) + length(p0);
        CHECK(length(p1 - p0) <= 1e-12 * scale);
        CHECK(impulse.vn_after == Approx(-e * vn).epsilon(1e-10).margin(1e-12 * std::fabs(vn)));
    }
}
