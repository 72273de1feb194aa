// Time-stepping's retaken step (docs/engine.md, "Dense contact", step 1): a
// body an impact sends past its reach makes the step be taken again only when
// its swept box may have met a point the step did not hold.
#include "support.h"
#include "support/random_piles.h"
#include "world.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::time_stepping;
using impulse::test::piles::deepest_overlap;

namespace {

constexpr double h = 1.0 / 60.0;

} // namespace

// A heavy disc at 6 m/s strikes a light one at rest (e = 1, no gravity): the
// light disc leaves at 2 M / (M + m) 6 m/s ~ 11.9 m/s, about 0.2 m within the
// step, where its reach (from v = 0) was d. With nothing in its way the step
// stands as solved; with a third disc 0.1 m ahead (no candidate pair at the
// step's start) it is taken again with the light disc's reach grown, and the
// pair is held: no overlap at the step's end, momentum M 6 kept.
TEST_CASE("an impact that outruns a reach retakes the step only if the body may meet another",
          "[unit][time-stepping]") {
    const double r = 0.1;
    const double v = 6.0;
    const double heavy = 100.0;
    const auto run_step = [&](bool obstacle) {
        std::vector<Body> bodies{dynamic_body(make_circle(r), heavy, {0.0, 0.0}),
                                 dynamic_body(make_circle(r), 1.0, {2.0 * r + 0.05, 0.0})};
        if (obstacle) {
            bodies.push_back(dynamic_body(make_circle(r), 1.0, {4.0 * r + 0.05 + 0.1, 0.0}));
        }
        bodies[0].state.velocity = {v, 0.0};
        World world = make_world(bodies, {0.0, 0.0}, 1.0, time_stepping());
        std::vector<CollisionEvent> events;
        REQUIRE_FALSE(step(world, 0.0, h, events));
        return world;
    };
    const World free = run_step(false);
    const double leaves = 2.0 * heavy / (heavy + 1.0) * v; // Eq. 9, e = 1, head on
    CHECK(free.bodies[1].state.velocity.x == Approx(leaves).epsilon(1e-12));
    CHECK(free.bodies[1].state.position.x - (2.0 * r + 0.05) > 0.19); // past its reach d
    CHECK(free.work.reach_retries == 0);

    const World blocked = run_step(true);
    CHECK(blocked.work.reach_retries >= 1);
    CHECK(deepest_overlap(blocked) <= blocked.solver.contact_tolerance);
    double momentum = 0.0;
    for (const Body& b : blocked.bodies) {
        momentum += b.state.velocity.x / b.inv_mass;
    }
    CHECK(momentum == Approx(heavy * v).epsilon(1e-12));
}

// Two light discs, each struck at the step's start by a heavy one at 30 m/s
// (e = 1, no gravity), fly at each other at 2 M / (M + m) 30 ~ 59.4 m/s: about
// 0.99 m each within the step, from 1.5 m apart, where neither box at the
// step's start reaches the other's swept box. Only the two outrunning bodies'
// swept boxes meet, so only that test (file_outran) can retake the step; held,
// the pair ends within the tolerance, and the heavy discs' momenta, equal and
// opposite, still sum to zero.
TEST_CASE("two bodies that both outrun their reach toward each other retake the step",
          "[unit][time-stepping]") {
    const double r = 0.1;
    const double v = 30.0;
    const double heavy = 100.0;
    const double b_x = 2.0 * r + 0.05;
    const double c_x = b_x + 2.0 * r + 1.5;
    std::vector<Body> bodies{dynamic_body(make_circle(r), heavy, {0.0, 0.0}),
                             dynamic_body(make_circle(r), 1.0, {b_x, 0.0}),
                             dynamic_body(make_circle(r), 1.0, {c_x, 0.0}),
                             dynamic_body(make_circle(r), heavy, {c_x + 2.0 * r + 0.05, 0.0})};
    bodies[0].state.velocity = {v, 0.0};
    bodies[3].state.velocity = {-v, 0.0};
    World world = make_world(bodies, {0.0, 0.0}, 1.0, time_stepping());
    std::vector<CollisionEvent> events;
    REQUIRE_FALSE(step(world, 0.0, h, events));
    CHECK(world.work.reach_retries >= 1);
    CHECK(deepest_overlap(world) <= world.solver.contact_tolerance);
    const double gap = world.bodies[2].state.position.x - world.bodies[1].state.position.x - 2 * r;
    CHECK(gap < 0.05); // they met: free, they would have passed into each other by 0.48 m
    double momentum = 0.0;
    for (const Body& b : world.bodies) {
        momentum += b.state.velocity.x / b.inv_mass;
    }
    CHECK(std::fabs(momentum) <= 1e-12 * heavy * v);
}
