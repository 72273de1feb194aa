// The exact answers of docs/physics.md through the whole simulation loop, for
// seeded random parameters, at time steps up to 1/30 s, to 1e-9 relative.
#include "support.h"

#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

using namespace impulse;
using impulse::test::close_relative;
using impulse::test::dynamic_body;
using impulse::test::log_uniform;
using impulse::test::static_body;
using impulse::test::uniform;

namespace {

constexpr double rel = 1e-9;
constexpr double time_steps[] = {1.0 / 30.0, 1.0 / 60.0, 1.0 / 240.0};

SolverSettings solver_with(Integrator integrator) {
    SolverSettings s;
    s.integrator = integrator;
    return s;
}

struct HeadOn {
    double ma, mb, va, vb, e;
    double va_after() const { return (ma * va + mb * vb - mb * e * (va - vb)) / (ma + mb); }
    double vb_after() const { return (ma * va + mb * vb + ma * e * (va - vb)) / (ma + mb); }
};

} // namespace

TEST_CASE("Head-on collision, mass ratios 1e-3 to 1e3, through the loop", "[exact]") {
    std::mt19937_64 rng(20261122);
    for (int trial = 0; trial < 200; ++trial) {
        const HeadOn c{1.0, log_uniform(rng, 1e-3, 1e3), uniform(rng, 0.1, 10.0),
                       -uniform(rng, 0.1, 10.0), uniform(rng, 0.0, 1.0)};
        const double dt = time_steps[trial % 3];
        const bool circles =
            trial % 2 == 0; // circles go through Eq. 9, boxes without rotation Eq. 6
        const Shape shape = circles ? make_circle(0.5) : make_box(0.5, 0.5);
        // They meet after a random time inside the run, at most 2 s.
        const double gap = uniform(rng, 0.05, 1.5) * (c.va - c.vb);
        World world =
            make_world({dynamic_body(shape, c.ma, {0, 0}, 0, {c.va, 0}, 0, circles),
                        dynamic_body(shape, c.mb, {1.0 + gap, 0}, 0, {c.vb, 0}, 0, circles)},
                       {0, 0}, c.e, solver_with(Integrator::symplectic_euler));
        const std::vector<CollisionEvent> events =
            test::run_steps(world, dt, static_cast<long long>(2.5 / dt));
        INFO("trial " << trial << " mass ratio " << c.mb << " e " << c.e << " dt " << dt);
        REQUIRE(events.size() == 1);
        const double scale = std::fabs(c.va) + std::fabs(c.vb);
        CHECK(close_relative(world.bodies[0].state.velocity.x, c.va_after(), rel, scale));
        CHECK(close_relative(world.bodies[1].state.velocity.x, c.vb_after(), rel, scale));
        CHECK(close_relative(events[0].time, gap / (c.va - c.vb), rel));
        const double p0 = c.ma * c.va + c.mb * c.vb;
        const double p1 =
            c.ma * world.bodies[0].state.velocity.x + c.mb * world.bodies[1].state.velocity.x;
        CHECK(std::fabs(p1 - p0) <= 1e-12 * (c.ma * std::fabs(c.va) + c.mb * std::fabs(c.vb)));
    }
}

TEST_CASE("Single-corner impact on static ground at many angles, masses and speeds", "[exact]") {
    std::mt19937_64 rng(1997);
    int checked_state = 0;
    const int trials = 300;
    for (int trial = 0; trial < trials; ++trial) {
        const double a = uniform(rng, 0.05, 2.0), b = uniform(rng, 0.05, 2.0);
        const double mass = log_uniform(rng, 0.01, 100.0);
        const double v = log_uniform(rng, 0.1, 100.0);
        const double e = uniform(rng, 0.0, 1.0);
        // Any angle away from a flat landing (there two corners would touch at once).
        const double quarter = 1.5707963267948966;
        const double angle =
            uniform(rng, 0.05, quarter - 0.05) + quarter * static_cast<double>(trial % 4);
        const double dt = time_steps[trial % 3];

        const Shape box = make_box(a, b);
        const Vec2 lowest = test::lowest_corner(a, b, angle);
        const double t_hit = uniform(rng, 0.1, 1.0);
        const Vec2 centre{0.0, -lowest.y + v * t_hit};
        World world = make_world({static_body(make_box(1000, 1), {0, -1}),
                                  dynamic_body(box, mass, centre, angle, {0, -v})},
                                 {0, 0}, e, solver_with(Integrator::verlet));

        // Exact answer (docs/physics.md): Eq. 9 for the one corner (support.h).
        const test::CornerLanding landing{a, b, mass, e, lowest.x};
        const double inertia = landing.inertia();
        const double rx = lowest.x;
        const double j = landing.impulse(v);
        const double vy_after = -v + j / mass;
        const double w_after = rx * j / inertia;

        std::vector<CollisionEvent> events;
        const long long steps = static_cast<long long>(1.5 / dt);
        long long k = 0;
        for (; k < steps && events.empty(); ++k) {
            REQUIRE_FALSE(step(world, static_cast<double>(k) * dt, dt, events));
        }
        INFO("trial " << trial << " a " << a << " b " << b << " angle " << angle << " v " << v
                      << " e " << e << " M " << mass << " dt " << dt);
        REQUIRE_FALSE(events.empty());
        const CollisionEvent& hit = events.front();
        CHECK(close_relative(hit.time, t_hit, rel));
        CHECK(close_relative(hit.vn_before, -v, rel));
        CHECK(close_relative(hit.impulse, j, rel));
        CHECK(close_relative(hit.point.x, rx, rel, a + b));
        CHECK(hit.normal == Vec2{0, 1});
        CHECK(close_relative(hit.vn_after, -e * hit.vn_before, rel, v));
        if (events.size() == 1) {
            // Zero gravity: nothing changes the velocities after the impact in this step.
            const BodyState& s = world.bodies[1].state;
            CHECK(s.velocity.x == 0.0);
            CHECK(close_relative(s.velocity.y, vy_after, rel, v));
            CHECK(close_relative(s.angular_velocity, w_after, rel, v / (a + b)));
            ++checked_state;
        }
    }
    CHECK(checked_state > trials / 2);
}

namespace {

using impulse::test::Drop;

void check_drop_events(const Drop& d, const std::vector<double>& times,
                       const std::vector<double>& rebound, int impacts) {
    REQUIRE(static_cast<int>(times.size()) >= impacts);
    double en = 1.0;
    for (int n = 1; n <= impacts; ++n) {
        en *= d.e;
        INFO("impact " << n);
        CHECK(close_relative(times[n - 1], d.impact_time(n), rel));
        CHECK(close_relative(rebound[n - 1], en * d.v1(), rel));
        const double apex = rebound[n - 1] * rebound[n - 1] / (2.0 * d.g);
        CHECK(close_relative(apex, en * en * d.h0, rel));
    }
}

} // namespace

TEST_CASE("Drop: impact times and apex ladder h_n = e^(2n) h0 through the loop", "[exact]") {
    std::mt19937_64 rng(42);
    for (int trial = 0; trial < 60; ++trial) {
        const Drop d{uniform(rng, 0.1, 10.0), uniform(rng, 1.0, 20.0), uniform(rng, 0.3, 0.95)};
        const double dt = time_steps[trial % 3];
        const Integrator integrator = trial % 2 ? Integrator::verlet : Integrator::rk4;
        const bool circle = trial % 4 < 2;
        const Shape shape = circle ? make_circle(0.5) : make_box(0.5, 0.5);
        const int impacts = 5;
        const double duration = d.duration(impacts);
        World world = make_world({static_body(make_box(50, 0.5), {0, -0.5}),
                                  dynamic_body(shape, 1.0, {0, 0.5 + d.h0}, 0, {}, 0, false)},
                                 {0, -d.g}, d.e, solver_with(integrator));
        const std::vector<CollisionEvent> events =
            test::run_steps(world, dt, static_cast<long long>(std::ceil(duration / dt)));
        std::vector<double> times, rebound;
        for (const CollisionEvent& ev : events) {
            times.push_back(ev.time);
            rebound.push_back(ev.vn_after);
        }
        INFO("trial " << trial << " h0 " << d.h0 << " g " << d.g << " e " << d.e << " dt " << dt);
        CHECK(events.size() >= static_cast<std::size_t>(impacts));
        check_drop_events(d, times, rebound, impacts);
    }
}

namespace {

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST_CASE("Drop through `impulse run`: the exact ladder survives the file format", "[exact][cli]") {
    std::mt19937_64 rng(7);
    for (int trial = 0; trial < 6; ++trial) {
        const Drop d{uniform(rng, 0.2, 5.0), 9.81, uniform(rng, 0.4, 0.9)};
        const double dt = time_steps[trial % 3];
        const int impacts = 4;
        const double duration = d.duration(impacts);
        nlohmann::json scene = {{"schema", "impulse/scene@1"},
                                {"name", "drop-exact"},
                                {"gravity", {0, -d.g}},
                                {"restitution", d.e},
                                {"dt", dt},
                                {"duration", duration},
                                {"solver", {{"integrator", trial % 2 ? "verlet" : "rk4"}}},
                                {"bodies",
                                 {{{"name", "ground"},
                                   {"static", true},
                                   {"shape", {{"box", {50, 0.5}}}},
                                   {"position", {0, -0.5}}},
                                  {{"name", "ball"},
                                   {"shape", {{"circle", 0.5}}},
                                   {"mass", 2.0},
                                   {"position", {0, 0.5 + d.h0}}}}}};
        const std::string dir = "impulse-test-exact-" + std::to_string(trial);
        const std::string scene_path = dir + "-scene.json";
        const std::string out_path = dir + "-out.json";
        std::ofstream(scene_path) << scene.dump(2);
        const std::string command =
            std::string(IMPULSE_BINARY) + " run " + scene_path + " --out " + out_path;
        REQUIRE(std::system(command.c_str()) == 0);
        const nlohmann::json trajectory = nlohmann::json::parse(read_text(out_path));
        std::vector<double> times, rebound;
        for (const auto& ev : trajectory.at("events")) {
            times.push_back(ev.at("t").get<double>());
            rebound.push_back(ev.at("vn_after").get<double>());
        }
        INFO("trial " << trial << " h0 " << d.h0 << " e " << d.e << " dt " << dt);
        check_drop_events(d, times, rebound, impacts);
        std::remove(scene_path.c_str());
        std::remove(out_path.c_str());
    }
}
