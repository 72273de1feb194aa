// The time-of-impact searches (docs/engine.md, "The secant search"): the secant
// search gives the exact answers of docs/physics.md through the whole loop as the
// seed's bisection does, in fewer iterations, and fails the same way; the
// bisection's results are unchanged to the bit.
#include "support.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ios>
#include <optional>
#include <random>
#include <vector>

using namespace impulse;
using impulse::test::close_relative;
using impulse::test::dynamic_body;
using impulse::test::static_body;
using impulse::test::uniform;

namespace {

constexpr double rel = 1e-9;
constexpr double time_steps[] = {1.0 / 30.0, 1.0 / 60.0};

// Spans decades without libm (std::pow may differ across platforms, and the
// bisection's digest below is pinned): a uniform mantissa times a power of ten.
double decades(std::mt19937_64& rng, int lowest, int count) {
    double scale = 1.0;
    for (int k = lowest; k < 0; ++k) {
        scale /= 10.0;
    }
    for (int k = 0; k < lowest; ++k) {
        scale *= 10.0;
    }
    const int decade = static_cast<int>(rng() % static_cast<std::uint64_t>(count));
    for (int k = 0; k < decade; ++k) {
        scale *= 10.0;
    }
    return scale * uniform(rng, 1.0, 10.0);
}

SolverSettings solver_with(Integrator integrator, TimeOfImpactMethod toi) {
    SolverSettings s;
    s.integrator = integrator;
    s.toi = toi;
    return s;
}

// What a set of runs cost the search, and a digest of every bit they produced
// (FNV-1a over events and final states) to pin the bisection's results.
struct Tally {
    long long iterations = 0; // world.work.toi_iterations
    long long collisions = 0; // world.work.collisions
    std::uint64_t digest = 14695981039346656037ull;

    void hash_bits(std::uint64_t bits) {
        for (int byte = 0; byte < 8; ++byte) {
            digest = (digest ^ ((bits >> (8 * byte)) & 0xffu)) * 1099511628211ull;
        }
    }
    void hash(double x) {
        std::uint64_t bits = 0;
        std::memcpy(&bits, &x, sizeof bits);
        hash_bits(bits);
    }
    void add(const World& world, const std::vector<CollisionEvent>& events) {
        iterations += world.work.toi_iterations;
        collisions += world.work.collisions;
        for (const CollisionEvent& ev : events) {
            for (double x : {ev.time, static_cast<double>(ev.body_a),
                             static_cast<double>(ev.body_b), ev.point.x, ev.point.y, ev.normal.x,
                             ev.normal.y, ev.impulse, ev.vn_before, ev.vn_after}) {
                hash(x);
            }
        }
        for (const Body& body : world.bodies) {
            const BodyState& s = body.state;
            for (double x : {s.position.x, s.position.y, s.angle, s.velocity.x, s.velocity.y,
                             s.angular_velocity}) {
                hash(x);
            }
        }
    }
    void add(const Tally& other) {
        iterations += other.iterations;
        collisions += other.collisions;
        hash_bits(other.digest);
    }
    double per_collision() const {
        return static_cast<double>(iterations) / static_cast<double>(collisions);
    }
};

using impulse::test::Drop;

// Seeded random drops, verlet and rk4 (exact for constant acceleration) at
// 1/30 and 1/60 s, circles and non-rotating boxes: the first five impacts.
Tally drops(TimeOfImpactMethod toi) {
    std::mt19937_64 rng(271828);
    Tally tally;
    const int impacts = 5;
    for (int trial = 0; trial < 32; ++trial) {
        const double dt = time_steps[trial % 2];
        Drop d{};
        long long steps = 0;
        do { // the run must end before t_inf: past it the Zeno cascade stops the loop
            d = {uniform(rng, 0.1, 10.0), uniform(rng, 1.0, 20.0), uniform(rng, 0.3, 0.95)};
            steps = static_cast<long long>(std::ceil(d.duration(impacts) / dt));
        } while (static_cast<double>(steps) * dt >= d.t_inf());
        const Integrator integrator = (trial / 2) % 2 ? Integrator::verlet : Integrator::rk4;
        const Shape shape = (trial / 4) % 2 ? make_box(0.5, 0.5) : make_circle(0.5);
        World world = make_world({static_body(make_box(50, 0.5), {0, -0.5}),
                                  dynamic_body(shape, 1.0, {0, 0.5 + d.h0}, 0, {}, 0, false)},
                                 {0, -d.g}, d.e, solver_with(integrator, toi));
        const std::vector<CollisionEvent> events = test::run_steps(world, dt, steps);
        INFO("trial " << trial << " h0 " << d.h0 << " g " << d.g << " e " << d.e << " dt " << dt);
        REQUIRE(events.size() >= static_cast<std::size_t>(impacts));
        double en = 1.0;
        for (int n = 1; n <= impacts; ++n) {
            en *= d.e;
            INFO("impact " << n);
            CHECK(close_relative(events[n - 1].time, d.impact_time(n), rel));
            CHECK(close_relative(events[n - 1].vn_after, en * d.v1(), rel));
        }
        tally.add(world, events);
    }
    return tally;
}

// Seeded random single-corner impacts on static ground (docs/physics.md):
// j = (1 + e) v / (1/M + rx^2 / I), vy' = -v + j / M, w' = rx j / I, vx unchanged,
// with I = M (4a^2 + 4b^2) / 12. Half the trials fall under gravity (verlet is
// exact for it), so that s(t) is a parabola, not a line.
Tally corners(TimeOfImpactMethod toi) {
    std::mt19937_64 rng(1642);
    Tally tally;
    for (int trial = 0; trial < 120; ++trial) {
        const double a = uniform(rng, 0.05, 2.0), b = uniform(rng, 0.05, 2.0);
        const double mass = decades(rng, -2, 4); // 0.01 to 100 kg
        const double v0 = decades(rng, -1, 3);   // 0.1 to 100 m/s
        const double g = trial % 2 ? uniform(rng, 1.0, 20.0) : 0.0;
        // Under gravity e >= 0.2: with e near 0 the corner's rebound ends in the
        // resting contact the seed model cannot continue (docs/engine.md).
        const double e = g == 0.0 ? uniform(rng, 0.0, 1.0) : uniform(rng, 0.2, 1.0);
        const double quarter = 1.5707963267948966;
        const double angle =
            uniform(rng, 0.05, quarter - 0.05) + quarter * static_cast<double>(trial % 4);
        const double t_hit = uniform(rng, 0.1, 1.0);
        const double dt = time_steps[(trial / 2) % 2];

        const Vec2 lowest = test::lowest_corner(a, b, angle);
        // The lowest corner falls v0 t + g t^2 / 2 to the ground, arriving at v = v0 + g t.
        const Vec2 centre{0.0, -lowest.y + v0 * t_hit + 0.5 * g * t_hit * t_hit};
        const double v = v0 + g * t_hit;
        World world = make_world({static_body(make_box(1000, 1), {0, -1}),
                                  dynamic_body(make_box(a, b), mass, centre, angle, {0, -v0})},
                                 {0, -g}, e, solver_with(Integrator::verlet, toi));

        const test::CornerLanding landing{a, b, mass, e, lowest.x};
        const double inertia = landing.inertia();
        const double rx = lowest.x;
        const double j = landing.impulse(v);

        std::vector<CollisionEvent> events;
        const long long steps = static_cast<long long>(1.5 / dt);
        for (long long k = 0; k < steps && events.empty(); ++k) {
            REQUIRE_FALSE(step(world, static_cast<double>(k) * dt, dt, events));
        }
        INFO("trial " << trial << " a " << a << " b " << b << " angle " << angle << " v " << v
                      << " g " << g << " e " << e << " M " << mass << " dt " << dt);
        REQUIRE_FALSE(events.empty());
        const CollisionEvent& hit = events.front();
        CHECK(close_relative(hit.time, t_hit, rel));
        CHECK(close_relative(hit.vn_before, -v, rel));
        CHECK(close_relative(hit.impulse, j, rel));
        CHECK(close_relative(hit.point.x, rx, rel, a + b));
        CHECK(hit.normal == Vec2{0, 1});
        CHECK(close_relative(hit.vn_after, -e * hit.vn_before, rel, v));
        if (g == 0.0 && events.size() == 1) {
            // Nothing changes the velocities after the impact in this step.
            const BodyState& s = world.bodies[1].state;
            CHECK(s.velocity.x == 0.0);
            CHECK(close_relative(s.velocity.y, -v + j / mass, rel, v));
            CHECK(close_relative(s.angular_velocity, rx * j / inertia, rel, v / (a + b)));
        }
        tally.add(world, events);
    }
    return tally;
}

// A ball and a non-rotating box (Eq. 6: one impulse for its flat landing) fall
// onto the ground within one step, in either order, with no gravity. When the
// later one comes first in body order, the pair found at the step's end is not
// the one that collides first: the search must switch to the other pair.
Tally ball_and_box(TimeOfImpactMethod toi, std::vector<std::vector<CollisionEvent>>& runs) {
    std::mt19937_64 rng(5);
    Tally tally;
    for (int trial = 0; trial < 40; ++trial) {
        const double dt = time_steps[trial % 2];
        // Impact times inside step 10, in either order.
        const double t_1 = dt * (10.0 + uniform(rng, 0.05, 0.95));
        const double t_2 = dt * (10.0 + uniform(rng, 0.05, 0.95));
        // At most 10 m/s, a third of a metre per step: no tunnelling through the ground.
        const double v_1 = decades(rng, -1, 2), v_2 = decades(rng, -1, 2);
        const double e = uniform(rng, 0.0, 1.0);
        World world = make_world(
            {static_body(make_box(50, 0.5), {0, -0.5}),
             dynamic_body(make_circle(0.5), 1.0, {-5, 0.5 + v_1 * t_1}, 0, {0, -v_1}),
             dynamic_body(make_box(0.5, 0.5), 2.0, {5, 0.5 + v_2 * t_2}, 0, {0, -v_2}, 0, false)},
            {0, 0}, e, solver_with(Integrator::verlet, toi));
        const std::vector<CollisionEvent> events = test::run_steps(world, dt, 11);
        INFO("trial " << trial << " t_1 " << t_1 << " t_2 " << t_2 << " e " << e);
        REQUIRE(events.size() == 2);
        const bool first_is_1 = t_1 < t_2;
        const CollisionEvent& hit_1 = first_is_1 ? events[0] : events[1];
        const CollisionEvent& hit_2 = first_is_1 ? events[1] : events[0];
        CHECK(hit_1.body_a == 1);
        CHECK(hit_2.body_a == 2);
        CHECK(close_relative(hit_1.time, t_1, rel));
        CHECK(close_relative(hit_2.time, t_2, rel));
        CHECK(close_relative(hit_1.vn_after, e * v_1, rel, v_1));
        CHECK(close_relative(hit_2.vn_after, e * v_2, rel, v_2));
        tally.add(world, events);
        runs.push_back(events);
    }
    return tally;
}

// A ball 1 cm above the ground falling at 1 m/s: it lands at t = 0.01 s,
// inside the first step, for the failure cases.
World first_step_drop(const SolverSettings& solver) {
    return make_world({static_body(make_box(50, 0.5), {0, -0.5}),
                       dynamic_body(make_circle(0.5), 1.0, {0, 0.5 + 0.01}, 0, {0, -1.0})},
                      {0, 0}, 0.5, solver);
}

} // namespace

TEST_CASE("secant search: drop impact times and rebound speeds e^n v1 hold", "[toi]") {
    const Tally secant = drops(TimeOfImpactMethod::secant);
    CHECK(secant.collisions >= 32 * 5);
}

TEST_CASE("secant search: single-corner impacts hold Eq. 9's exact answer", "[toi]") {
    const Tally secant = corners(TimeOfImpactMethod::secant);
    CHECK(secant.collisions >= 120);
}

TEST_CASE("secant search: an earlier collision of another pair takes over the bracket", "[toi]") {
    std::vector<std::vector<CollisionEvent>> bisection_runs, secant_runs;
    const Tally bisection = ball_and_box(TimeOfImpactMethod::bisection, bisection_runs);
    const Tally secant = ball_and_box(TimeOfImpactMethod::secant, secant_runs);
    REQUIRE(secant_runs.size() == bisection_runs.size());
    for (std::size_t run = 0; run < secant_runs.size(); ++run) {
        INFO("trial " << run);
        for (std::size_t k = 0; k < secant_runs[run].size(); ++k) {
            const CollisionEvent& s = secant_runs[run][k];
            const CollisionEvent& b = bisection_runs[run][k];
            CHECK(s.body_a == b.body_a);
            CHECK(std::fabs(s.time - b.time) <= 2e-12); // both within toi_tolerance of the root
        }
    }
    INFO("bisection " << bisection.iterations << ", secant " << secant.iterations);
    CHECK(2 * secant.iterations <= bisection.iterations);
}

TEST_CASE("secant search needs at most half the bisection's iterations", "[toi]") {
    const Tally bisection_drops = drops(TimeOfImpactMethod::bisection);
    const Tally bisection_corners = corners(TimeOfImpactMethod::bisection);
    const Tally secant_drops = drops(TimeOfImpactMethod::secant);
    const Tally secant_corners = corners(TimeOfImpactMethod::secant);
    Tally bisection = bisection_drops;
    bisection.add(bisection_corners);
    Tally secant = secant_drops;
    secant.add(secant_corners);
    const double ratio =
        static_cast<double>(secant.iterations) / static_cast<double>(bisection.iterations);
    INFO("drops, per collision: bisection " << bisection_drops.per_collision() << ", secant "
                                            << secant_drops.per_collision());
    INFO("corners, per collision: bisection " << bisection_corners.per_collision() << ", secant "
                                              << secant_corners.per_collision());
    INFO("total: bisection " << bisection.iterations << " iterations for " << bisection.collisions
                             << " collisions, secant " << secant.iterations << " for "
                             << secant.collisions << "; ratio " << ratio);
    // Both resolve the same collisions; the secant search with far fewer
    // iterations (measured: 0.13, 4.6 per collision against 34.5).
    CHECK(secant.collisions == bisection.collisions);
    CHECK(ratio <= 0.5);
    CHECK(ratio <= 0.25);
    CHECK(secant_drops.per_collision() <= 0.5 * bisection_drops.per_collision());
    CHECK(secant_corners.per_collision() <= 0.5 * bisection_corners.per_collision());
}

TEST_CASE("an impossible toi_tolerance ends in toi_not_converged, never a hang", "[toi]") {
    for (const TimeOfImpactMethod toi :
         {TimeOfImpactMethod::bisection, TimeOfImpactMethod::secant}) {
        for (const double tolerance : {1e-300, 1e-30}) {
            SolverSettings solver = solver_with(Integrator::verlet, toi);
            solver.toi_tolerance = tolerance;
            World world = first_step_drop(solver);
            std::vector<CollisionEvent> events;
            const std::optional<StepError> error = step(world, 0.0, 1.0 / 60.0, events);
            INFO("method " << static_cast<int>(toi) << " tolerance " << tolerance);
            REQUIRE(error);
            CHECK(error->failure == StepFailure::toi_not_converged);
            CHECK(error->body_a == 1);
            CHECK(events.empty());
            CHECK(world.work.toi_iterations <= solver.max_search_iterations);
            // Left at the last configuration free of interpenetration, at the impact.
            CHECK(world.bodies[1].state.position.y >= 0.5);
            CHECK(std::fabs(error->time - 0.01) < 1e-12);
        }
    }
}

TEST_CASE("the iteration bound ends the secant search as it does the bisection", "[toi]") {
    for (const TimeOfImpactMethod toi :
         {TimeOfImpactMethod::bisection, TimeOfImpactMethod::secant}) {
        SolverSettings solver = solver_with(Integrator::verlet, toi);
        solver.max_search_iterations = 2;
        World world = first_step_drop(solver);
        std::vector<CollisionEvent> events;
        const std::optional<StepError> error = step(world, 0.0, 1.0 / 60.0, events);
        REQUIRE(error);
        CHECK(error->failure == StepFailure::toi_not_converged);
        CHECK(world.work.toi_iterations == 2);
    }
}

TEST_CASE("both searches give the same bits run after run", "[toi][determinism]") {
    for (const TimeOfImpactMethod toi :
         {TimeOfImpactMethod::bisection, TimeOfImpactMethod::secant}) {
        Tally first = drops(toi);
        first.add(corners(toi));
        Tally second = drops(toi);
        second.add(corners(toi));
        CHECK(first.digest == second.digest);
        CHECK(first.iterations == second.iterations);
    }
}

TEST_CASE("the bisection's results are those of the seed's engine, to the bit", "[toi]") {
    Tally bisection = drops(TimeOfImpactMethod::bisection);
    bisection.add(corners(TimeOfImpactMethod::bisection));
    // Pinned from the engine before the secant search was added; an intended
    // change to the bisection updates these two numbers.
    INFO("digest 0x" << std::hex << bisection.digest << std::dec << ", iterations "
                     << bisection.iterations);
    CHECK(bisection.digest == 0xa1ccf9c8cd404fd9ull);
    CHECK(bisection.iterations == 10343);
}
