// Expectations a scene declares (harness/gate/expectations.h): every kind on small
// trajectories written by hand from the physics, passing as given and failing
// when one value moves just beyond its tolerance; then the exact answers of
// docs/physics.md against real runs of the engine.
//
// Every number here is derived in the comments beside it, never copied from a
// run.
#include "expectations.h"
#include "run.h"
#include "scene.h"
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

const std::string test_file = "scenes/test.json";

// ---------------------------------------------------------------- building blocks

int failures(const std::vector<ExpectationResult>& results) {
    int n = 0;
    for (const ExpectationResult& r : results) {
        n += r.passed ? 0 : 1;
    }
    return n;
}

// Every result, one per line, for INFO.
std::string listing(const std::vector<ExpectationResult>& results) {
    std::string out;
    for (const ExpectationResult& r : results) {
        out += (r.passed ? "  pass " : "  FAIL ") + r.path + " " + r.what + " (" + r.detail + ")\n";
    }
    return out;
}

// The one result whose `what` contains `text`.
const ExpectationResult& result_about(const std::vector<ExpectationResult>& results,
                                      const std::string& text) {
    const ExpectationResult* found = nullptr;
    for (const ExpectationResult& r : results) {
        if (r.what.find(text) != std::string::npos) {
            REQUIRE(found == nullptr);
            found = &r;
        }
    }
    INFO("no result about '" << text << "' in\n" << listing(results));
    REQUIRE(found != nullptr);
    return *found;
}

// Only the result about `text` fails.
void require_only_failure(const std::vector<ExpectationResult>& results, const std::string& text) {
    INFO(listing(results));
    CHECK(failures(results) == 1);
    CHECK_FALSE(result_about(results, text).passed);
    CHECK_FALSE(result_about(results, text).detail.empty());
}

std::string with_expectations(const std::string& scene, const std::string& expectations) {
    return scene.substr(0, scene.rfind('}')) + R"(, "expectations": )" + expectations + "}";
}

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

std::vector<ExpectationResult> evaluate(const std::string& scene, const std::string& expectations,
                                        const Trajectory& trajectory) {
    return evaluate_expectations(parse_scene(with_expectations(scene, expectations), test_file),
                                 trajectory);
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
    SECTION("as derived: 12, 12, 6, 6, 4.5, 4.125") {
        const std::vector<ExpectationResult> results =
            evaluate(drop_scene, expectation, drop_trajectory());
        INFO(listing(results));
        REQUIRE(results.size() == 1);
        CHECK(results[0].passed);
    }
    SECTION("a rise of 8 * 1e-10 = 0.8e-9 at the apex passes, 8 * 2e-10 = 1.6e-9 fails") {
        Trajectory t = drop_trajectory();
        t.frames[3][2] += 1e-10; // y at t = 0.75; E = v^2 / 2 + 8 y
        CHECK(failures(evaluate(drop_scene, expectation, t)) == 0);
        t.frames[3][2] += 1e-10;
        const std::vector<ExpectationResult> results = evaluate(drop_scene, expectation, t);
        require_only_failure(results, "energy non-increasing");
        CHECK(results[0].what == "energy non-increasing, largest rise at t = 0.75 s");
        CHECK(results[0].expected == 6.0);
        CHECK(std::abs(results[0].actual - 6.0 - 1.6e-9) <= 1e-14);
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

namespace {

// No gravity, e = 1. A static wall whose left face is x = 5; disc a (mass 1,
// r 0.5) from the origin at (4, 1); discs b and c (mass 2) on y = 3, 3 m
// apart, closing at 1 m/s each. Frames every 0.5 s:
//   b and c touch at t = 1.0 (their gap of 2 m closes at 2 m/s) and, equal
//   masses with e = 1, swap velocities: j = 2 * 2 * 2 * 2 / 4 = 4, n = (-1, 0)
//   from c toward b. Momentum passes between them; the total does not change.
//   a's right side reaches the wall at x = 4.5 / 4 = 1.125 s: n = (-1, 0)
//   toward a, j = 1 * (1 + 1) * 4 = 8, so a leaves at (-4, 1) and at t = 1.5
//   is at 4.5 - 4 * 0.375 = 3.
// P(0) = (4 + 2 - 2, 1) = (4, 1); P(1.5) = (-4 - 2 + 2, 1) = (-4, 1): the
// change (-8, 0) is the wall's j n. Scale at t = 0: |(4, 1)| + 2 + 2 =
// sqrt(17) + 4 = 8.123...; from t = 1.125 on, plus |j| = 8.
const std::string balance_scene = R"({
    "schema": "impulse/scene@1", "name": "balance", "gravity": [0, 0], "restitution": 1,
    "dt": 0.5, "duration": 1.5,
    "bodies": [
        {"name": "wall", "static": true, "shape": {"box": [0.5, 5]}, "position": [5.5, 0]},
        {"name": "a", "shape": {"circle": 0.5}, "mass": 1, "velocity": [4, 1]},
        {"name": "b", "shape": {"circle": 0.5}, "mass": 2, "position": [-1.5, 3],
         "velocity": [1, 0]},
        {"name": "c", "shape": {"circle": 0.5}, "mass": 2, "position": [1.5, 3],
         "velocity": [-1, 0]}]})";

const TrajectoryEvent pair_event = make_event(1.0, "b", "c", 0, 3, -1, 0, 4.0, -2.0, 2.0);
const TrajectoryEvent wall_event = make_event(1.125, "a", "wall", 5, 1.125, -1, 0, 8.0, -4.0, 4.0);

Trajectory balance_trajectory(std::vector<TrajectoryEvent> events = {pair_event, wall_event}) {
    return trajectory_of(
        {"a", "b", "c"},
        {{0.0, 0, 0.0, 0, 4, 1, 0, -1.5, 3, 0, 1, 0, 0, 1.5, 3, 0, -1, 0, 0},
         {0.5, 2, 0.5, 0, 4, 1, 0, -1.0, 3, 0, 1, 0, 0, 1.0, 3, 0, -1, 0, 0},
         // The pair's event is at this frame's time, so the frame shows its result.
         {1.0, 4, 1.0, 0, 4, 1, 0, -0.5, 3, 0, -1, 0, 0, 0.5, 3, 0, 1, 0, 0},
         {1.5, 3, 1.5, 0, -4, 1, 0, -1.0, 3, 0, -1, 0, 0, 1.0, 3, 0, 1, 0, 0}},
        std::move(events));
}

// A disc (mass 1, r 0.5) rattling between two walls with faces at x = +-1.5,
// at 4 m/s from the origin: it hits the right wall at t = 0.25 and the left at
// 0.75, each time j = 8 and its velocity flips. Frames every 0.25 s fall on
// the events: P = 4, -4, -4, 4, 4, and the sums of j n up to each are 0, -8,
// -8, 0, 0.
const std::string rattle_scene = R"({
    "schema": "impulse/scene@1", "name": "rattle", "gravity": [0, 0], "restitution": 1,
    "dt": 0.25, "duration": 1,
    "bodies": [
        {"name": "left", "static": true, "shape": {"box": [0.5, 2]}, "position": [-2, 0]},
        {"name": "right", "static": true, "shape": {"box": [0.5, 2]}, "position": [2, 0]},
        {"name": "a", "shape": {"circle": 0.5}, "mass": 1, "velocity": [4, 0]}]})";

Trajectory rattle_trajectory(std::vector<TrajectoryEvent> events) {
    return trajectory_of({"a"},
                         {{0.00, 0, 0, 0, 4, 0, 0},
                          {0.25, 1, 0, 0, -4, 0, 0},
                          {0.50, 0, 0, 0, -4, 0, 0},
                          {0.75, -1, 0, 0, 4, 0, 0},
                          {1.00, 0, 0, 0, 4, 0, 0}},
                         std::move(events));
}

const std::string balance = R"([{"kind": "momentum-balance", "rtol": 1e-10}])";

} // namespace

TEST_CASE("momentum-balance: the walls' impulses account for the change", "[expectations]") {
    SECTION("as derived; the pair's own event changes nothing") {
        const std::vector<ExpectationResult> results =
            evaluate(balance_scene, balance, balance_trajectory());
        INFO(listing(results));
        REQUIRE(results.size() == 1);
        CHECK(results[0].passed);
        CHECK(results[0].path == "expectations[0]");
        CHECK(results[0].what.rfind("momentum balance (", 0) == 0);
    }
    SECTION("the static body may be a: the impulse on b is -j n") {
        const TrajectoryEvent flipped =
            make_event(1.125, "wall", "a", 5, 1.125, 1, 0, 8.0, -4.0, 4.0);
        CHECK(failures(evaluate(balance_scene, balance,
                                balance_trajectory({pair_event, flipped}))) == 0);
    }
    SECTION("without the wall's event, momentum is off by 8 after it") {
        const std::vector<ExpectationResult> results =
            evaluate(balance_scene, balance, balance_trajectory({pair_event}));
        require_only_failure(results, "momentum balance");
        CHECK(results[0].what == "momentum balance (x), nearest to its tolerance at t = 1.5 s");
        CHECK(results[0].expected == 4.0);
        CHECK(results[0].actual == -4.0);
    }
    SECTION("the pair's event counted as a wall's would be off by 4") {
        // Make c static in the scene's eyes by naming the wall instead: then the
        // event gives b j n = (-4, 0) that its partner does not return.
        const TrajectoryEvent as_wall = make_event(1.0, "b", "wall", 0, 3, -1, 0, 4.0, -2.0, 2.0);
        require_only_failure(
            evaluate(balance_scene, balance, balance_trajectory({as_wall, wall_event})),
            "momentum balance (x)");
    }
    SECTION("rtol is of |m v| at t = 0 plus the |j| given so far") {
        // At t = 0.5 the scale is sqrt(17) + 4 = 8.12: rtol 1e-10 allows 8.1e-10.
        // At t = 1.5 it is 16.12: 1.6e-9 allowed.
        Trajectory t = balance_trajectory();
        t.frames[3][4] += 1.5e-9; // a's vx at t = 1.5
        CHECK(failures(evaluate(balance_scene, balance, t)) == 0);
        t.frames[3][4] += 0.2e-9;
        require_only_failure(evaluate(balance_scene, balance, t), "at t = 1.5 s");
        Trajectory early = balance_trajectory();
        early.frames[1][11] += 1.5e-9; // b's vy at t = 0.5: P.y moves by 2 * 1.5e-9
        const std::vector<ExpectationResult> results = evaluate(balance_scene, balance, early);
        require_only_failure(results, "momentum balance (y)");
        CHECK(results[0].what == "momentum balance (y), nearest to its tolerance at t = 0.5 s");
        CHECK(std::abs(results[0].actual - (1.0 + 3e-9)) <= 1e-15);
    }
    SECTION("a NaN fails") {
        Trajectory t = balance_trajectory();
        t.frames[2][5] = std::nan("");
        require_only_failure(evaluate(balance_scene, balance, t), "at t = 1 s");
    }
    SECTION("an event naming a body the scene lacks") {
        const TrajectoryEvent ghost =
            make_event(1.125, "a", "ghost", 5, 1.125, -1, 0, 8.0, -4.0, 4.0);
        const std::vector<ExpectationResult> results =
            evaluate(balance_scene, balance, balance_trajectory({pair_event, ghost}));
        INFO(listing(results));
        REQUIRE(results.size() == 1);
        CHECK_FALSE(results[0].passed);
        CHECK(results[0].detail == "event 1 names 'ghost', which is not a body of the scene");
    }
}

TEST_CASE("momentum-balance counts an event at a frame's own time, in time order",
          "[expectations]") {
    const TrajectoryEvent right = make_event(0.25, "a", "right", 1.5, 0, -1, 0, 8.0, -4.0, 4.0);
    const TrajectoryEvent left = make_event(0.75, "a", "left", -1.5, 0, 1, 0, 8.0, -4.0, 4.0);
    CHECK(failures(evaluate(rattle_scene, balance, rattle_trajectory({right, left}))) == 0);
    // Recorded out of order, as a run whose bodies keep their own clocks may.
    CHECK(failures(evaluate(rattle_scene, balance, rattle_trajectory({left, right}))) == 0);
    // Without the first, the frame at its time is already off by 8.
    const std::vector<ExpectationResult> results =
        evaluate(rattle_scene, balance, rattle_trajectory({left}));
    require_only_failure(results, "momentum balance (x)");
    CHECK(results[0].what == "momentum balance (x), nearest to its tolerance at t = 0.25 s");
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

// ---------------------------------------------------------------- real runs

namespace {

// docs/physics.md, drop: impact n at t1 + sum_{k=1..n-1} 2 e^k v1 / g.
double drop_impact_time(double h0, double g, double e, int n) {
    const double v1 = std::sqrt(2.0 * g * h0);
    double t = v1 / g;
    double ek = 1.0;
    for (int k = 1; k < n; ++k) {
        ek *= e;
        t += 2.0 * ek * v1 / g;
    }
    return t;
}

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
        const double last = drop_impact_time(c.h0, c.g, c.e, c.impacts);
        const double next = drop_impact_time(c.h0, c.g, c.e, c.impacts + 1);
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
    };
    const Case cases[] = {
        {1.0, 1.0, 3.0, 0.0, 1.0, true, "symplectic-euler", 1.0 / 60.0}, // vA' = 0 exactly
        {1.0, 3.0, 4.0, -1.0, 0.5, false, "rk4", 1.0 / 30.0},
        {5.0, 0.2, 0.7, -2.5, 0.9, true, "verlet", 1.0 / 60.0},
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
        const double end = 0.5 * (drop_impact_time(h0, g, e, 3) + drop_impact_time(h0, g, e, 4));
        const std::vector<ExpectationResult> results = run_and_evaluate(
            scene_json(g, e, 1.0 / 60.0, end, "verlet", {ground(), ball}, expectation));
        INFO(listing(results));
        CHECK(results.size() == 1);
        CHECK(failures(results) == 0);
    }
    SECTION("explicit Euler gains m g^2 h^2 / 2 per step of free fall, and is caught") {
        // x' = x + h v, v' = v - g h: v'^2 / 2 + g x' = v^2 / 2 + g x + g^2 h^2 / 2.
        const double mass = 1.5, g = 9.81, dt = 1.0 / 60.0;
        const Json ball = {
            {"name", "ball"}, {"shape", {{"circle", 0.5}}}, {"mass", mass}, {"position", {0, 2.5}}};
        const std::vector<ExpectationResult> results =
            run_and_evaluate(scene_json(g, 0.5, dt, 0.5, "euler", {ground(), ball}, expectation));
        REQUIRE(results.size() == 1);
        CHECK_FALSE(results[0].passed);
        const double rise = results[0].actual - results[0].expected;
        const double per_step = mass * g * g * dt * dt / 2.0;
        CHECK(std::abs(rise - per_step) <= 1e-9 * per_step);
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
