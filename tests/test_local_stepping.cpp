// Local stepping (docs/engine.md, "Local stepping"): the seed's rules pair by
// pair, each body on its own clock. It must give the seed's bits where there
// is one pair to collide, the exact answers in a crowd, conservation in a gas,
// and work per collision that does not grow with the number of bodies.
#include "run.h"
#include "scene.h"
#include "support.h"
#include "trajectory.h"
#include "world.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <random>
#include <string>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::run_steps;
using impulse::test::static_body;
using impulse::test::uniform;

namespace {

SolverSettings local_solver(TimeOfImpactMethod toi = TimeOfImpactMethod::bisection) {
    SolverSettings solver;
    solver.integrator = Integrator::symplectic_euler;
    solver.toi = toi;
    solver.stepping = Stepping::local;
    return solver;
}

int pair_count(const harness::Scene& scene) {
    int pairs = 0;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        for (std::size_t k = i + 1; k < scene.bodies.size(); ++k) {
            pairs += scene.bodies[i].is_static && scene.bodies[k].is_static ? 0 : 1;
        }
    }
    return pairs;
}

// A row of idle balls far from everything, moving in step so they never meet.
void add_idle_crowd(std::vector<Body>& bodies, int count) {
    for (int i = 0; i < count; ++i) {
        bodies.push_back(dynamic_body(make_circle(0.1), 1.0,
                                      {100.0 + 0.5 * (i % 50), 100.0 + 0.5 * (i / 50)}, 0.0,
                                      {1.0, 0.5}));
    }
}

} // namespace

TEST_CASE("local stepping gives the seed's bits in every canonical scene with one pair",
          "[unit][local]") {
    const std::string dir = std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes/";
    int compared = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".json") {
            continue;
        }
        harness::Scene scene = harness::load_scene(entry.path().string());
        // Local stepping is the seed's loop pair by pair; the models past the
        // seed that look at the whole world (ccd, resting, simultaneous
        // contact) are refused with it.
        if (pair_count(scene) != 1 || scene.solver.stepping != Stepping::world ||
            scene.solver.ccd || scene.solver.resting ||
            scene.solver.contacts != ContactMode::single) {
            continue;
        }
        for (const TimeOfImpactMethod toi :
             {TimeOfImpactMethod::bisection, TimeOfImpactMethod::secant}) {
            scene.solver.toi = toi;
            scene.solver.stepping = Stepping::world;
            const harness::Trajectory world = harness::run_scene(scene);
            scene.solver.stepping = Stepping::local;
            const harness::Trajectory local = harness::run_scene(scene);
            INFO(scene.name << " with toi " << harness::toi_method_name(toi));
            CHECK(local.frames.size() == world.frames.size());
            CHECK(local.events.size() == world.events.size());
            CHECK(harness::digest_hex(harness::digest_of(local)) ==
                  harness::digest_hex(harness::digest_of(world)));
            ++compared;
        }
    }
    CHECK(compared >= 20); // most canonical scenes are one body on the ground
}

TEST_CASE("a head-on collision in a crowd happens at the exact time with the exact exchange",
          "[unit][local]") {
    // Equal balls, radius r, centres d apart, closing at 2v, e = 1: they touch
    // at t = (d - 2r) / (2v) and swap velocities (docs/physics.md, head-on).
    for (const TimeOfImpactMethod toi :
         {TimeOfImpactMethod::bisection, TimeOfImpactMethod::secant}) {
        const double r = 0.25;
        const double d = 3.0;
        const double v = 2.0;
        std::vector<Body> bodies;
        bodies.push_back(dynamic_body(make_circle(r), 2.0, {-0.5 * d, 0.0}, 0.0, {v, 0.0}));
        bodies.push_back(dynamic_body(make_circle(r), 2.0, {0.5 * d, 0.0}, 0.0, {-v, 0.0}));
        // A second pair far away, colliding later in the same step.
        bodies.push_back(dynamic_body(make_circle(r), 1.0, {-0.5 * d, 40.0}, 0.0, {v, 0.0}));
        bodies.push_back(dynamic_body(make_circle(r), 1.0, {0.5 * d + 0.01, 40.0}, 0.0, {-v, 0.0}));
        add_idle_crowd(bodies, 400);
        World world = make_world(std::move(bodies), {0.0, 0.0}, 1.0, local_solver(toi));
        const double dt = 1.0 / 30.0;
        const std::vector<CollisionEvent> events = run_steps(world, dt, 30);
        REQUIRE(events.size() == 2);
        CHECK(events[0].body_a == 0);
        CHECK(events[0].time == Approx((d - 2 * r) / (2 * v)).epsilon(1e-11));
        CHECK(events[1].body_a == 2);
        CHECK(events[1].time == Approx((d + 0.01 - 2 * r) / (2 * v)).epsilon(1e-11));
        CHECK(world.bodies[0].state.velocity.x == Approx(-v).epsilon(1e-12));
        CHECK(world.bodies[1].state.velocity.x == Approx(v).epsilon(1e-12));
        CHECK(world.bodies[2].state.velocity.x == Approx(-v).epsilon(1e-12));
        CHECK(world.bodies[3].state.velocity.x == Approx(v).epsilon(1e-12));
        CHECK(world.bodies[0].state.velocity.y == 0.0);
    }
}

TEST_CASE("the work of a collision does not grow with the bodies not in it", "[unit][local]") {
    // One pair collides while `idle` bodies fly elsewhere. Local stepping
    // integrates each idle body once per step, whatever happens; the seed's
    // loop integrates every body again for every trial of every search.
    const auto run = [](int idle, Stepping stepping) {
        std::vector<Body> bodies;
        bodies.push_back(dynamic_body(make_box(0.2, 0.1), 1.0, {-1.0, 0.0}, 0.3, {3.0, 0.0}, 1.0));
        bodies.push_back(dynamic_body(make_circle(0.2), 3.0, {1.0, 0.05}, 0.0, {-1.0, 0.0}));
        add_idle_crowd(bodies, idle);
        SolverSettings solver = local_solver();
        solver.stepping = stepping;
        World world = make_world(std::move(bodies), {0.0, -9.81}, 1.0, solver);
        run_steps(world, 1.0 / 60.0, 60);
        REQUIRE(world.work.collisions >= 1);
        return world.work;
    };
    const WorkCounters alone = run(0, Stepping::local);
    const WorkCounters crowded = run(500, Stepping::local);
    const long long steps = alone.steps;
    CHECK(crowded.collisions == alone.collisions);
    CHECK(crowded.toi_iterations == alone.toi_iterations);
    // Beyond one advance per idle body per step, not one advance more.
    CHECK(crowded.body_advances - alone.body_advances == 500 * steps);

    const WorkCounters seed_alone = run(0, Stepping::world);
    const WorkCounters seed_crowded = run(500, Stepping::world);
    CHECK(seed_crowded.body_advances - seed_alone.body_advances >
          500 * (steps + seed_alone.toi_iterations));
}

TEST_CASE("a gas in open space conserves momentum, angular momentum and energy", "[unit][local]") {
    // Circles and boxes with random velocities and spins, e = 1, no gravity,
    // no walls: every collision conserves all three (Eq. 9), so the totals do.
    std::mt19937_64 rng(7);
    std::vector<Body> bodies;
    for (int j = 0; j < 15; ++j) {
        for (int i = 0; i < 15; ++i) {
            const Vec2 p{0.5 * i, 0.5 * j};
            const Vec2 v{uniform(rng, -3, 3), uniform(rng, -3, 3)};
            const double mass = uniform(rng, 0.5, 2.0);
            bodies.push_back((i + j) % 2 == 0
                                 ? dynamic_body(make_circle(0.1), mass, p, 0.0, v)
                                 : dynamic_body(make_box(0.12, 0.08), mass, p, uniform(rng, -3, 3),
                                                v, uniform(rng, -5, 5)));
        }
    }
    const auto totals = [](const World& world) {
        double px = 0, py = 0, l = 0, e = 0, px_scale = 0, l_scale = 0;
        for (const Body& b : world.bodies) {
            const double m = 1.0 / b.inv_mass;
            const double inertia = b.rotates() ? 1.0 / b.inv_inertia : 0.0;
            const BodyState& s = b.state;
            px += m * s.velocity.x;
            py += m * s.velocity.y;
            px_scale += m * length(s.velocity);
            const double spin = inertia * s.angular_velocity;
            l += m * cross(s.position, s.velocity) + spin;
            l_scale += std::abs(m * cross(s.position, s.velocity)) + std::abs(spin);
            e += 0.5 * m * length_squared(s.velocity) +
                 0.5 * inertia * s.angular_velocity * s.angular_velocity;
        }
        return std::array<double, 6>{px, py, l, e, px_scale, l_scale};
    };
    World world =
        make_world(std::move(bodies), {0.0, 0.0}, 1.0, local_solver(TimeOfImpactMethod::secant));
    const auto before = totals(world);
    run_steps(world, 1.0 / 60.0, 120);
    const auto after = totals(world);
    CHECK(world.work.collisions > 100);
    CHECK(std::abs(after[0] - before[0]) <= 1e-12 * before[4]);
    CHECK(std::abs(after[1] - before[1]) <= 1e-12 * before[4]);
    CHECK(std::abs(after[2] - before[2]) <= 1e-12 * after[5]);
    CHECK(std::abs(after[3] - before[3]) <= 1e-12 * before[3]);
}

TEST_CASE("local stepping refuses a Zeno cascade as the seed's loop does", "[unit][local]") {
    // A box dropped with e = 0.5 bounces ever lower until the seed model
    // stalls; both loops must stop with the same failure at the same time.
    const auto run = [](Stepping stepping) {
        SolverSettings solver = local_solver();
        solver.stepping = stepping;
        std::vector<Body> bodies{static_body(make_box(5.0, 0.5), {0.0, -0.5}),
                                 dynamic_body(make_box(0.5, 0.5), 1.0, {0.0, 1.5})};
        World world = make_world(std::move(bodies), {0.0, -9.81}, 0.5, solver);
        std::vector<CollisionEvent> events;
        for (int k = 0; k < 600; ++k) {
            if (const std::optional<StepError> error = step(world, k / 60.0, 1.0 / 60.0, events)) {
                return std::make_pair(*error, events.size());
            }
        }
        FAIL("no failure in 10 s");
        return std::make_pair(StepError{}, events.size());
    };
    const auto [seed_error, seed_events] = run(Stepping::world);
    const auto [local_error, local_events] = run(Stepping::local);
    CHECK(local_error.failure == seed_error.failure);
    CHECK(local_error.time == seed_error.time);
    CHECK(local_error.body_a == 1);
    CHECK(local_error.body_b == 0);
    CHECK(local_events == seed_events);
}
