// ccd under time-stepping (docs/engine.md, "Tunnelling"): a time step holds
// the contact points its start sees, linear in the velocities, so a thin rod
// spinning thousands of rad/s can turn through a thin wall no point held.
// Without ccd it passes silently; with ccd the step's motion is swept and the
// crossing refused; at a dt fine enough for the points to hold it, it
// rebounds.
#include "support.h"

#include <catch2/catch.hpp>
#include <vector>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::static_body;

namespace {

// A static wall 4 mm thick and 2 m tall at x = 0; a rod 0.6 x 0.01 m at
// x = -1 flying at 120 m/s toward it while it spins at 3000 rad/s, zero
// gravity, e = 1, time-stepping.
World rod_and_wall(bool ccd) {
    SolverSettings s;
    s.integrator = Integrator::verlet;
    s.resting = true;
    s.resting_method = RestingMethod::time_stepping;
    s.ccd = ccd;
    return make_world({static_body(make_box(0.002, 1.0), {0.0, 0.0}),
                       dynamic_body(make_box(0.3, 0.005), 1.0, {-1.0, -0.3415770166939983},
                                    0.26319673242323416, {120.0, 0.0}, 3000.0)},
                      {0.0, 0.0}, 1.0, s);
}

// Steps to t = 0.025 s (the rod reaches the wall after about 0.008 s),
// returning the first error.
std::optional<StepError> run(World& world, double h) {
    std::vector<CollisionEvent> events;
    const int steps = static_cast<int>(0.025 / h + 0.5);
    for (int k = 0; k < steps; ++k) {
        if (std::optional<StepError> error = step(world, k * h, h, events)) {
            return error;
        }
    }
    return std::nullopt;
}

} // namespace

TEST_CASE("ccd under time-stepping refuses a rod spinning through a thin wall", "[unit][ccd]") {
    const double h = 1.0 / 240.0; // 12.5 rad and 0.5 m per step
    World unswept = rod_and_wall(false);
    REQUIRE_FALSE(run(unswept, h));
    CHECK(unswept.bodies[1].state.position.x > 1.0); // through the wall, unseen

    World swept = rod_and_wall(true);
    const double before = swept.bodies[1].state.position.x;
    const std::optional<StepError> error = run(swept, h);
    REQUIRE(error);
    CHECK(error->failure == StepFailure::swept_crossing);
    CHECK(
        ((error->body_a == 1 && error->body_b == 0) || (error->body_a == 0 && error->body_b == 1)));
    // Within the step in which the rod's near end, 0.3 m ahead of its centre
    // at most, can reach the wall's near face (x = -0.002), and left at that
    // step's start.
    CHECK(error->time >= (1.0 - 0.3 - 0.002) / 120.0 - h);
    CHECK(error->time <= (1.0 + 0.3 + 0.002) / 120.0);
    CHECK(swept.bodies[1].state.position.x < -0.002);
    CHECK(swept.bodies[1].state.position.x >= before);
}

TEST_CASE("ccd under time-stepping lets a fine enough step hold the rod", "[unit][ccd]") {
    // At dt = 1/4000 s (0.75 rad, 3 cm per step) the contact points hold it:
    // it bounces back off the wall (e = 1), and the sweep finds nothing.
    World world = rod_and_wall(true);
    REQUIRE_FALSE(run(world, 1.0 / 4000.0));
    CHECK(world.bodies[1].state.position.x < -1.0);
    CHECK(world.bodies[1].state.velocity.x < 0.0);
}
