// Tunnelling caught (solver.ccd; docs/engine.md, "Tunnelling"): with ccd the
// step samples every pair's motion by conservative advancement, so a body that
// crosses a thin one within a step is seen, at the exact time of the hit; a
// motion the seed sees already gives the same events; a spin too fast to
// sample ends in a clear error, never in a body passing through another.
#include "configuration.h"
#include "continuous_collision.h"
#include "integrator.h"
#include "manifold.h"
#include "narrow_phase_query.h"
#include "support.h"
#include "swept_run.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

using namespace impulse;
using impulse::test::close_relative;
using impulse::test::deepest;
using impulse::test::dynamic_body;
using impulse::test::run_checking_free_stretches;
using impulse::test::static_body;
using impulse::test::uniform;

namespace {

constexpr double dt = 1.0 / 30.0;

SolverSettings solver_with(bool ccd, TimeOfImpactMethod toi = TimeOfImpactMethod::secant,
                           Integrator integrator = Integrator::verlet) {
    SolverSettings s;
    s.ccd = ccd;
    s.toi = toi;
    s.integrator = integrator;
    return s;
}

// The case: a static wall 0.02 m thick (half extents [0.01, 1]) at the
// origin, body 0, and a bullet 10 m to its left flying at it at 1000 m/s,
// body 1, in zero gravity.
World bullet_world(const Shape& bullet, bool ccd, TimeOfImpactMethod toi, double e,
                   double angular_velocity = 0.0, bool rotates = true) {
    return make_world(
        {static_body(make_box(0.01, 1.0), {0, 0}),
         dynamic_body(bullet, 0.01, {-10, 0}, 0.0, {1000, 0}, angular_velocity, rotates)},
        {0, 0}, e, solver_with(ccd, toi));
}

// Where the search may put a collision of a pair closing at speed v: it
// converges at lo with a bracket at most toi_tolerance wide and the pair within
// contact_tolerance of touching, and lo is never past the first touch, so lo
// lies within min(toi_tolerance, contact_tolerance / v) before it. The sum of
// the two covers that and the rounding of the positions (an ulp of 10 m is
// 1.8e-15 m, or 1.8e-18 s at 1000 m/s).
double time_tolerance(const SolverSettings& s, double v) {
    return s.toi_tolerance + s.contact_tolerance / v;
}

const char* name_of(TimeOfImpactMethod toi) {
    return toi == TimeOfImpactMethod::secant ? "secant" : "bisection";
}

} // namespace

TEST_CASE("ccd catches the disc the seed lets through a thin wall, at the exact time",
          "[unit][ccd]") {
    const double r = 0.05;
    // The disc's front (x = -10 + r) meets the wall's face (x = -0.01) after
    // 9.94 m at 1000 m/s.
    const double t_hit = (10.0 - 0.01 - r) / 1000.0;
    for (TimeOfImpactMethod toi : {TimeOfImpactMethod::bisection, TimeOfImpactMethod::secant}) {
        for (double e : {1.0, 0.5}) {
            INFO(name_of(toi) << " e " << e);
            World world = bullet_world(make_circle(r), true, toi, e);
            const std::vector<CollisionEvent> events = test::run_steps(world, dt, 3);
            REQUIRE(events.size() == 1);
            const CollisionEvent& hit = events[0];
            CHECK(std::fabs(hit.time - t_hit) <= time_tolerance(world.solver, 1000.0));
            CHECK(hit.body_a == 1);
            CHECK(hit.body_b == 0);
            CHECK(hit.normal == Vec2{-1, 0}); // out of the wall, toward the bullet (a)
            CHECK(hit.vn_before == -1000.0);
            // Newton's law with a static wall: v' = -e v, j = (1 + e) m v.
            CHECK(close_relative(hit.vn_after, e * 1000.0, 1e-15));
            CHECK(close_relative(hit.impulse, (1.0 + e) * 0.01 * 1000.0, 1e-15));
            const BodyState& s = world.bodies[1].state;
            CHECK(close_relative(s.velocity.x, -e * 1000.0, 1e-15));
            CHECK(s.position.x < -0.01 - r); // back on the side it came from
        }
        // Without ccd the seed looks at the step's ends only, 33.3 m apart:
        // the disc is 9.94 m short of the wall at t = 0 and 23.3 m past it
        // after one step.
        World seed = bullet_world(make_circle(r), false, toi, 1.0);
        CHECK(test::run_steps(seed, dt, 3).empty());
        CHECK(seed.bodies[1].state.position.x > 0.01 + r);
        CHECK(seed.bodies[1].state.velocity.x == 1000.0);
    }
}

TEST_CASE("ccd catches a box bullet, still or slowly turning", "[unit][ccd]") {
    const double half = 0.05; // a 0.1 m square
    for (TimeOfImpactMethod toi : {TimeOfImpactMethod::bisection, TimeOfImpactMethod::secant}) {
        DYNAMIC_SECTION(name_of(toi) << ", without rotation: face to face, Eq. 6") {
            World world = bullet_world(make_box(half, half), true, toi, 1.0, 0.0, false);
            const std::vector<CollisionEvent> events = test::run_steps(world, dt, 3);
            REQUIRE(events.size() == 1);
            const double t_hit = (10.0 - 0.01 - half) / 1000.0;
            CHECK(std::fabs(events[0].time - t_hit) <= time_tolerance(world.solver, 1000.0));
            CHECK(close_relative(events[0].impulse, 2.0 * 0.01 * 1000.0, 1e-15));
            CHECK(world.bodies[1].state.velocity.x == -1000.0);
            CHECK(world.bodies[1].state.position.x < -0.01 - half);
            World seed = bullet_world(make_box(half, half), false, toi, 1.0, 0.0, false);
            CHECK(test::run_steps(seed, dt, 3).empty());
            CHECK(seed.bodies[1].state.position.x > 0.01 + half);
        }
        DYNAMIC_SECTION(name_of(toi) << ", turning at 1 rad/s: a corner hits first") {
            const double omega = 1.0;
            World world = bullet_world(make_box(half, half), true, toi, 1.0, omega);
            const double m = 0.01;
            const double inertia = m * (4 * half * half + 4 * half * half) / 12.0;
            const double energy = 0.5 * m * 1000.0 * 1000.0 + 0.5 * inertia * omega * omega;
            std::vector<CollisionEvent> events;
            for (int k = 0; k < 3; ++k) {
                REQUIRE_FALSE(step(world, k * dt, dt, events));
            }
            REQUIRE_FALSE(events.empty());
            // Turned by theta = omega t (small, positive), the square reaches
            // half (cos theta + sin theta) ahead of its centre (the corner at
            // (half, -half) in its own frame), so the corner meets the face when
            // 1000 t = 9.99 - half (cos omega t + sin omega t): a fixed point,
            // contracting by about half omega / 1000 per iteration.
            double t_hit = 0.0;
            for (int i = 0; i < 8; ++i) {
                t_hit =
                    (9.99 - half * (std::cos(omega * t_hit) + std::sin(omega * t_hit))) / 1000.0;
            }
            CHECK(std::fabs(events[0].time - t_hit) <= time_tolerance(world.solver, 1000.0));
            const BodyState& s = world.bodies[1].state;
            CHECK(s.velocity.x < 0.0);
            CHECK(s.position.x < -0.01 - half * std::sqrt(2.0));
            // e = 1 and a static wall: the kinetic energy comes back whole.
            const double after = 0.5 * m * length_squared(s.velocity) +
                                 0.5 * inertia * s.angular_velocity * s.angular_velocity;
            CHECK(close_relative(after, energy, 1e-12));
            World seed = bullet_world(make_box(half, half), false, toi, 1.0, omega);
            CHECK(test::run_steps(seed, dt, 3).empty());
            CHECK(seed.bodies[1].state.position.x > 0.01 + half * std::sqrt(2.0));
        }
    }
}

TEST_CASE("the sweep's samples: a bullet is found in one, a separating or resting pair costs "
          "at most two",
          "[unit][ccd]") {
    SECTION("the bullet: the first advance lands contact_tolerance deep") {
        World world = bullet_world(make_circle(0.05), true, TimeOfImpactMethod::secant, 1.0);
        const SweptContact swept = first_swept_contact(world, configuration_of(world), dt);
        REQUIRE(swept.converged);
        CHECK(swept.pair == 0);
        // From the gap s = 9.94 m at 1000 m/s, the sample (s + contact_tolerance)
        // / 1000 later is the first within the wall: two queries (t = 0 and it),
        // one advance (the wall never moves).
        CHECK(std::fabs(swept.time - (9.94 + 1e-9) / 1000.0) <= 1e-15);
        CHECK(world.work.narrow_phase_queries == 2);
        CHECK(world.work.body_advances == 1);
    }
    SECTION("touching and moving apart: straight to the end of the step") {
        // The disc just bounced: touching the wall's face, leaving at 1000 m/s.
        World world =
            make_world({static_body(make_box(0.01, 1.0), {0, 0}),
                        dynamic_body(make_circle(0.05), 0.01, {-0.06, 0}, 0.0, {-1000, 0})},
                       {0, 0}, 1.0, solver_with(true));
        const SweptContact swept = first_swept_contact(world, configuration_of(world), dt);
        REQUIRE(swept.converged);
        CHECK(swept.pair == -1);
        CHECK(swept.time == dt);
        CHECK(world.work.narrow_phase_queries == 2);
    }
    SECTION("touching and sliding along: straight to the end of the step") {
        // e = 0 took the normal velocity; the tangential 1000 m/s stays. Both
        // faces at x = -1/64 exactly (binary fractions), so s = 0 throughout.
        World world = make_world({static_body(make_box(1.0 / 64, 50.0), {0, 0}),
                                  dynamic_body(make_box(1.0 / 16, 1.0 / 16), 0.01, {-5.0 / 64, 0},
                                               0.0, {0, 1000}, 0.0, false)},
                                 {0, 0}, 0.0, solver_with(true));
        const Configuration start = configuration_of(world);
        REQUIRE(pair_separation(world, start, world.pairs[0]) == 0.0);
        world.work = {}; // count the sweep's queries alone
        const SweptContact swept = first_swept_contact(world, start, dt);
        REQUIRE(swept.converged);
        CHECK(swept.pair == -1);
        CHECK(world.work.narrow_phase_queries == 2);
    }
    for (Integrator integrator :
         {Integrator::euler, Integrator::symplectic_euler, Integrator::verlet, Integrator::rk4}) {
        DYNAMIC_SECTION("at rest on the ground under gravity, integrator "
                        << static_cast<int>(integrator) << ": found at the next sample") {
            World world = make_world({static_body(make_box(50, 0.5), {0, -0.5}),
                                      dynamic_body(make_box(0.5, 0.5), 1.0, {0, 0.5})},
                                     {0, -9.81}, 1.0,
                                     solver_with(true, TimeOfImpactMethod::secant, integrator));
            const SweptContact swept = first_swept_contact(world, configuration_of(world), dt);
            REQUIRE(swept.converged);
            if (integrator == Integrator::euler) {
                // The seed's Euler moves a body by its starting velocity, 0:
                // it does not fall within the step at all.
                CHECK(swept.pair == -1);
            } else {
                // The box sinks (c / 2) g u^2 by u (c = 2 for symplectic
                // Euler, 1 for verlet and rk4): the first sample is where that
                // is contact_tolerance, u = sqrt(2 d / (c g)), 1.4e-5 s for
                // verlet (to rounding: d is 1e-9 m against ulps of 1e-16 m).
                const double c = integrator == Integrator::symplectic_euler ? 2.0 : 1.0;
                CHECK(swept.pair == 0);
                CHECK(close_relative(swept.time,
                                     std::sqrt(2.0 * world.solver.contact_tolerance / (c * 9.81)),
                                     1e-6));
            }
            CHECK(world.work.narrow_phase_queries == 2);
        }
    }
}

TEST_CASE("a motion the seed already sees gives the same events with ccd", "[unit][ccd]") {
    // A disc dropped 2 m onto the ground, e = 1, for three impacts: at most
    // 6.3 m/s, 0.1 m per 1/60 s step against a 1 m thick ground.
    const test::Drop d{2.0, 9.81, 1.0};
    const double step = 1.0 / 60.0;
    const long long steps = static_cast<long long>(std::ceil(d.duration(3) / step));
    for (Integrator integrator :
         {Integrator::euler, Integrator::symplectic_euler, Integrator::verlet, Integrator::rk4}) {
        for (TimeOfImpactMethod toi : {TimeOfImpactMethod::bisection, TimeOfImpactMethod::secant}) {
            INFO("integrator " << static_cast<int>(integrator) << " " << name_of(toi));
            std::vector<CollisionEvent> runs[2];
            double toi_tolerance = 0.0;
            for (bool ccd : {false, true}) {
                World world = make_world({static_body(make_box(50, 0.5), {0, -0.5}),
                                          dynamic_body(make_circle(0.5), 1.0, {0, 2.5})},
                                         {0, -9.81}, d.e, solver_with(ccd, toi, integrator));
                runs[ccd] = test::run_steps(world, step, steps);
                toi_tolerance = world.solver.toi_tolerance;
            }
            REQUIRE(runs[0].size() == 3);
            REQUIRE(runs[1].size() == runs[0].size());
            // Only the searches' brackets differ (ccd ends them at the sample
            // found, the seed at the step's end). Each search stops at lo, some
            // eps in [0, toi_tolerance] before its motion first touches. A
            // bounce eps early (e = 1) starts the mirror image of the exact
            // flight, at the state the exact one reaches eps after its bounce:
            // every later touch comes 2 eps early. So impact n is
            // 2 (eps_1 + ... + eps_n-1) + eps_n early, in [0, (2n - 1)
            // toi_tolerance], in either run. (For verlet and rk4, exact here;
            // euler and symplectic Euler also split their steps at slightly
            // other times, which moves a body by about eps g dt, far less.)
            for (std::size_t k = 0; k < runs[0].size(); ++k) {
                INFO("impact " << k + 1 << " diff " << runs[1][k].time - runs[0][k].time);
                const double n = static_cast<double>(k + 1);
                CHECK(std::fabs(runs[1][k].time - runs[0][k].time) <=
                      (2.0 * n - 1.0) * toi_tolerance);
            }
        }
    }
}

namespace {

// A rod 2 m long and 0.02 m thick (half extents [1, 0.01]), body 1, centred
// 0.9 m from a wall's face (x = -0.01), body 0: turning, its end sweeps to
// 0.1 m past the face whenever it lies flat. At 300 rad/s it turns 10 rad per
// 1/30 s step, its end moving at 300 m/s.
World rod_world(bool ccd, int max_search_iterations = SolverSettings{}.max_search_iterations) {
    SolverSettings solver = solver_with(ccd);
    solver.max_search_iterations = max_search_iterations;
    return make_world(
        {static_body(make_box(0.01, 5.0), {0, 0}),
         dynamic_body(make_box(1.0, 0.01), 1.0, {-0.91, 0}, 1.5707963267948966, {}, 300.0)},
        {0, 0}, 1.0, solver);
}

} // namespace

TEST_CASE("a rod spinning 10 rad per step never passes into a wall unseen", "[unit][ccd]") {
    const int steps = 30;
    const int n = 4000; // instants per free stretch: 2.5 mrad of turn apart
    // Without ccd the seed sees only the step ends: its motion dips deep into
    // the wall between them (the check below is not vacuous).
    {
        World seed = rod_world(false);
        double lowest = 0.0;
        for (int k = 0; k < steps; ++k) {
            const Configuration start = configuration_of(seed);
            std::vector<CollisionEvent> events;
            if (step(seed, k * dt, dt, events) || !events.empty()) {
                break;
            }
            const double d = deepest(seed, start, dt, n);
            lowest = d < lowest ? d : lowest;
        }
        CHECK(lowest < -0.01);
    }
    World world = rod_world(true);
    const auto [events, error] = run_checking_free_stretches(world, dt, steps, n);
    if (error) {
        // The one way the sweep may give up, naming the rod and the wall.
        CHECK(error->failure == StepFailure::sweep_not_converged);
        CHECK(error->body_a == 1);
        CHECK(error->body_b == 0);
    } else {
        CHECK_FALSE(events.empty());
    }
}

namespace {

// A 0.14 x 0.06 m box spinning at 21.77 rad/s while it drifts along a wall's
// face (x = -0.9) at 3.26 m/s and toward it at only 0.479 m/s, zero gravity,
// e = 1: corners pass within millimetres of the face, and two of them hit it
// (an exact event-driven reference at 40 digits: at 0.0362628218289 s and
// 0.0440572257396 s, then none before 0.1 s). Each sample's fastest point
// moves at about 1.7 m/s against a corner's 0.06 m/s toward the face, so
// charging every point that speed needed more than 200 samples per step.
World grazing_world() {
    return make_world({static_body(make_box(0.25, 5.0), {-1.15, 0}),
                       dynamic_body(make_box(0.07, 0.03), 0.37, {-0.808921, -0.296334}, -24.19266,
                                    {-0.479, 3.2575}, -21.7704)},
                      {0, 0}, 1.0, solver_with(true));
}

// The first time a corner of the grazing box reaches the face, from its free
// motion in closed form (libm's sine and cosine, bisection to the last bit).
double first_corner_touch() {
    const Vec2 corners[4] = {{0.07, 0.03}, {-0.07, 0.03}, {-0.07, -0.03}, {0.07, -0.03}};
    const auto gap = [&](double t) {
        const double angle = -24.19266 - 21.7704 * t;
        double least = std::numeric_limits<double>::infinity();
        for (const Vec2 r : corners) {
            least = std::min(least, -0.808921 - 0.479 * t + std::cos(angle) * r.x -
                                        std::sin(angle) * r.y + 0.9);
        }
        return least;
    };
    return impulse::test::first_negative(gap, 0.1);
}

double kinetic_energy(const World& world) {
    const Body& box = world.bodies[1];
    return 0.5 * length_squared(box.state.velocity) / box.inv_mass +
           0.5 * box.state.angular_velocity * box.state.angular_velocity / box.inv_inertia;
}

} // namespace

TEST_CASE("a box spinning along a wall is swept point by point, at the exact touch",
          "[unit][ccd]") {
    const double exact = first_corner_touch();
    REQUIRE(std::fabs(exact - 0.0362628218289) < 1e-12); // the reference's
    for (const double h : {1.0 / 97.0, 1.0 / 1000.0}) {
        INFO("dt " << h);
        World world = grazing_world();
        const double energy = kinetic_energy(world);
        const int steps = static_cast<int>(std::ceil(0.1 / h));
        const auto [events, error] = run_checking_free_stretches(world, h, steps, 400);
        REQUIRE_FALSE(error);
        REQUIRE(events.size() == 2);
        CHECK(std::fabs(events[0].time - exact) <=
              time_tolerance(world.solver, std::fabs(events[0].vn_before)));
        CHECK(std::fabs(events[1].time - 0.0440572257396) < 1e-8);
        CHECK(std::fabs(kinetic_energy(world) - energy) <= 1e-12 * energy); // e = 1
    }
}

TEST_CASE("a sweep that needs more than max_search_iterations samples ends in sweep_not_converged",
          "[unit][ccd]") {
    // The rod's end closes on the wall at 300 |sin theta| m/s against a bound
    // of 300 m/s, so each sample takes it only part of the way: more than 4.
    World world = rod_world(true, 4);
    const SweptContact swept = first_swept_contact(world, configuration_of(world), dt);
    CHECK_FALSE(swept.converged);
    CHECK(swept.stalled_pair == 0);
    CHECK(world.work.narrow_phase_queries == 4);
    std::vector<CollisionEvent> events;
    const std::optional<StepError> error = step(world, 0.0, dt, events);
    REQUIRE(error);
    CHECK(error->failure == StepFailure::sweep_not_converged);
    CHECK(error->body_a == 1);
    CHECK(error->body_b == 0);
    CHECK(error->time == 0.0);
    CHECK(events.empty());
}

TEST_CASE("the sample found is the search's trial to the bit", "[unit][ccd]") {
    for (int which = 0; which < 2; ++which) {
        World world = which == 0
                          ? bullet_world(make_circle(0.05), true, TimeOfImpactMethod::secant, 1.0)
                          : rod_world(true);
        const Configuration start = configuration_of(world);
        const SweptContact swept = first_swept_contact(world, start, dt);
        REQUIRE(swept.converged);
        REQUIRE(swept.pair == 0);
        Configuration trial;
        advance_all(world, start, swept.time, trial);
        CHECK(first_interpenetrating_pair(world, trial) == swept.pair);
        // Interpenetrating by at most the contact tolerance (and rounding).
        CHECK(pair_separation(world, trial, world.pairs[0]) >=
              -world.solver.contact_tolerance * (1.0 + 1e-6));
    }
}

TEST_CASE("random bullets never tunnel and hit at the straight-line time", "[unit][ccd]") {
    std::mt19937_64 rng(20240611);
    int tunnelled_without_ccd = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const double speed = test::log_uniform(rng, 10.0, 1000.0);
        const double thickness = uniform(rng, 0.005, 0.1);
        const double r = uniform(rng, 0.005, 0.05);
        // The direction (1, k) / |(1, k)|: up to 79 degrees off the wall's
        // normal, without libm trig (the trials are the same everywhere).
        const double k = uniform(rng, -5.0, 5.0);
        const double norm = std::sqrt(1.0 + k * k);
        const Vec2 v{speed / norm, speed * k / norm};
        // The disc's front reaches the face x = -thickness / 2 after t_hit, on
        // a straight line, at a height within 0.5 m of the middle of a wall
        // 2 m tall: its face, never its ends.
        const double t_hit = uniform(rng, 0.01, 0.5);
        const double face = -0.5 * thickness;
        const Vec2 from{face - r - v.x * t_hit, uniform(rng, -0.5, 0.5) - v.y * t_hit};
        const TimeOfImpactMethod toi =
            trial % 2 ? TimeOfImpactMethod::secant : TimeOfImpactMethod::bisection;
        const long long steps = static_cast<long long>(std::ceil(t_hit / dt)) + 2;
        INFO("trial " << trial << " speed " << speed << " thickness " << thickness << " r " << r
                      << " k " << k << " t_hit " << t_hit);
        for (bool ccd : {false, true}) {
            World world = make_world({static_body(make_box(0.5 * thickness, 1.0), {0, 0}),
                                      dynamic_body(make_circle(r), 0.01, from, 0.0, v)},
                                     {0, 0}, 1.0, solver_with(ccd, toi));
            const std::vector<CollisionEvent> events = test::run_steps(world, dt, steps);
            const BodyState& s = world.bodies[1].state;
            if (!ccd) {
                tunnelled_without_ccd += events.empty() && s.position.x > -face + r;
                continue;
            }
            REQUIRE(events.size() == 1);
            // The search's bound on a pair closing at v.x (the normal speed).
            CHECK(std::fabs(events[0].time - t_hit) <= time_tolerance(world.solver, v.x));
            CHECK(events[0].normal == Vec2{-1, 0});
            // e = 1, frictionless: the normal velocity turns over, the rest stays.
            CHECK(close_relative(s.velocity.x, -v.x, 1e-12));
            CHECK(s.velocity.y == v.y);
            CHECK(s.position.x < face - r);
        }
    }
    // A disc crosses unseen when a step carries it past the wall's far face
    // from before its near one: most of these, at 0.33 to 33 m per step
    // against walls and discs a few centimetres across.
    CHECK(tunnelled_without_ccd > 100);
}
