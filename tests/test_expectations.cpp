// Expectations a scene declares (harness/gate/expectations.h): every kind on small
// trajectories written by hand from the physics, passing as given and failing
// when one value moves just beyond its tolerance. The exact answers of
// docs/physics.md against real runs of the engine are in
// test_expectations_real_runs.cpp.
//
// Every number here is derived in the comments beside it, never copied from a
// run.
#include "expectations.h"
#include "run.h"
#include "run_json.h"
#include "scene.h"
#include "support/expectation_results.h"
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

// ---------------------------------------------------------------- building blocks

// ---------------------------------------------------------------- the hand-built scenes

// A ball of mass 1, radius 0.5, released at rest with its lowest point 1 m
// above static ground (h0 = 1), g = 8, e = 0.5. By docs/physics.md, drop:
//   v1 = sqrt(2 g h0) = 4, t1 = v1 / g = 0.5;
//   impact 2 at t1 + 2 e v1 / g = 0.5 + 0.5 = 1.0, impact 3 at 1.0 + 2 e^2 v1 / g = 1.25;
//   rebound speeds e v1 = 2, e^2 v1 = 1, e^3 v1 = 0.5;
//   apex gaps e^2 h0 = 0.25 = 2^2 / 16, e^4 h0 = 1/16, e^6 h0 = 1/64.
// Between impacts the ball flies freely: from the ground (centre at 0.5) at
// speed v, y = 0.5 + v s - 4 s^2.
const std::string drop_scene = R"({
    "schema": "impulse/scene@1", "name": "drop", "gravity": [0, -8], "restitution": 0.5,
    "dt": 0.25, "duration": 1.5,
    "bodies": [
        {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
        {"name": "ball", "shape": {"circle": 0.5}, "mass": 1, "position": [0, 1.5]}]})";

Trajectory drop_trajectory() {
    // Energy per frame, E = v^2 / 2 + 8 y: 12, 12, 6, 6, 4.5, 4.125 (each bounce
    // keeps e^2 = 1/4 of the kinetic energy at impact).
    return trajectory_of({"ball"},
                         {{0.00, 0, 1.50, 0, 0, 0.0, 0},
                          {0.25, 0, 1.25, 0, 0, -2.0, 0},
                          {0.50, 0, 0.50, 0, 0, 2.0, 0},
                          {0.75, 0, 0.75, 0, 0, 0.0, 0},
                          {1.00, 0, 0.50, 0, 0, 1.0, 0},
                          {1.25, 0, 0.50, 0, 0, 0.5, 0}},
                         // j = m (1 + e) v: 6, 3, 1.5.
                         {make_event(0.50, "ball", "ground", 0, 0, 0, 1, 6.0, -4, 2.0),
                          make_event(1.00, "ball", "ground", 0, 0, 0, 1, 3.0, -2, 1.0),
                          make_event(1.25, "ball", "ground", 0, 0, 0, 1, 1.5, -1, 0.5)});
}

// A triangle with its centroid at the origin, vertices (1, -1), (0.5, 1),
// (-1.5, 0): one lowest corner at rx = 1, 1 m below the centre. Mass 2,
// inertia given as 1, centre at (0, 2) so the corner is h = 1 m above the
// ground; moving sideways at vx0 = 1, g = 8, e = 0.5. docs/physics.md, corner:
//   v = sqrt(2 g h) = 4, hit at t = v / g = 0.5 where the corner is at x = 0.5 + 1 = 1.5;
//   j = (1 + e) v / (1/M + rx^2 / I) = 6 / 1.5 = 4;
//   vy' = -v + j / M = -2, w' = rx j / I = 4 (the corner leaves at vy' + w' rx = 2 = e v).
// The frame at t = 0.75 is a quarter second of free fall later: vy = -2 - 8 / 4 = -4.
const std::string corner_scene = R"({
    "schema": "impulse/scene@1", "name": "corner", "gravity": [0, -8], "restitution": 0.5,
    "dt": 0.25, "duration": 1,
    "bodies": [
        {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
        {"name": "tri", "shape": {"polygon": [[1, -1], [0.5, 1], [-1.5, 0]]}, "mass": 2,
         "inertia": 1, "position": [0, 2], "velocity": [1, 0]}]})";

Trajectory corner_trajectory() {
    return trajectory_of({"tri"},
                         {{0.00, 0.00, 2.00, 0, 1, 0, 0},
                          {0.25, 0.25, 1.75, 0, 1, -2, 0},
                          // The impact comes at the end of this step: touching, not yet resolved.
                          {0.50, 0.50, 1.00, 0, 1, -4, 0},
                          // y = 1 - 2 / 4 - 4 / 16, angle = 4 / 4.
                          {0.75, 0.75, 0.25, 1, 1, -4, 4}},
                         {make_event(0.5, "tri", "ground", 1.5, 0, 0, 1, 4.0, -4.0, 2.0)});
}

// Discs of radius 0.5: a (mass 1) at the origin moving (4, 1), b (mass 3) at
// (2, 0) moving (0, 1); no gravity, e = 0.5. They close at 4 m/s along
// u = (1, 0) and touch at t = 0.25. docs/physics.md, head-on with vA = 4, vB = 0:
//   vA' = (4 - 3 * 0.5 * 4) / 4 = -0.5, vB' = (4 + 0.5 * 4) / 4 = 1.5,
//   j = 1 * 3 * 1.5 * 4 / 4 = 4.5; across u both keep vy = 1.
const std::string head_on_scene = R"({
    "schema": "impulse/scene@1", "name": "head-on", "gravity": [0, 0], "restitution": 0.5,
    "dt": 0.25, "duration": 1,
    "bodies": [
        {"name": "a", "shape": {"circle": 0.5}, "mass": 1, "velocity": [4, 1]},
        {"name": "b", "shape": {"circle": 0.5}, "mass": 3, "position": [2, 0],
         "velocity": [0, 1]}]})";

Trajectory head_on_trajectory() {
    return trajectory_of(
        {"a", "b"},
        {{0.00, 0.000, 0.00, 0, 4.0, 1, 0, 2.000, 0.00, 0, 0.0, 1, 0},
         {0.25, 1.000, 0.25, 0, 4.0, 1, 0, 2.000, 0.25, 0, 0.0, 1, 0},
         {0.50, 0.875, 0.50, 0, -0.5, 1, 0, 2.375, 0.50, 0, 1.5, 1, 0}},
        // n = (-1, 0) points toward a: vn_before = (4 - 0) * -1, vn_after = (-0.5 - 1.5) * -1.
        {make_event(0.25, "a", "b", 1.5, 0.25, -1, 0, 4.5, -4.0, 2.0)});
}

// The same discs with e = 1 and b spinning at 2 rad/s (I_b = 3 * 0.5^2 / 2 =
// 0.375; a frictionless hit cannot change it). Head-on with e = 1:
// vA' = (4 - 3 * 4) / 4 = -2, vB' = (4 + 4) / 4 = 2. Totals about the origin:
//   P = (4, 4) throughout;
//   L = m x cross v + I w: at t = 0, 0 + 3 * (2 * 1) + 0.375 * 2 = 6.75;
//       at t = 0.5, a at (0.5, 0.5) moving (-2, 1): 0.5 + 1 = 1.5,
//       b at (2.5, 0.5) moving (2, 1): 3 * (2.5 - 1) = 4.5, plus 0.75;
//   E = 1 * 17 / 2 + 3 * 1 / 2 + 0.375 * 4 / 2 = 10.75 before,
//       1 * 5 / 2 + 3 * 5 / 2 + 0.75 = 10.75 after.
const std::string conserved_scene = R"({
    "schema": "impulse/scene@1", "name": "conserved", "gravity": [0, 0], "restitution": 1,
    "dt": 0.25, "duration": 1,
    "bodies": [
        {"name": "a", "shape": {"circle": 0.5}, "mass": 1, "velocity": [4, 1]},
        {"name": "b", "shape": {"circle": 0.5}, "mass": 3, "position": [2, 0],
         "velocity": [0, 1], "angular_velocity": 2}]})";

Trajectory conserved_trajectory() {
    return trajectory_of({"a", "b"},
                         {{0.00, 0.0, 0.00, 0, 4, 1, 0, 2.0, 0.00, 0.0, 0, 1, 2},
                          {0.25, 1.0, 0.25, 0, 4, 1, 0, 2.0, 0.25, 0.5, 0, 1, 2},
                          {0.50, 0.5, 0.50, 0, -2, 1, 0, 2.5, 0.50, 1.0, 2, 1, 2},
                          {0.75, 0.0, 0.75, 0, -2, 1, 0, 3.0, 0.75, 1.5, 2, 1, 2}},
                         {make_event(0.25, "a", "b", 1.5, 0.25, -1, 0, 6.0, -4.0, 4.0)});
}

} // namespace

// ---------------------------------------------------------------- every kind, by hand

TEST_CASE("drop: impact times, rebound speeds and apex gaps of a hand-built bounce",
          "[expectations]") {
    const std::string expectation = R"([{"kind": "drop", "body": "ball", "impacts": 3,
                                         "atol": 1e-9}])";
    SECTION("as derived") {
        const std::vector<ExpectationResult> results =
            evaluate(drop_scene, expectation, drop_trajectory());
        INFO(listing(results));
        CHECK(results.size() == 9);
        CHECK(failures(results) == 0);
        const ExpectationResult& rebound = result_about(results, "impact 2 rebound speed");
        CHECK(rebound.what == "drop of 'ball': impact 2 rebound speed");
        CHECK(rebound.path == "expectations[0]");
        CHECK(rebound.expected == 1.0);
        CHECK(result_about(results, "impact 3 time").expected == 1.25);
        CHECK(result_about(results, "impact 1 apex gap").expected == 0.25);
    }
    SECTION("an impact time just beyond the tolerance") {
        Trajectory t = drop_trajectory();
        t.events[1].t = 1.0 + 2e-9;
        require_only_failure(evaluate(drop_scene, expectation, t), "impact 2 time");
    }
    SECTION("an impact time just within the tolerance") {
        Trajectory t = drop_trajectory();
        t.events[1].t = 1.0 + 0.5e-9;
        CHECK(failures(evaluate(drop_scene, expectation, t)) == 0);
    }
    SECTION("a rebound speed just beyond: the speed and its apex both fail") {
        Trajectory t = drop_trajectory();
        // The apex v^2 / 16 moves by about 2 * 0.5 * 4e-9 / 16 = 2.5e-10: within.
        t.events[2].vn_after = 0.5 + 4e-9;
        require_only_failure(evaluate(drop_scene, expectation, t), "impact 3 rebound speed");
        // Apex gap after impact 1: 0.25 -> (2 + d)^2 / 16, off by d / 4 > 1e-9 for d = 8e-9.
        t = drop_trajectory();
        t.events[0].vn_after = 2.0 + 8e-9;
        const std::vector<ExpectationResult> results = evaluate(drop_scene, expectation, t);
        CHECK(failures(results) == 2);
        CHECK_FALSE(result_about(results, "impact 1 apex gap").passed);
    }
    SECTION("fewer impacts than expected") {
        Trajectory t = drop_trajectory();
        t.events.pop_back();
        const std::vector<ExpectationResult> results = evaluate(drop_scene, expectation, t);
        require_only_failure(results, "impacts");
        CHECK(result_about(results, "impacts").detail ==
              "the run has 2 collisions of 'ball', fewer than the 3 impacts expected");
        CHECK(results.size() == 7);
    }
}

TEST_CASE("corner-impact: a hand-built triangle landing on one corner", "[expectations]") {
    const std::string expectation = R"([{"kind": "corner-impact", "body": "tri", "atol": 1e-9}])";
    SECTION("as derived") {
        const std::vector<ExpectationResult> results =
            evaluate(corner_scene, expectation, corner_trajectory());
        INFO(listing(results));
        CHECK(results.size() == 7);
        CHECK(failures(results) == 0);
        CHECK(result_about(results, "impulse").expected == 4.0);
        CHECK(result_about(results, "time").expected == 0.5);
        CHECK(result_about(results, "vn_before").expected == -4.0);
        CHECK(result_about(results, "point.x").expected == 1.5);
        CHECK(result_about(results, "omega after").expected == 4.0);
        CHECK(result_about(results, "vx after").expected == 1.0);
        CHECK(result_about(results, "vy after").expected == -4.0);
        CHECK(result_about(results, "omega after").what == "corner impact of 'tri': omega after");
    }
    SECTION("each value just beyond the tolerance") {
        struct Perturbation {
            const char* what;
            void (*apply)(Trajectory&);
        };
        const Perturbation perturbations[] = {
            {"time", [](Trajectory& t) { t.events[0].t += 2e-9; }},
            {"impulse", [](Trajectory& t) { t.events[0].impulse += 2e-9; }},
            {"vn_before", [](Trajectory& t) { t.events[0].vn_before -= 2e-9; }},
            {"point.x", [](Trajectory& t) { t.events[0].point[0] += 2e-9; }},
            {"omega after", [](Trajectory& t) { t.frames[3][6] += 2e-9; }},
            {"vx after", [](Trajectory& t) { t.frames[3][4] -= 2e-9; }},
            {"vy after", [](Trajectory& t) { t.frames[3][5] += 2e-9; }},
        };
        for (const Perturbation& p : perturbations) {
            INFO(p.what);
            Trajectory t = corner_trajectory();
            p.apply(t);
            require_only_failure(evaluate(corner_scene, expectation, t), p.what);
        }
    }
    SECTION("a second collision before the next frame leaves the state unchecked") {
        Trajectory t = corner_trajectory();
        t.events.push_back(make_event(0.6, "tri", "ground", -0.5, 0, 0, 1, 1.0, -1.0, 0.5));
        t.frames[3][6] = 99.0; // the second hit changed the spin: not the first one's answer
        const std::vector<ExpectationResult> results = evaluate(corner_scene, expectation, t);
        INFO(listing(results));
        CHECK(results.size() == 4);
        CHECK(failures(results) == 0);
    }
    SECTION("no collision at all") {
        Trajectory t = corner_trajectory();
        t.events.clear();
        const std::vector<ExpectationResult> results = evaluate(corner_scene, expectation, t);
        REQUIRE(results.size() == 1);
        CHECK_FALSE(results[0].passed);
        CHECK(results[0].detail.find("no collision of 'tri'") != std::string::npos);
    }
}

TEST_CASE("head-on: two hand-built discs meeting along the line of centres", "[expectations]") {
    const std::string expectation = R"([{"kind": "head-on", "a": "a", "b": "b", "atol": 1e-9}])";
    SECTION("as derived") {
        const std::vector<ExpectationResult> results =
            evaluate(head_on_scene, expectation, head_on_trajectory());
        INFO(listing(results));
        CHECK(results.size() == 5);
        CHECK(failures(results) == 0);
        CHECK(result_about(results, "impulse").expected == 4.5);
        CHECK(result_about(results, "'a' velocity along").expected == -0.5);
        CHECK(result_about(results, "'b' velocity along").expected == 1.5);
        CHECK(result_about(results, "'a' velocity across").expected == 1.0);
        CHECK(result_about(results, "'b' velocity across").expected == 1.0);
    }
    SECTION("each value just beyond the tolerance") {
        const std::pair<std::vector<std::size_t>, const char*> cases[] = {
            {{2, 4}, "'a' velocity along"},
            {{2, 10}, "'b' velocity along"},
            {{2, 5}, "'a' velocity across"},
            {{2, 11}, "'b' velocity across"},
        };
        for (const auto& [where, what] : cases) {
            INFO(what);
            Trajectory t = head_on_trajectory();
            t.frames[where[0]][where[1]] += 2e-9;
            require_only_failure(evaluate(head_on_scene, expectation, t), what);
        }
        Trajectory t = head_on_trajectory();
        t.events[0].impulse -= 2e-9;
        require_only_failure(evaluate(head_on_scene, expectation, t), "impulse");
    }
    SECTION("the bodies may be named in either order in the event") {
        Trajectory t = head_on_trajectory();
        std::swap(t.events[0].a, t.events[0].b);
        CHECK(failures(evaluate(head_on_scene, expectation, t)) == 0);
    }
    SECTION("no collision between them") {
        Trajectory t = head_on_trajectory();
        t.events.clear();
        const std::vector<ExpectationResult> results = evaluate(head_on_scene, expectation, t);
        REQUIRE(results.size() == 1);
        CHECK(results[0].detail == "the run has no collision between 'a' and 'b'");
        // Nothing was measured: no "expected 0, got 0" that reads like a pass.
        CHECK_FALSE(results[0].numeric);
        CHECK(impulse::harness::expectation_message(results[0]).find("expected") ==
              std::string::npos);
    }
}

TEST_CASE("a velocity that is zero by the physics is judged against the speeds going in",
          "[expectations]") {
    // Equal masses, e = 1: vA' = (4 + 0 - 4) / 2 = 0 and vB' = 4. A run leaves
    // a rounding residue in vA'; rtol alone must not hold it to an exact zero.
    const std::string scene = R"({
        "schema": "impulse/scene@1", "name": "swap", "gravity": [0, 0], "restitution": 1,
        "dt": 0.25, "duration": 1,
        "bodies": [
            {"name": "a", "shape": {"circle": 0.5}, "mass": 1, "velocity": [4, 0]},
            {"name": "b", "shape": {"circle": 0.5}, "mass": 1, "position": [2, 0]}]})";
    const std::string expectation = R"([{"kind": "head-on", "a": "a", "b": "b", "rtol": 1e-12}])";
    auto run_with_residue = [](double residue) {
        return trajectory_of({"a", "b"},
                             {{0.00, 0, 0, 0, 4, 0, 0, 2, 0, 0, 0, 0, 0},
                              {0.50, 1, 0, 0, residue, 0, 0, 3, 0, 0, 4, 0, 0}},
                             {make_event(0.25, "a", "b", 1.5, 0, -1, 0, 4.0, -4.0, 4.0)});
    };
    // The scale of vA' is (|MA vA| + |MB vB| + MB e |vA - vB|) / (MA + MB) = 4:
    // 4e-12 is allowed.
    CHECK(failures(evaluate(scene, expectation, run_with_residue(1e-16))) == 0);
    CHECK(failures(evaluate(scene, expectation, run_with_residue(3e-12))) == 0);
    require_only_failure(evaluate(scene, expectation, run_with_residue(5e-12)),
                         "'a' velocity along");
}

TEST_CASE("conserved: momentum, angular momentum and energy of a hand-built collision",
          "[expectations]") {
    const std::string expectation =
        R"([{"kind": "conserved", "quantities": ["momentum", "angular_momentum", "energy"],
             "atol": 1e-9}])";
    SECTION("as derived") {
        const std::vector<ExpectationResult> results =
            evaluate(conserved_scene, expectation, conserved_trajectory());
        INFO(listing(results));
        REQUIRE(results.size() == 3);
        CHECK(failures(results) == 0);
        CHECK(result_about(results, "conserved angular momentum").expected == 6.75);
        CHECK(result_about(results, "conserved energy").expected == 10.75);
        const double p = result_about(results, "conserved momentum").expected;
        CHECK(p == 4.0); // both components are 4
    }
    SECTION("a's spin off by 2e-8 moves L by I_a * 2e-8 = 2.5e-9, and E by nothing visible") {
        // I_a = 1 * 0.5^2 / 2 = 0.125; the energy moves by 0.125 * (2e-8)^2 / 2.
        Trajectory t = conserved_trajectory();
        t.frames[2][6] = 2e-8;
        const std::vector<ExpectationResult> results = evaluate(conserved_scene, expectation, t);
        require_only_failure(results, "conserved angular momentum");
        const ExpectationResult& l = result_about(results, "conserved angular momentum");
        CHECK(l.what == "conserved angular momentum, furthest from t = 0 at t = 0.5 s");
        CHECK(l.expected == 6.75);
        CHECK(std::abs(l.actual - (6.75 + 2.5e-9)) <= 1e-15);
    }
    SECTION("a's vx off by 1.5e-9 moves P.x by 1.5e-9, L by -0.5 * 1.5e-9, E by -2 * 1.5e-9") {
        Trajectory t = conserved_trajectory();
        t.frames[2][4] += 1.5e-9; // at t = 0.5 a is at (0.5, 0.5) moving (-2, 1)
        const std::vector<ExpectationResult> results = evaluate(conserved_scene, expectation, t);
        INFO(listing(results));
        CHECK(failures(results) == 2);
        const ExpectationResult& p = result_about(results, "conserved momentum");
        CHECK_FALSE(p.passed);
        CHECK(p.what == "conserved momentum (x), furthest from t = 0 at t = 0.5 s");
        CHECK(result_about(results, "conserved angular momentum").passed);
        CHECK_FALSE(result_about(results, "conserved energy").passed);
    }
    SECTION("relative tolerance is taken of the terms, for totals that are zero") {
        // Scale of P at t = 0: 1 * |(4, 1)| + 3 * |(0, 1)| = sqrt(17) + 3 = 7.123...;
        // rtol 1e-10 allows 7.1e-10, so a P.y drift of 3 * 2e-10 = 6e-10 passes
        // and 3 * 3e-10 = 9e-10 fails.
        const std::string relative =
            R"([{"kind": "conserved", "quantities": ["momentum"], "rtol": 1e-10}])";
        Trajectory t = conserved_trajectory();
        t.frames[1][11] += 2e-10;
        CHECK(failures(evaluate(conserved_scene, relative, t)) == 0);
        t.frames[1][11] += 1e-10;
        require_only_failure(evaluate(conserved_scene, relative, t), "conserved momentum (y)");
    }
}

TEST_CASE("energy-non-increasing on a hand-built bounce", "[expectations]") {
    const std::string expectation = R"([{"kind": "energy-non-increasing", "atol": 1e-9}])";
    // The hand-built motion is exact free flight, as verlet integrates it; the
    // scene's default, explicit Euler, is allowed its own gain (below).
    std::string exact_scene = drop_scene;
    const std::string dt = R"("dt": 0.25)";
    exact_scene.replace(exact_scene.find(dt), dt.size(),
                        R"("solver": {"integrator": "verlet"}, "dt": 0.25)");
    SECTION("as derived: 12, 12, 6, 6, 4.5, 4.125") {
        const std::vector<ExpectationResult> results =
            evaluate(exact_scene, expectation, drop_trajectory());
        INFO(listing(results));
        REQUIRE(results.size() == 1);
        CHECK(results[0].passed);
    }
    SECTION("a rise of 8 * 1e-10 = 0.8e-9 at the apex passes, 8 * 2e-10 = 1.6e-9 fails") {
        Trajectory t = drop_trajectory();
        t.frames[3][2] += 1e-10; // y at t = 0.75; E = v^2 / 2 + 8 y
        CHECK(failures(evaluate(exact_scene, expectation, t)) == 0);
        t.frames[3][2] += 1e-10;
        const std::vector<ExpectationResult> results = evaluate(exact_scene, expectation, t);
        require_only_failure(results, "energy non-increasing");
        CHECK(results[0].what == "energy non-increasing, largest rise at t = 0.75 s");
        CHECK(results[0].expected == 6.0);
        CHECK(std::abs(results[0].actual - 6.0 - 1.6e-9) <= 1e-14);
    }
    SECTION("an allowance past the largest double allows any rise, as asked") {
        // atol + rtol x 12 J overflows; a rise of 8 J is within "any".
        Trajectory t = drop_trajectory();
        t.frames[3][2] += 1.0;
        const std::vector<ExpectationResult> results = evaluate(
            exact_scene, R"([{"kind": "energy-non-increasing", "atol": 1e308, "rtol": 1e308}])", t);
        INFO(listing(results));
        CHECK(failures(results) == 0);
    }
    SECTION("explicit Euler may gain m g^2 h^2 / 2 = 1 * 64 * 0.0625 / 2 = 2 J a step, no more") {
        // Under explicit Euler the ball flies on its start-of-step velocity:
        // 8 y may rise by 2 J in the step to t = 0.75 (dy = 0.25), not by
        // 2 J + 2e-9 (dy = 0.25 + 2.5e-10, past atol 1e-9).
        Trajectory t = drop_trajectory();
        t.frames[3][2] += 0.25;
        CHECK(failures(evaluate(drop_scene, expectation, t)) == 0);
        CHECK(failures(evaluate(exact_scene, expectation, t)) == 1);
        t.frames[3][2] += 2.5e-10;
        const std::vector<ExpectationResult> results = evaluate(drop_scene, expectation, t);
        require_only_failure(results, "energy non-increasing");
        CHECK(results[0].detail.find("explicit Euler's sum m g^2 h^2 / 2 of 2") !=
              std::string::npos);
    }
}

TEST_CASE("event: literal values of one collision", "[expectations]") {
    // The second bounce of the drop: t = 1, j = 3, vn -2 -> 1, at (0, 0), normal (0, 1).
    const std::string expectation =
        R"([{"kind": "event", "index": 1, "a": "ball", "b": "ground", "t": 1.0, "impulse": 3,
             "vn_before": -2, "vn_after": 1, "point": [0, 0], "normal": [0, 1],
             "atol": 1e-9}])";
    SECTION("as given") {
        const std::vector<ExpectationResult> results =
            evaluate(drop_scene, expectation, drop_trajectory());
        INFO(listing(results));
        CHECK(results.size() == 10);
        CHECK(failures(results) == 0);
        CHECK(result_about(results, "normal.y").what == "event 1: normal.y");
    }
    SECTION("each number just beyond the tolerance") {
        for (const char* field : {"t", "impulse", "vn_before", "vn_after", "point.x", "point.y",
                                  "normal.x", "normal.y"}) {
            INFO(field);
            Trajectory t = drop_trajectory();
            TrajectoryEvent& e = t.events[1];
            const std::string f = field;
            double& value = f == "t"           ? e.t
                            : f == "impulse"   ? e.impulse
                            : f == "vn_before" ? e.vn_before
                            : f == "vn_after"  ? e.vn_after
                            : f == "point.x"   ? e.point[0]
                            : f == "point.y"   ? e.point[1]
                            : f == "normal.x"  ? e.normal[0]
                                               : e.normal[1];
            value += 2e-9;
            require_only_failure(evaluate(drop_scene, expectation, t), "event 1: " + f);
        }
    }
    SECTION("another body") {
        Trajectory t = drop_trajectory();
        t.events[1].a = "ground";
        t.events[1].b = "ball";
        const std::vector<ExpectationResult> results = evaluate(drop_scene, expectation, t);
        CHECK(failures(results) == 2);
        CHECK(result_about(results, "event 1: a").detail == "expected 'ball', got 'ground'");
    }
    SECTION("an event the run does not have") {
        const std::vector<ExpectationResult> results =
            evaluate(drop_scene, R"([{"kind": "event", "index": 3, "t": 1.4, "atol": 1e-9}])",
                     drop_trajectory());
        REQUIRE(results.size() == 1);
        CHECK_FALSE(results[0].passed);
        CHECK(results[0].detail == "the run has 3 collision events, so there is no event 3");
    }
}

TEST_CASE("state: literal values of one body at one frame", "[expectations]") {
    // The apex after the first bounce: t = 0.75, y = 0.5 + 2 * 0.25 - 4 * 0.25^2 = 0.75, vy = 0.
    const std::string expectation =
        R"([{"kind": "state", "body": "ball", "t": 0.75, "x": 0, "y": 0.75, "angle": 0,
             "vx": 0, "vy": 0, "omega": 0, "atol": 1e-9}])";
    SECTION("as given") {
        const std::vector<ExpectationResult> results =
            evaluate(drop_scene, expectation, drop_trajectory());
        INFO(listing(results));
        CHECK(results.size() == 6);
        CHECK(failures(results) == 0);
        CHECK(result_about(results, ": y").what == "state of 'ball' at t = 0.75 s: y");
    }
    SECTION("each value just beyond the tolerance") {
        const char* fields[] = {"x", "y", "angle", "vx", "vy", "omega"};
        for (std::size_t i = 0; i < 6; ++i) {
            INFO(fields[i]);
            Trajectory t = drop_trajectory();
            t.frames[3][1 + i] -= 2e-9;
            require_only_failure(evaluate(drop_scene, expectation, t),
                                 std::string(": ") + fields[i]);
        }
    }
    SECTION("a frame time that is off by rounding still finds its frame") {
        Trajectory t = drop_trajectory();
        t.frames[3][0] = std::nextafter(0.75, 1.0);
        CHECK(failures(evaluate(drop_scene, expectation, t)) == 0);
    }
    SECTION("a run whose frames miss the time") {
        // A run at dt = 0.5 (a command-line override) has no frame at 0.75.
        const Trajectory t = trajectory_of(
            {"ball"},
            {{0.0, 0, 1.5, 0, 0, 0, 0}, {0.5, 0, 0.5, 0, 0, 2, 0}, {1.0, 0, 0.5, 0, 0, 1, 0}}, {});
        const std::vector<ExpectationResult> results = evaluate(drop_scene, expectation, t);
        REQUIRE(results.size() == 1);
        CHECK_FALSE(results[0].passed);
        CHECK(results[0].detail ==
              "the run has no frame at t = 0.75 s (its frames are 0.5 s apart and end at 1 s)");
    }
}

TEST_CASE("expectations are evaluated in order, each result naming its path", "[expectations]") {
    const std::vector<ExpectationResult> results =
        evaluate(drop_scene,
                 R"([{"kind": "energy-non-increasing", "atol": 1e-9},
                     {"kind": "drop", "body": "ball", "impacts": 1, "rtol": 1e-12}])",
                 drop_trajectory());
    REQUIRE(results.size() == 4);
    CHECK(results[0].path == "expectations[0]");
    for (std::size_t i = 1; i < 4; ++i) {
        CHECK(results[i].path == "expectations[1]");
    }
    CHECK(failures(results) == 0);
    CHECK(evaluate_expectations(parse_scene(drop_scene, test_file), drop_trajectory()).empty());
}
