// The exact answers of docs/physics.md against real runs of the engine, as a
// scene's expectations judge them (harness/gate/expectations.h); the kinds on
// hand-built trajectories are in test_expectations.cpp. Every number here is
// derived in the comments beside it, never copied from a run.
#include "expectations.h"
#include "run.h"
#include "scene.h"
#include "support.h"
#include "support/expectation_results.h"
#include "support/scene_text.h"
#include "support/trajectories.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

using impulse::harness::evaluate_expectations;
using impulse::harness::ExpectationResult;
using impulse::harness::parse_scene;
using impulse::harness::run_scene;
using impulse::harness::Scene;
using impulse::harness::Trajectory;
using impulse::harness::TrajectoryEvent;
using namespace impulse::test;
using Json = nlohmann::json;

namespace {

Json ground() {
    return {{"name", "ground"},
            {"static", true},
            {"shape", {{"box", {50, 0.5}}}},
            {"position", {0, -0.5}}};
}

Json scene_json(double g, double e, double dt, double duration, const char* integrator, Json bodies,
                Json expectations) {
    return {{"schema", "impulse/scene@1"},
            {"name", "exact"},
            {"gravity", {0, g == 0.0 ? 0.0 : -g}}, // no -0.0 in a file
            {"restitution", e},
            {"dt", dt},
            {"duration", duration},
            {"solver", {{"integrator", integrator}}},
            {"bodies", std::move(bodies)},
            {"expectations", std::move(expectations)}};
}

std::vector<ExpectationResult> run_and_evaluate(const Json& scene_document) {
    const Scene scene = parse_scene(scene_document.dump(), test_file);
    return evaluate_expectations(scene, run_scene(scene));
}

} // namespace

TEST_CASE("drop expectations hold at rtol 1e-9 on real runs", "[expectations]") {
    struct Case {
        double h0, g, e;
        bool circle;
        const char* integrator;
        double dt;
        int impacts;
    };
    // verlet and rk4 are exact for constant acceleration (docs/engine.md), so
    // the ladder holds at any time step.
    const Case cases[] = {
        {1.0, 9.81, 0.8, true, "verlet", 1.0 / 60.0, 5},
        {2.5, 9.81, 0.6, false, "rk4", 1.0 / 30.0, 4},
        {0.7, 3.7, 0.9, true, "rk4", 1.0 / 60.0, 6},
        {4.0, 20.0, 0.5, false, "verlet", 1.0 / 30.0, 3},
    };
    for (const Case& c : cases) {
        INFO("h0 " << c.h0 << " g " << c.g << " e " << c.e << " " << c.integrator << " dt "
                   << c.dt);
        // End at the apex after the last impact: half the next flight, e^n v1 / g.
        const Drop drop{c.h0, c.g, c.e};
        const double last = drop.impact_time(c.impacts);
        const double next = drop.impact_time(c.impacts + 1);
        Json body = {{"name", "body"}, {"mass", 2.0}, {"position", {0.3, 0.5 + c.h0}}};
        if (c.circle) {
            body["shape"] = {{"circle", 0.5}};
        } else {
            body["shape"] = {{"box", {0.75, 0.5}}};
            body["rotation"] = false;
            body["position"] = {0.3, 0.5 + c.h0};
        }
        const std::vector<ExpectationResult> results = run_and_evaluate(scene_json(
            c.g, c.e, c.dt, 0.5 * (last + next), c.integrator, {ground(), body},
            {{{"kind", "drop"}, {"body", "body"}, {"impacts", c.impacts}, {"rtol", 1e-9}}}));
        INFO(listing(results));
        CHECK(results.size() == static_cast<std::size_t>(3 * c.impacts));
        CHECK(failures(results) == 0);
    }
}

TEST_CASE("corner-impact expectations hold at rtol 1e-9 on real runs", "[expectations]") {
    struct Case {
        double a, b, angle, mass, vx, vy, h, g, e;
        const char* integrator;
        double dt;
    };
    const Case cases[] = {
        {1.0, 0.5, 0.5, 2.0, 0.5, 0.0, 1.0, 9.81, 0.5, "verlet", 1.0 / 60.0},
        {0.5, 0.25, -0.3, 1.0, -1.0, -2.0, 0.8, 9.81, 0.8, "rk4", 1.0 / 30.0},
        {1.5, 0.4, 1.2, 5.0, 0.0, -3.0, 0.6, 0.0, 0.3, "verlet", 1.0 / 30.0},
        {0.3, 0.6, 2.0, 0.5, 2.0, 1.0, 0.5, 4.0, 1.0, "rk4", 1.0 / 60.0},
    };
    int with_state = 0;
    for (const Case& c : cases) {
        INFO("box " << c.a << " x " << c.b << " angle " << c.angle << " v (" << c.vx << ", " << c.vy
                    << ") h " << c.h << " g " << c.g << " e " << c.e << " " << c.integrator
                    << " dt " << c.dt);
        // The lowest corner of a box turned by the angle is |a sin| + |b cos|
        // below its centre; put it h above the ground (top at y = 0).
        const double depth = std::abs(c.a * std::sin(c.angle)) + std::abs(c.b * std::cos(c.angle));
        // It meets the ground at the positive root of h + vy t - g t^2 / 2 = 0.
        const double speed = std::sqrt(c.vy * c.vy + 2.0 * c.g * c.h);
        const double t_hit = c.g > 0.0 ? (c.vy + speed) / c.g : c.h / -c.vy;
        const Json body = {{"name", "box"},    {"shape", {{"box", {c.a, c.b}}}},
                           {"mass", c.mass},   {"position", {0.2, depth + c.h}},
                           {"angle", c.angle}, {"velocity", {c.vx, c.vy}}};
        // Two frames past the impact: the state the impact left is seen in the first.
        const std::vector<ExpectationResult> results = run_and_evaluate(
            scene_json(c.g, c.e, c.dt, t_hit + 2.0 * c.dt, c.integrator, {ground(), body},
                       {{{"kind", "corner-impact"}, {"body", "box"}, {"rtol", 1e-9}}}));
        INFO(listing(results));
        CHECK((results.size() == 7 || results.size() == 4));
        CHECK(failures(results) == 0);
        with_state += results.size() == 7 ? 1 : 0;
    }
    CHECK(with_state >= 3);
}

TEST_CASE("head-on expectations hold on real runs, including a velocity that cancels to zero",
          "[expectations]") {
    struct Case {
        double ma, mb, va, vb, e;
        bool circles;
        const char* integrator;
        double dt;
        bool simultaneous = false;
    };
    const Case cases[] = {
        {1.0, 1.0, 3.0, 0.0, 1.0, true, "symplectic-euler", 1.0 / 60.0}, // vA' = 0 exactly
        {1.0, 3.0, 4.0, -1.0, 0.5, false, "rk4", 1.0 / 30.0},
        {5.0, 0.2, 0.7, -2.5, 0.9, true, "verlet", 1.0 / 60.0},
        // Faces meeting whole: two events at one instant, whose impulses sum to j.
        {3.7, 0.013, 1.0, -2.0, 0.93, false, "verlet", 1.0 / 60.0, true},
    };
    for (const Case& c : cases) {
        INFO("masses " << c.ma << ", " << c.mb << " e " << c.e);
        auto disc = [&](const char* name, double mass, double x, double v) {
            Json body = {
                {"name", name}, {"mass", mass}, {"position", {x, 0.25}}, {"velocity", {v, 0.5}}};
            body["shape"] = c.circles ? Json{{"circle", 0.5}} : Json{{"box", {0.5, 0.5}}};
            if (!c.circles) {
                body["rotation"] = false;
            }
            return body;
        };
        // They start 1 m apart (surfaces) and meet after 1 / (va - vb) s.
        const double meet = 1.0 / (c.va - c.vb);
        Json scene = scene_json(0.0, c.e, c.dt, meet + 0.5, c.integrator,
                                {disc("a", c.ma, 0.0, c.va), disc("b", c.mb, 2.0, c.vb)},
                                {{{"kind", "head-on"}, {"a", "a"}, {"b", "b"}, {"rtol", 1e-9}}});
        if (c.simultaneous) {
            scene["solver"]["contacts"] = "simultaneous";
        }
        const std::vector<ExpectationResult> results = run_and_evaluate(scene);
        INFO(listing(results));
        CHECK(results.size() == 5);
        CHECK(failures(results) == 0);
    }
}

namespace {

// A zero-gravity glancing hit of two rotating boxes, e given: the striker's
// corner meets the target off its centre, so both spin afterwards.
Json glancing(double e, const char* integrator, double dt, Json expectations) {
    Json scene = scene_json(0.0, e, dt, 2.0, integrator,
                            {{{"name", "striker"},
                              {"shape", {{"box", {0.5, 0.5}}}},
                              {"mass", 1},
                              {"position", {-2, 0.6}},
                              {"angle", 0.2},
                              {"velocity", {3, 0.1}},
                              {"angular_velocity", 0.4}},
                             {{"name", "target"},
                              {"shape", {{"box", {0.75, 0.25}}}},
                              {"mass", 2},
                              {"position", {1, 0}},
                              {"velocity", {-0.2, 0}}}},
                            std::move(expectations));
    return scene;
}

} // namespace

TEST_CASE("momentum, angular momentum and energy are conserved on a real glancing hit",
          "[expectations]") {
    const Json expectation = {{{"kind", "conserved"},
                               {"quantities", {"momentum", "angular_momentum", "energy"}},
                               {"rtol", 1e-12}}};
    for (const char* integrator : {"symplectic-euler", "rk4"}) {
        for (const double dt : {1.0 / 30.0, 1.0 / 60.0}) {
            INFO(integrator << " dt " << dt);
            const Json document = glancing(1.0, integrator, dt, expectation);
            const Scene scene = parse_scene(document.dump(), test_file);
            const Trajectory run = run_scene(scene);
            REQUIRE_FALSE(run.events.empty());
            // The hit is off-centre: the target, still at first, ends up spinning.
            CHECK(run.frames.back().back() != 0.0);
            const std::vector<ExpectationResult> results = evaluate_expectations(scene, run);
            INFO(listing(results));
            CHECK(results.size() == 3);
            CHECK(failures(results) == 0);
        }
    }
}

TEST_CASE("energy never increases on real runs with e = 0.5", "[expectations]") {
    const Json expectation = {{{"kind", "energy-non-increasing"}, {"rtol", 1e-12}}};
    SECTION("a glancing hit in free space") {
        const std::vector<ExpectationResult> results =
            run_and_evaluate(glancing(0.5, "rk4", 1.0 / 60.0, expectation));
        INFO(listing(results));
        CHECK(results.size() == 1);
        CHECK(failures(results) == 0);
    }
    SECTION("a ball bouncing under gravity, verlet") {
        // Verlet is exact for constant acceleration, so between impacts the
        // energy only rounds; each impact takes away 1 - e^2 of the kinetic part.
        const Json ball = {
            {"name", "ball"}, {"shape", {{"circle", 0.5}}}, {"mass", 1.5}, {"position", {0, 2.5}}};
        const double h0 = 2.0, g = 9.81, e = 0.5;
        const double end = Drop{h0, g, e}.duration(3); // between impacts 3 and 4
        const std::vector<ExpectationResult> results = run_and_evaluate(
            scene_json(g, e, 1.0 / 60.0, end, "verlet", {ground(), ball}, expectation));
        INFO(listing(results));
        CHECK(results.size() == 1);
        CHECK(failures(results) == 0);
    }
    SECTION("explicit Euler gains m g^2 h^2 / 2 per step of free fall, which is allowed it") {
        // x' = x + h v, v' = v - g h: v'^2 / 2 + g x' = v^2 / 2 + g x + g^2 h^2 / 2.
        const double mass = 1.5, g = 9.81, dt = 1.0 / 60.0;
        const Json ball = {
            {"name", "ball"}, {"shape", {{"circle", 0.5}}}, {"mass", mass}, {"position", {0, 2.5}}};
        const std::vector<ExpectationResult> results =
            run_and_evaluate(scene_json(g, 0.5, dt, 0.5, "euler", {ground(), ball}, expectation));
        // The integrator's own gain is not the contact's: the check allows
        // exactly it, so the largest rise it reports is one step's gain.
        REQUIRE(results.size() == 1);
        CHECK(results[0].passed);
        const double rise = results[0].actual - results[0].expected;
        const double per_step = mass * g * g * dt * dt / 2.0;
        CHECK(std::abs(rise - per_step) <= 1e-9 * per_step);
        REQUIRE(results[0].allowed);
        CHECK(*results[0].allowed >= per_step);
        CHECK(*results[0].allowed <= per_step * (1 + 1e-9) + 1e-12 * 100);
    }
}

TEST_CASE("conserved and energy-non-increasing scale their rtol by the terms, not by frame 0's "
          "totals, which can be 0",
          "[expectations]") {
    SECTION("a ball released at rest at y = 0: frame 0's energy terms are all 0") {
        // Falls 2 m onto a floor whose top is at y = -2.5, radius 0.5; with
        // e = 1 and verlet the energy only rounds, of terms up to m g 2 = 72.6 J.
        const Json floor = {{"name", "floor"},
                            {"static", true},
                            {"shape", {{"box", {10, 0.5}}}},
                            {"position", {0, -3}}};
        const Json ball = {
            {"name", "ball"}, {"shape", {{"circle", 0.5}}}, {"mass", 3.7}, {"position", {0, 0}}};
        const Json expectations = {
            {{"kind", "conserved"}, {"quantities", {"energy"}}, {"rtol", 1e-12}},
            {{"kind", "energy-non-increasing"}, {"rtol", 1e-12}}};
        const std::vector<ExpectationResult> results = run_and_evaluate(
            scene_json(9.81, 1.0, 1.0 / 60.0, 1.5, "verlet", {floor, ball}, expectations));
        INFO(listing(results));
        CHECK(results.size() == 2);
        CHECK(failures(results) == 0);
    }
    SECTION("a head-on hit along a line through the origin: x cross v = 0 of terms that are not") {
        // The canonical head-on turned by 30 degrees about the origin: every
        // body moves along the line y = x tan(30 deg), so L = 0 in every frame,
        // as the difference of m x_x v_y and m x_y v_x, each up to 1.5e3.
        const double c = std::sqrt(3.0) / 2.0, s = 0.5;
        const Json heavy = {{"name", "heavy"},
                            {"shape", {{"circle", 0.5}}},
                            {"mass", 1000},
                            {"position", {-2 * c, -2 * s}},
                            {"velocity", {c, s}}};
        const Json light = {{"name", "light"},
                            {"shape", {{"circle", 0.5}}},
                            {"mass", 1},
                            {"position", {2 * c, 2 * s}},
                            {"velocity", {-5 * c, -5 * s}}};
        const Json expectations = {{{"kind", "conserved"},
                                    {"quantities", {"momentum", "angular_momentum"}},
                                    {"rtol", 1e-12}}};
        const std::vector<ExpectationResult> results = run_and_evaluate(scene_json(
            0.0, 0.9, 1.0 / 60.0, 1.5, "symplectic-euler", {heavy, light}, expectations));
        INFO(listing(results));
        CHECK(results.size() == 2); // momentum is judged on its worse component
        CHECK(failures(results) == 0);
    }
}

TEST_CASE("energy and the momentum balance hold at rtol 1e-9 on a real gas in a room",
          "[expectations]") {
    // The canonical gas scenes' settings with the seed's world stepping (the
    // local stepping they ask for is the engine's to test).
    for (const char* shape : {R"({"circle": 0.1})", R"({"box": [0.1, 0.1]})"}) {
        INFO(shape);
        const std::string text = std::string(R"({
            "schema": "impulse/scene@1", "name": "gas", "gravity": [0, 0], "restitution": 1,
            "dt": 0.016666666666666666, "duration": 3,
            "solver": {"integrator": "symplectic-euler", "toi": "secant", "stepping": "world"},
            "gas": {"count": 10, "shape": )") +
                                 shape + R"(, "mass": 1, "spacing": 0.5, "max_speed": 5,
                    "max_angular_speed": 5, "random_angles": true, "seed": 1},
            "expectations": [
                {"kind": "conserved", "quantities": ["energy"], "rtol": 1e-9},
                {"kind": "momentum-balance", "rtol": 1e-9}]})";
        const Scene scene = parse_scene(text, test_file);
        const Trajectory trajectory = run_scene(scene);
        std::size_t with_walls = 0;
        for (const TrajectoryEvent& e : trajectory.events) {
            with_walls += e.b.rfind("wall-", 0) == 0 || e.a.rfind("wall-", 0) == 0 ? 1 : 0;
        }
        CHECK(with_walls >= 10); // the walls really do change the momentum
        const std::vector<ExpectationResult> results = evaluate_expectations(scene, trajectory);
        INFO(listing(results));
        REQUIRE(results.size() == 2);
        CHECK(failures(results) == 0);
    }
}
