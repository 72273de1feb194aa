// examples/engines/python-seed/engine.py, an engine outside this one, run as
// the harness runs it (docs/engine-protocol.md): python3 with a normalized
// scene as its argument, the trajectory on stdout. The scenes are written
// here by hand; the physics is checked against the exact answers of
// docs/physics.md (harness/scene/exact_answers.h) and conservation laws
// computed here, never against the engine's own earlier output.
#include "exact_answers.h"
#include "scene.h"
#include "support/files.h"
#include "support/program.h"
#include "support/tool.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

using impulse::harness::CornerImpact;
using impulse::harness::DropLadder;
using impulse::harness::HeadOn;
using impulse::harness::Scene;
using impulse::test::Outcome;
using impulse::test::TempDir;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const fs::path engine_script =
    fs::path(IMPULSE_SOURCE_DIR) / "examples" / "engines" / "python-seed" / "engine.py";

// python3 as CMake found it; CI installs it with scripts/setup. Missing, the
// tests fail saying so: an engine example nobody runs is not tested.
std::string python3() {
    const std::string found = IMPULSE_PYTHON3;
    INFO("no python3 at '" << found
                           << "' (where CMake found it, or NOTFOUND): "
                              "scripts/setup installs python3; then configure the build again");
    REQUIRE(fs::exists(found));
    return found;
}

// Runs `python3 SCRIPT SCENE` as the harness would, without a shell.
Outcome run_engine_script(const fs::path& script, const fs::path& scene) {
    return impulse::test::run_program({python3(), script.string(), scene.string()});
}

// A normalized scene (docs/engine-protocol.md): every key explicit, the
// solver at the seed's values until a test changes one.
json normalized_scene(const std::string& integrator, double e, double dt, double duration,
                      const json& gravity, const std::vector<json>& bodies) {
    return {{"schema", "impulse/scene@1"},
            {"name", "python-seed-test"},
            {"gravity", gravity},
            {"restitution", e},
            {"dt", dt},
            {"duration", duration},
            {"solver",
             {{"integrator", integrator},
              {"toi", "bisection"},
              {"toi_tolerance", 1e-12},
              {"contact_tolerance", 1e-9},
              {"contacts", "single"},
              {"stepping", "world"},
              {"vertex_normal", "reference-face"},
              {"ccd", false},
              {"resting", false}}},
            {"bodies", json(bodies)}};
}

// Static ground with its top face at y = 0.
json ground() {
    return {{"name", "ground"},
            {"static", true},
            {"shape", {{"box", {50.0, 0.5}}}},
            {"position", {0.0, -0.5}},
            {"angle", 0.0}};
}

json body(const std::string& name, const json& shape, const json& position, double angle,
          const json& velocity, double mass, double inertia) {
    return {{"name", name},
            {"static", false},
            {"shape", shape},
            {"position", position},
            {"angle", angle},
            {"velocity", velocity},
            {"angular_velocity", 0.0},
            {"mass", mass},
            {"inertia", inertia},
            {"rotation", true}};
}

// The scene as the harness reads it, for the exact answers of its parameters.
Scene harness_scene(const json& scene) {
    return impulse::harness::parse_scene(scene.dump(), "python-seed-test.json");
}

const impulse::harness::SceneBody& scene_body(const Scene& scene, const std::string& name) {
    for (const impulse::harness::SceneBody& b : scene.bodies) {
        if (b.name == name) {
            return b;
        }
    }
    FAIL("no body " << name);
    throw;
}

// Runs the engine at `script` on `scene` and returns its trajectory; the run
// must succeed.
json run_scene(const json& scene, const fs::path& script = engine_script) {
    const TempDir dir;
    const fs::path file = dir.dir / "scene.json";
    impulse::test::spit(file, scene.dump());
    const Outcome o = run_engine_script(script, file);
    INFO("stderr: " << o.err);
    REQUIRE(o.exited);
    REQUIRE(o.exit_code == 0);
    return json::parse(o.out);
}

std::vector<json> events_of(const json& trajectory, const std::string& name) {
    std::vector<json> out;
    for (const json& e : trajectory["events"]) {
        if (e["a"] == name || e["b"] == name) {
            out.push_back(e);
        }
    }
    return out;
}

// The first frame after time t, as the harness reads a state after an event.
const json& frame_after(const json& trajectory, double t) {
    for (const json& f : trajectory["frames"]) {
        if (f[0].get<double>() > t) {
            return f;
        }
    }
    FAIL("no frame after t = " << t);
    throw;
}

// A ball of radius 0.5 (mass 1.5, a disc's inertia) released at rest with
// its bottom h0 = 2 m above the ground, under rk4 at 1/30 s.
json drop_scene(double duration = 3.0) {
    const double m = 1.5, r = 0.5;
    return normalized_scene("rk4", 0.7, 1.0 / 30.0, duration, {0.0, -9.81},
                            {ground(), body("ball", {{"circle", r}}, {0.0, 2.0 + r}, 0.0,
                                            {0.0, 0.0}, m, m * r * r / 2.0)});
}

// The canonical drop-circle's tolerance: 1e-9 relative. The search resolves
// each impact at most contact_tolerance / v (1e-9 s for v >= 1 m/s) before
// the touch, far inside it.
constexpr double drop_rtol = 1e-9;

// How far each of the first `impacts` rebound speeds is from e^n v1,
// relative to e^n v1, at most.
double worst_rebound_error(const json& trajectory, const DropLadder& drop, int impacts) {
    const std::vector<json> hits = events_of(trajectory, "ball");
    REQUIRE(hits.size() >= static_cast<std::size_t>(impacts));
    double worst = 0.0;
    for (int n = 1; n <= impacts; ++n) {
        const double exact = drop.rebound_speed(n);
        const double speed = hits[static_cast<std::size_t>(n - 1)]["vn_after"].get<double>();
        worst = std::max(worst, std::abs(speed - exact) / exact);
    }
    return worst;
}

} // namespace

TEST_CASE("python-seed: a disc dropped with e = 0.7 under rk4 meets the drop ladder",
          "[python-seed]") {
    const json scene = drop_scene();
    const Scene s = harness_scene(scene);
    const DropLadder drop = *impulse::harness::drop_ladder(s, scene_body(s, "ball"));
    REQUIRE(drop.h0 == 2.0); // the gap the scene was built with
    const json trajectory = run_scene(scene);

    const std::vector<json> hits = events_of(trajectory, "ball");
    REQUIRE(hits.size() >= 5);
    for (int n = 1; n <= 5; ++n) {
        const json& hit = hits[static_cast<std::size_t>(n - 1)];
        INFO("impact " << n);
        CHECK(hit["a"] == "ball"); // the dynamic body is A, the normal points toward it: up
        CHECK(hit["normal"] == json({0.0, 1.0}));
        CHECK(hit["t"].get<double>() ==
              Approx(drop.impact_time(n)).epsilon(drop_rtol).margin(1e-12));
        CHECK(hit["vn_after"].get<double>() ==
              Approx(drop.rebound_speed(n)).epsilon(drop_rtol).margin(1e-12));
        // Eq. 3 at the point: what arrives at e^(n-1) v1 leaves at e times it.
        CHECK(-hit["vn_before"].get<double>() ==
              Approx(drop.rebound_speed(n - 1)).epsilon(drop_rtol).margin(1e-12));
    }
    CHECK(worst_rebound_error(trajectory, drop, 5) <= drop_rtol);
}

TEST_CASE("python-seed: frames at k dt for every dynamic body, in scene order", "[python-seed]") {
    // 0.3 / 0.1 is 2.9999999999999996: within 1e-9 of 3, so 3 steps; 0.25 / 0.1
    // is 2.5, rounded up to 3 steps. Two bodies around a static one, which has
    // no columns.
    for (const double duration : {0.3, 0.25}) {
        json scene = normalized_scene(
            "euler", 1.0, 0.1, duration, {0.0, -9.81},
            {body("left", {{"circle", 0.5}}, {-5.0, 0.0}, 0.0, {0.0, 0.0}, 1.0, 0.125), ground(),
             body("right", {{"box", {0.5, 0.5}}}, {5.0, 3.0}, 0.0, {0.0, 0.0}, 1.0, 1.0 / 6.0)});
        scene["bodies"][1]["position"] = json({0.0, -10.0});
        const json trajectory = run_scene(scene);
        CHECK(trajectory["schema"] == "impulse/trajectory@1");
        CHECK(trajectory["columns"] ==
              json({"t", "left.x", "left.y", "left.angle", "left.vx", "left.vy", "left.omega",
                    "right.x", "right.y", "right.angle", "right.vx", "right.vy", "right.omega"}));
        REQUIRE(trajectory["frames"].size() == 4);
        for (std::size_t k = 0; k < 4; ++k) {
            CHECK(trajectory["frames"][k][0].get<double>() == static_cast<double>(k) * 0.1);
        }
        CHECK(trajectory["events"].empty());
        CHECK(trajectory["cost"]["seconds"].get<double>() >= 0.0);
    }
}

TEST_CASE("python-seed: a head-on pair leaves with Eq. 9's velocities", "[python-seed]") {
    // Two free discs in zero gravity, 3 kg at +2 m/s and 1 kg at -1 m/s, e = 0.5,
    // their surfaces 1.5 m apart: they meet at t = 0.5 s.
    const json scene = normalized_scene(
        "symplectic-euler", 0.5, 1.0 / 60.0, 1.0, {0.0, 0.0},
        {body("heavy", {{"circle", 0.5}}, {0.0, 0.0}, 0.0, {2.0, 0.0}, 3.0, 0.375),
         body("light", {{"circle", 0.5}}, {2.5, 0.0}, 0.0, {-1.0, 0.0}, 1.0, 0.125)});
    const Scene s = harness_scene(scene);
    const HeadOn exact =
        impulse::harness::head_on(s, scene_body(s, "heavy"), scene_body(s, "light"));
    const json trajectory = run_scene(scene);

    REQUIRE(trajectory["events"].size() == 1);
    const json& hit = trajectory["events"][0];
    CHECK(hit["a"] == "heavy");
    CHECK(hit["normal"] == json({-1.0, 0.0})); // toward A, from B
    CHECK(hit["t"].get<double>() == Approx(0.5).epsilon(1e-9));
    CHECK(hit["impulse"].get<double>() == Approx(exact.j.value).epsilon(1e-12));
    CHECK(hit["vn_after"].get<double>() ==
          Approx(-0.5 * hit["vn_before"].get<double>()).epsilon(1e-12));
    const json& last = trajectory["frames"].back();
    CHECK(last[4].get<double>() == Approx(exact.va_after.value).epsilon(1e-12));
    CHECK(last[10].get<double>() == Approx(exact.vb_after.value).epsilon(1e-12));
    // Momentum: 3 * 2 + 1 * -1 before, the same after.
    CHECK(3.0 * last[4].get<double>() + last[10].get<double>() == Approx(5.0).epsilon(1e-12));
}

TEST_CASE("python-seed: a box landing on one corner meets the corner-impact answer",
          "[python-seed]") {
    // A 2 x 1 box of 2 kg, turned 0.3 rad, its lowest corner 1 m up; free to rotate.
    const double m = 2.0, a = 1.0, b = 0.5;
    const double inertia = m * (4.0 * a * a + 4.0 * b * b) / 12.0;
    const double lowest = a * std::sin(0.3) + b * std::cos(0.3); // centre above the corner
    const json scene =
        normalized_scene("verlet", 0.5, 1.0 / 60.0, 0.6, {0.0, -9.81},
                         {ground(), body("box", {{"box", {a, b}}}, {0.0, 1.0 + lowest}, 0.3,
                                         {0.0, 0.0}, m, inertia)});
    const Scene s = harness_scene(scene);
    const impulse::harness::SceneBody& box = scene_body(s, "box");
    const double h = *impulse::harness::gap_to_static_ground(s, box);
    REQUIRE(h == Approx(1.0).epsilon(1e-12));
    const CornerImpact exact = impulse::harness::corner_impact(s, box, h);
    const json trajectory = run_scene(scene);

    const std::vector<json> hits = events_of(trajectory, "box");
    REQUIRE(!hits.empty());
    const json& hit = hits.front();
    const double t_hit = hit["t"].get<double>();
    CHECK(t_hit == Approx(exact.t_hit).epsilon(1e-9));
    CHECK(hit["impulse"].get<double>() == Approx(exact.j).epsilon(1e-9));
    CHECK(hit["vn_before"].get<double>() == Approx(-exact.v).epsilon(1e-9));
    CHECK(hit["point"][0].get<double>() == Approx(exact.point_x).epsilon(1e-9));
    const json& after = frame_after(trajectory, t_hit);
    const double flight = after[0].get<double>() - t_hit;
    CHECK(after[4].get<double>() == Approx(0.0).margin(1e-12));
    CHECK(after[5].get<double>() == Approx(exact.vy_after - 9.81 * flight).epsilon(1e-9));
    CHECK(after[6].get<double>() == Approx(exact.w_after).epsilon(1e-9));
}

TEST_CASE("python-seed: a tilted box that does not rotate bounces by the drop ladder, unturned",
          "[python-seed]") {
    // "rotation": false is infinite inertia: Eq. 9 loses its rotational terms
    // (Eq. 6), so the box landing on a corner bounces like a point mass.
    json box = body("box", {{"box", {1.0, 0.5}}}, {0.0, 3.0}, 0.3, {0.0, 0.0}, 2.0, 0.0);
    box.erase("inertia");
    box["rotation"] = false;
    const json scene =
        normalized_scene("verlet", 0.5, 1.0 / 60.0, 2.0, {0.0, -9.81}, {ground(), box});
    const Scene s = harness_scene(scene);
    const DropLadder drop = *impulse::harness::drop_ladder(s, scene_body(s, "box"));
    const json trajectory = run_scene(scene);

    const std::vector<json> hits = events_of(trajectory, "box");
    REQUIRE(hits.size() >= 3);
    for (int n = 1; n <= 3; ++n) {
        const json& hit = hits[static_cast<std::size_t>(n - 1)];
        INFO("impact " << n);
        CHECK(hit["t"].get<double>() ==
              Approx(drop.impact_time(n)).epsilon(drop_rtol).margin(1e-12));
        CHECK(hit["vn_after"].get<double>() ==
              Approx(drop.rebound_speed(n)).epsilon(drop_rtol).margin(1e-12));
    }
    for (const json& f : trajectory["frames"]) {
        REQUIRE(f[3].get<double>() == 0.3);
        REQUIRE(f[6].get<double>() == 0.0);
    }
}

TEST_CASE("python-seed: with e = 1 under symplectic Euler energy stays within the "
          "integrator's loss",
          "[python-seed]") {
    // A tilted box bouncing on its corners, e = 1, dt = 1 ms, 2 s. Eq. 9 with
    // e = 1 conserves kinetic energy in every collision and the collision
    // moves nothing. A symplectic Euler sub-step of s under gravity g,
    // v' = v - g s, y' = y + s v', changes m v^2 / 2 + m g y by
    //   m (v' - v)(v' + v) / 2 + m g s v' = -m g s (v' + v) / 2 + m g s v' = -m g^2 s^2 / 2
    // exactly (spin and horizontal motion are uniform). The sub-steps up to t
    // sum to t and none is longer than h, so 0 <= E(0) - E(t) <= m g^2 h t / 2.
    const double m = 1.5, a = 0.5, b = 0.25, g = 9.81, h = 1e-3;
    const double inertia = m * (4.0 * a * a + 4.0 * b * b) / 12.0;
    const json scene = normalized_scene(
        "symplectic-euler", 1.0, h, 2.0, {0.0, -g},
        {ground(), body("box", {{"box", {a, b}}}, {0.0, 1.5}, 0.4, {0.5, 0.0}, m, inertia)});
    const json trajectory = run_scene(scene);
    REQUIRE(events_of(trajectory, "box").size() >= 3);

    const auto energy = [&](const json& f) {
        const double vx = f[4], vy = f[5], w = f[6], y = f[2];
        return m * (vx * vx + vy * vy) / 2.0 + inertia * w * w / 2.0 + m * g * y;
    };
    const double e0 = energy(trajectory["frames"][0]);
    const double rounding = 1e-10 * e0; // a few thousand steps of roundings of e0's size
    for (const json& f : trajectory["frames"]) {
        const double t = f[0], loss = e0 - energy(f);
        INFO("t = " << t << " loss " << loss);
        REQUIRE(loss >= -rounding);
        REQUIRE(loss <= m * g * g * h * t / 2.0 + rounding);
    }
}

TEST_CASE("python-seed: what the seed does not model is refused with exit 3 and one sentence",
          "[python-seed]") {
    struct Case {
        const char* key;
        json value;
    };
    const Case cases[] = {{"contacts", "simultaneous"},
                          {"resting", true},
                          {"ccd", true},
                          {"vertex_normal", "bisector"},
                          {"integrator", "leapfrog"}};
    for (const Case& c : cases) {
        json scene = drop_scene();
        scene["solver"][c.key] = c.value;
        const TempDir dir;
        impulse::test::spit(dir.dir / "scene.json", scene.dump());
        const Outcome o = run_engine_script(engine_script, dir.dir / "scene.json");
        INFO(c.key << ": " << o.err);
        CHECK(o.exit_code == 3);
        CHECK(o.out.empty());
        CHECK(o.err.find(std::string("solver.") + c.key) != std::string::npos);
        CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
    }
}

TEST_CASE("python-seed: secant search and local stepping run as the seed's bisection",
          "[python-seed]") {
    // Both find the same collision within the same two tolerances, so the
    // engine runs its bisection for them (README.md) and says so.
    json scene = drop_scene();
    const json seed = run_scene(scene);
    scene["solver"]["toi"] = "secant";
    scene["solver"]["stepping"] = "local";
    const json faster = run_scene(scene);
    CHECK(faster["frames"] == seed["frames"]);
    CHECK(faster["events"] == seed["events"]);
    CHECK(faster["solver"]["toi"] == "bisection");
}

TEST_CASE("python-seed: a scene it cannot read is exit 2 naming the file and the JSON path",
          "[python-seed]") {
    const TempDir dir;
    json scene = drop_scene();
    scene["bodies"][1].erase("mass");
    impulse::test::spit(dir.dir / "missing.json", scene.dump());
    impulse::test::spit(dir.dir / "broken.json", "{\"schema\": ");
    const Outcome missing = run_engine_script(engine_script, dir.dir / "missing.json");
    CHECK(missing.exit_code == 2);
    CHECK(missing.err.find("missing.json: bodies[1].mass is missing") != std::string::npos);
    const Outcome broken = run_engine_script(engine_script, dir.dir / "broken.json");
    CHECK(broken.exit_code == 2);
    CHECK(broken.err.find("broken.json") != std::string::npos);
    CHECK(broken.err.find("Traceback") == std::string::npos);
    CHECK(broken.out.empty());
}

TEST_CASE("python-seed: a number that is not finite is exit 1, never NaN in the output",
          "[python-seed]") {
    // 1.5e308 m/s for 10 s is past the largest double: x becomes infinite.
    const json scene = normalized_scene(
        "euler", 1.0, 10.0, 10.0, {0.0, -9.81},
        {body("fast", {{"circle", 0.5}}, {0.0, 0.0}, 0.0, {1.5e308, 0.0}, 1.0, 0.125)});
    const TempDir dir;
    impulse::test::spit(dir.dir / "scene.json", scene.dump());
    const Outcome o = run_engine_script(engine_script, dir.dir / "scene.json");
    INFO(o.err);
    CHECK(o.exit_code == 1);
    CHECK(o.out.empty());
    CHECK(o.err.find("not finite") != std::string::npos);
}

TEST_CASE("python-seed: an engine with its restitution subtly broken misses the drop ladder",
          "[python-seed]") {
    // The marked line of Eq. 9 with (1 + e) turned into (1 + 0.9 e): the
    // engine still runs and bounces, and only the exact answers show it. Its
    // bounces die out sooner (e = 0.63: every impact over by 2.81 s, which the
    // seed's loop cannot pass), so the run stops at 2.5 s, after 3 impacts of
    // either engine.
    const TempDir dir;
    const std::string marker = "# Eq. 9: j (tests/test_python_seed.cpp breaks this line)";
    std::string source = impulse::test::slurp(engine_script);
    const std::size_t line = source.find(marker);
    REQUIRE(line != std::string::npos);
    REQUIRE(source.find(marker, line + 1) == std::string::npos);
    const std::size_t start = source.rfind('\n', line) + 1;
    const std::size_t factor = source.find("(1.0 + e)", start);
    REQUIRE(factor < line);
    source.replace(factor, 9, "(1.0 + 0.9 * e)");
    const fs::path broken = dir.dir / "engine.py";
    impulse::test::spit(broken, source);

    const json scene = drop_scene(2.5);
    const Scene s = harness_scene(scene);
    const DropLadder drop = *impulse::harness::drop_ladder(s, scene_body(s, "ball"));
    CHECK(worst_rebound_error(run_scene(scene), drop, 3) <= drop_rtol);
    // 0.9 e instead of e: the first rebound is already 10% slow.
    const double broken_error = worst_rebound_error(run_scene(scene, broken), drop, 3);
    CHECK(broken_error > 0.09);
    CHECK(broken_error > 1e6 * drop_rtol);
}
