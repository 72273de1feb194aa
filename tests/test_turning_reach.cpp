// Time-stepping's candidate pairs and a body that turns far within a step
// (docs/engine.md, "Dense contact", step 1): a point turning by an angle
// moves along a chord, never more than the body's diameter, and a body lies
// within the disc of its rotation radius about its centre at every instant,
// so a fast spinner takes no contact from a body it cannot reach.
#include "contact_candidates.h"
#include "support.h"
#include "world.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::static_body;
using impulse::test::time_stepping;

TEST_CASE("turning moves a point along a chord: at most R |angle| and at most 2 R",
          "[unit][time-stepping]") {
    const Shape box = make_box(0.3, 0.4); // rotation radius 0.5
    CHECK(turning_reach(box, 0.1) == Approx(0.05).epsilon(1e-15));
    CHECK(turning_reach(box, -0.1) == Approx(0.05).epsilon(1e-15));
    CHECK(turning_reach(box, 50.0) == Approx(1.0).epsilon(1e-15));
    CHECK(turning_reach(box, -3000.0 / 60.0) == Approx(1.0).epsilon(1e-15));
    CHECK(turning_reach(make_circle(0.5), 50.0) == 0.0); // a circle turns into itself
}

// A rod of half-length L = 0.5 m spins in place (no gravity, verlet, dt = 1/60
// s) beside a wall whose face is 0.6 m from its centre: no point of the rod
// can ever reach it, at any speed. Its linear contact rows see the tip close
// at up to L omega: at 100 rad/s up to 0.83 m within one step, and the rod
// took an impact in its second step and flew off at 29 m/s. Free flight is exact: the
// angle advances by omega h each step, the centre and the spin do not change.
// With the face at 0.49 m the rod does reach the wall, and is struck.
TEST_CASE("a rod spinning in place takes no impact from a wall it cannot reach",
          "[unit][time-stepping]") {
    const double h = 1.0 / 60.0;
    const double half_length = 0.5;
    const auto run = [&](double omega, double face) {
        std::vector<Body> bodies{
            static_body(make_box(0.05, 2.0), {face + 0.05, 0.0}),
            dynamic_body(make_box(half_length, 0.005), 0.1, {0.0, 0.0}, 0.785)};
        bodies[1].state.angular_velocity = omega;
        World world = make_world(bodies, {0.0, 0.0}, 1.0, time_stepping());
        std::vector<CollisionEvent> events;
        for (int k = 0; k < 60; ++k) {
            REQUIRE_FALSE(step(world, k * h, h, events));
        }
        return std::make_pair(world, events.size());
    };
    for (const double omega : {40.0, 100.0, 3000.0, -100.0}) {
        INFO("omega " << omega);
        const auto [world, impacts] = run(omega, 0.6);
        const BodyState& rod = world.bodies[1].state;
        CHECK(impacts == 0);
        CHECK(rod.angular_velocity == omega);
        CHECK(rod.position.x == 0.0);
        CHECK(rod.position.y == 0.0);
        CHECK(rod.angle == Approx(0.785 + omega * 60 * h).epsilon(1e-12));
    }
    for (const double omega : {40.0, 100.0}) {
        INFO("omega " << omega);
        CHECK(run(omega, 0.49).second > 0);
    }
}
