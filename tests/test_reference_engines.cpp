// The reference engines of references/ (Box2D v3 from box2d3-wasm 5.2.0 and
// Rapier2D from rapier2d-deterministic-compat 0.20.0, run by Node) through
// the real binary, as a user runs them: `impulse run --engine-command 'node
// references/ENGINE/engine.mjs' SCENE --out T.json` and `impulse bless` /
// `impulse check` of a small project naming both. The scenes are written
// here; every number asserted comes from the physics of the scene or from
// the engines' documented models (docs/references.md), never from their
// earlier output. Without node or references/node_modules the tests fail
// saying so: scripts/setup installs both, and CI runs it.
#include "exact_answers.h"
#include "scene.h"
#include "support/files.h"
#include "support/outcome.h"
#include "support/program.h"
#include "support/tool.h"
#include "support/tool_in_folder.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;
using nlohmann::json;

namespace {

const fs::path references = fs::path(IMPULSE_SOURCE_DIR) / "references";

// float's epsilon: both engines compute in single precision.
constexpr double eps_f = std::numeric_limits<float>::epsilon();

struct Reference {
    const char* name;        // as the project file names it
    const char* script;      // under references/
    const char* substeps;    // the solver-block key that records the sub-steps
    const char* npm_package; // what must be in references/node_modules
};

const Reference box2d_v3{"box2d-v3", "box2d-v3/engine.mjs", "substeps", "box2d3-wasm"};
const Reference rapier{"rapier", "rapier/engine.mjs", "num_solver_iterations",
                       "@dimforge/rapier2d-deterministic-compat"};

// `node` as CMake found it and the engine's npm package: missing, the test
// fails with the command that installs them.
std::string node_command(const Reference& engine, const std::string& options = "") {
    const std::string node = IMPULSE_NODE;
    INFO("no node at '" << node
                        << "' (where CMake found it, or NOTFOUND): scripts/setup "
                           "installs Debian's nodejs and npm; then configure again");
    REQUIRE(fs::exists(node));
    const fs::path package = references / "node_modules" / engine.npm_package / "package.json";
    INFO("no " << package.string() << ": scripts/setup runs npm ci in references/");
    REQUIRE(fs::exists(package));
    return node + " " + (references / engine.script).string() + (options.empty() ? "" : " ") +
           options;
}

json solver_block() {
    return {{"integrator", "verlet"},
            {"toi", "bisection"},
            {"toi_tolerance", 1e-12},
            {"contact_tolerance", 1e-9}};
}

json circle(const std::string& name, double r, double x, double y, double vx, double vy,
            double mass) {
    return {{"name", name},       {"shape", {{"circle", r}}},
            {"position", {x, y}}, {"velocity", {vx, vy}},
            {"mass", mass},       {"rotation", false}};
}

json scene(const std::string& name, double g, double e, double dt, double duration,
           const std::vector<json>& bodies) {
    return {{"schema", "impulse/scene@1"},
            {"name", name},
            {"gravity", {0.0, g}},
            {"restitution", e},
            {"dt", dt},
            {"duration", duration},
            {"solver", solver_block()},
            {"bodies", bodies}};
}

// `impulse run SCENE --engine-command COMMAND --out T.json`: the trajectory,
// validated by the harness and written in its canonical form.
json run_in(const std::string& command, const fs::path& scene_file, const TempDir& temp) {
    const fs::path out = temp.dir / (scene_file.stem().string() + ".trajectory.json");
    const Outcome run = run_tool({"run", scene_file.string(), "--engine-command", command, "--out",
                                  out.string(), "--quiet"});
    require_exit(run, 0);
    return json::parse(slurp(out));
}

// `node SCRIPT SCENE` run directly, as the harness would but without it:
// for scenes the harness's own loader would refuse before any engine runs.
Outcome run_node(const std::string& script, const fs::path& scene_file) {
    return impulse::test::run_program({IMPULSE_NODE, script, scene_file.string()});
}

std::size_t column(const json& trajectory, const std::string& name) {
    const json& columns = trajectory["columns"];
    const auto at = std::find(columns.begin(), columns.end(), name);
    REQUIRE(at != columns.end());
    return static_cast<std::size_t>(at - columns.begin());
}

} // namespace

// Both engines integrate each sub-step h = dt / S with symplectic Euler
// (v += g h, then y += v h): from rest after n = k S sub-steps, v = g n h
// and y = y0 + g h^2 n (n + 1) / 2. One sub-step instead of four moves y by
// 3 g dt^2 k / 8 (3 cm at k = 30), far beyond single precision's rounding.
TEST_CASE("Box2D v3 and Rapier: free fall is sub-stepped symplectic Euler to single precision, "
          "and --substeps N is the number of sub-steps",
          "[references]") {
    const TempDir temp;
    const double g = -9.81, dt = 1.0 / 60.0, y0 = 10.0, vx = 1.0;
    const fs::path file = temp.dir / "fall.json";
    spit(file,
         scene("fall", g, 1.0, dt, 0.5, {circle("ball", 0.25, 0.0, y0, vx, 0.0, 2.0)}).dump());
    for (const Reference* engine : {&box2d_v3, &rapier}) {
        for (const int substeps : {4, 1}) {
            INFO(engine->name << " with " << substeps << " sub-steps");
            const std::string options =
                substeps == 4 ? "" : "--substeps " + std::to_string(substeps); // 4: the default
            const json t = run_in(node_command(*engine, options), file, temp);
            CHECK(t["solver"][engine->substeps] == substeps);
            CHECK(t["solver"]["precision"] == "single");
            const std::size_t x = column(t, "ball.x"), y = column(t, "ball.y"),
                              vy = column(t, "ball.vy");
            const double h = dt / substeps;
            REQUIRE(t["frames"].size() == 31);
            for (std::size_t k = 0; k < t["frames"].size(); ++k) {
                const json& f = t["frames"][k];
                const double n = static_cast<double>(k) * substeps;
                // Rounding: each sub-step rounds v and y once in float.
                const double bound = (n + 1.0) * eps_f * 16.0;
                CHECK(std::abs(f[vy].get<double>() - g * n * h) <= bound);
                CHECK(std::abs(f[y].get<double>() - (y0 + g * h * h * n * (n + 1.0) / 2.0)) <=
                      bound);
                CHECK(std::abs(f[x].get<double>() - vx * n * h) <= bound);
            }
        }
    }
}

// Two free circles, no gravity, e = 0.8: both engines apply restitution to
// the relative velocity the pair had at the start of the step, which without
// gravity is the approach velocity, so the exit velocities are the exact
// head-on answer (docs/physics.md) to single precision; momentum is
// conserved in every frame; the event is stamped with the end of the step
// that resolved it, within one step after the contact (at t = 0.75 s).
TEST_CASE("Box2D v3 and Rapier: a head-on conserves momentum and leaves with the exact velocities",
          "[references]") {
    const TempDir temp;
    const double e = 0.8, ma = 1.0, mb = 3.0, ua = 3.0, ub = -1.0, dt = 0.01;
    const fs::path file = temp.dir / "head-on.json";
    spit(file, scene("head-on", 0.0, e, dt, 1.0,
                     {circle("left", 0.5, -2.0, 0.0, ua, 0.0, ma),
                      circle("right", 0.5, 2.0, 0.0, ub, 0.0, mb)})
                   .dump());
    const double p = ma * ua + mb * ub;
    const double va = (p - mb * e * (ua - ub)) / (ma + mb);
    const double vb = (p + ma * e * (ua - ub)) / (ma + mb);
    const double t_contact = (4.0 - 1.0) / (ua - ub); // the gap of 3 m closing at 4 m/s
    for (const Reference* engine : {&box2d_v3, &rapier}) {
        INFO(engine->name);
        const json t = run_in(node_command(*engine), file, temp);
        const std::size_t a = column(t, "left.vx"), b = column(t, "right.vx");
        for (const json& f : t["frames"]) {
            CHECK(std::abs(ma * f[a].get<double>() + mb * f[b].get<double>() - p) <=
                  8.0 * eps_f * (ma * std::abs(ua) + mb * std::abs(ub)));
        }
        const json& last = t["frames"].back();
        CHECK(last[a].get<double>() == Approx(va).epsilon(8.0 * eps_f));
        CHECK(last[b].get<double>() == Approx(vb).epsilon(8.0 * eps_f));
        REQUIRE(t["events"].size() == 1);
        const json& event = t["events"][0];
        CHECK(event["a"] == "left");
        CHECK(event["normal"][0].get<double>() == Approx(-1.0)); // toward a, out of b
        CHECK(event["t"].get<double>() >= t_contact - 1e-9);
        CHECK(event["t"].get<double>() <= t_contact + dt + 1e-9);
        // a receives +j n: j = MA (va - ua) / n_x
        CHECK(event["impulse"].get<double>() == Approx(ma * (ua - va)).epsilon(8.0 * eps_f));
        CHECK(event["vn_after"].get<double>() ==
              Approx(-e * event["vn_before"].get<double>()).epsilon(8.0 * eps_f));
    }
}

// drop-box (the canonical scene) under each engine. The model
// (docs/references.md): the impact is resolved in the step the box reaches
// the ground, stamped with its end, and the box leaves at e times the speed
// it had at the start of that step. Sub-stepped symplectic Euler falls at
// most one sub-step h ahead of the exact motion and never arrives faster, so
// no bounce rises above the exact apex e^(2n) h0, and bounce n can fall
// short of the exact rebound speed by at most s_n = e (s_(n-1) + g (dt + h))
// (each impact's start-of-step speed and each flight's sub-step lose at most
// g dt and g h, scaled by e at every later impact): apex n >= (e^n v1 -
// s_n)^2 / 2g. Each impact can start its rebound at most dt late, and each
// short rebound shortens the next flight by at most 2 s / g, so impact n
// lies in [t_n - h - sum 2 s_i / g (i < n), t_n + n dt].
// The apex is read from the first frame after the impact, y + vy^2 / 2g,
// less the box's half height (the ground's top is y = 0), where the box may
// still overlap the ground by Box2D's linear slop, 0.005 m.
TEST_CASE("Box2D v3 and Rapier: drop-box's impacts and apex heights within the bounds of their "
          "model, every rebound e times the speed at the start of its step",
          "[references]") {
    // Without its expectations, which hold the impulse engine to 1e-9: run
    // would exit 1 on them.
    const TempDir temp;
    const fs::path file = temp.dir / "drop-box.json";
    json canonical =
        json::parse(slurp(fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes" / "drop-box.json"));
    canonical.erase("expectations");
    spit(file, canonical.dump());
    const impulse::harness::Scene s = impulse::harness::load_scene(file.string());
    const impulse::harness::DropLadder drop = *impulse::harness::drop_ladder(s, s.bodies[1]);
    const double g = -s.gravity.y, dt = s.dt, h = dt / 4.0, e = s.restitution;
    const double half_height = 0.5, slop = 0.005;
    for (const Reference* engine : {&box2d_v3, &rapier}) {
        INFO(engine->name);
        const json t = run_in(node_command(*engine), file, temp);
        const std::size_t y = column(t, "box.y"), vy = column(t, "box.vy");
        const json& events = t["events"];
        REQUIRE(events.size() >= 3);
        double shortfall = 0.0; // s_n, the bound on e^n v1 - rebound speed n
        double early = h;       // how much earlier than t_n impact n can come
        for (int n = 1; n <= 3; ++n) {
            INFO("impact " << n);
            const json& event = events[static_cast<std::size_t>(n - 1)];
            const double t_n = event["t"].get<double>();
            CHECK(t_n >= drop.impact_time(n) - early);
            CHECK(t_n <= drop.impact_time(n) + n * dt + 1e-9);
            CHECK(event["vn_after"].get<double>() ==
                  Approx(-e * event["vn_before"].get<double>()).epsilon(8.0 * eps_f));
            const auto k = static_cast<std::size_t>(std::llround(t_n / dt));
            const json& after = t["frames"][k];
            const double speed = after[vy].get<double>();
            const double apex = after[y].get<double>() - half_height + speed * speed / (2.0 * g);
            shortfall = e * (shortfall + g * (dt + h));
            early += 2.0 * shortfall / g;
            const double lowest = drop.rebound_speed(n) - shortfall;
            CHECK(apex <= drop.apex_gap(n) * (1.0 + 8.0 * eps_f));
            CHECK(apex >= lowest * lowest / (2.0 * g) - slop);
        }
    }
}

// A project naming both engines: bless writes a golden per engine, check
// runs them again and every golden matches (the engines are deterministic
// and the harness writes no cost into a golden); a polygon of 10 vertices,
// more than Box2D v3's 8, is Box2D's SKIPPED row with its sentence and a
// golden for Rapier.
TEST_CASE("Box2D v3 and Rapier behind the gate: bless, check, and a polygon Box2D v3 cannot take "
          "skipped",
          "[references]") {
    const TempDir temp;
    const fs::path dir = temp.dir / "project";
    const std::string box2d = node_command(box2d_v3), rapier_command = node_command(rapier);
    auto words = [](const std::string& command) {
        json out = json::array();
        for (std::size_t at = 0; at < command.size();) {
            const std::size_t end = std::min(command.find(' ', at), command.size());
            out.push_back(command.substr(at, end - at));
            at = end + 1;
        }
        return out;
    };
    spit(dir / "impulse.json", json{{"schema", "impulse/project@1"},
                                    {"scenes", {"scenes"}},
                                    {"engines",
                                     {{{"name", "box2d-v3"}, {"command", words(box2d)}},
                                      {{"name", "rapier"}, {"command", words(rapier_command)}}}}}
                                   .dump());
    spit(dir / "scenes" / "pair.json", scene("pair", 0.0, 1.0, 0.01, 1.0,
                                             {circle("left", 0.5, -2.0, 0.0, 2.0, 0.0, 1.0),
                                              circle("right", 0.5, 2.0, 0.0, -2.0, 0.0, 1.0)})
                                           .dump());
    json decagon = json::array();
    for (int i = 0; i < 10; ++i) {
        const double angle = 2.0 * std::acos(-1.0) * i / 10.0;
        decagon.push_back({0.5 * std::cos(angle), 0.5 * std::sin(angle)});
    }
    json ten = scene("decagon", -9.81, 0.5, 0.01, 1.0, {});
    ten["bodies"] = {{{"name", "ground"},
                      {"static", true},
                      {"shape", {{"box", {5.0, 0.5}}}},
                      {"position", {0.0, -0.5}}},
                     {{"name", "stone"},
                      {"shape", {{"polygon", decagon}}},
                      {"position", {0.0, 1.0}},
                      {"mass", 1.0}}};
    spit(dir / "scenes" / "decagon.json", ten.dump());

    const Outcome blessed = run_tool_in(dir, {"bless"});
    INFO(blessed.out << blessed.err);
    CHECK(fs::is_regular_file(dir / "goldens" / "box2d-v3" / "pair.json"));
    CHECK(fs::is_regular_file(dir / "goldens" / "rapier" / "pair.json"));
    CHECK(fs::is_regular_file(dir / "goldens" / "rapier" / "decagon.json"));
    CHECK_FALSE(fs::exists(dir / "goldens" / "box2d-v3" / "decagon.json"));
    const Outcome checked = run_tool_in(dir, {"check"});
    INFO(checked.out << checked.err);
    require_exit(checked, 0);
    CHECK(has(checked.out, "SKIPPED"));
    CHECK(has(checked.out, "Box2D v3 takes at most 8 polygon vertices, this one has 10"));
    CHECK(has(slurp(dir / "goldens" / "box2d-v3" / "pair.json"),
              "\"engine\": \"box2d 3.2-pre 3a4f0da8 (box2d3-wasm 5.2.0, compat)\""));
    CHECK(has(slurp(dir / "goldens" / "rapier" / "pair.json"), "\"num_solver_iterations\": 4"));
}

// A scene the harness would never write (a shape kind of another format)
// given to each program directly: exit 3 and one line on standard error
// naming the JSON path, as the protocol asks of a scene an engine does not
// model.
TEST_CASE("Box2D v3 and Rapier refuse an unknown shape kind with exit 3 and one sentence",
          "[references]") {
    const TempDir temp;
    const fs::path file = temp.dir / "capsule.json";
    json s =
        scene("capsule", -9.81, 1.0, 0.01, 1.0, {circle("ball", 0.25, 0.0, 1.0, 0.0, 0.0, 1.0)});
    s["solver"].update({{"contacts", "single"},
                        {"stepping", "world"},
                        {"vertex_normal", "reference-face"},
                        {"ccd", false},
                        {"resting", false}});
    for (json& b : s["bodies"]) {
        b.update({{"static", false}, {"angle", 0.0}, {"angular_velocity", 0.0}});
    }
    s["bodies"][0]["shape"] = {{"capsule", {0.5, 0.25}}};
    spit(file, s.dump());
    for (const Reference* engine : {&box2d_v3, &rapier}) {
        INFO(engine->name);
        const std::string command = node_command(*engine);
        const std::string script = command.substr(command.find(' ') + 1);
        const Outcome o = run_node(script, file);
        CHECK(o.exit_code == 3);
        CHECK(o.out.empty());
        CHECK(has(o.err, "bodies[0].shape: the shape kind \"capsule\" is not one"));
        CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
    }
}
