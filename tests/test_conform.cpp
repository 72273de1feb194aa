// `impulse conform` (docs/conformance.md): the rule that picks the
// conformance scenes, and the scorecard through the real binary: a correct
// engine passes, a subtly wrong one fails naming the expectation, a refusing
// one is skipped, a crashing one is an error row.
//
// Tests that run an external engine are tagged [conform-external], hidden,
// until the engine protocol's runner lands (run_engine throws "cannot be run
// yet" for external engines before it); then the tag becomes [conform].
#include "conformance.h"
#include "scene.h"
#include "support/files.h"
#include "support/outcome.h"
#include "support/tool.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;
using impulse::harness::conformance_exclusion;
using impulse::harness::ExpectationResult;
using impulse::harness::parse_scene;
using impulse::harness::shipped_scenes;
using namespace impulse::test;

namespace {

const std::string source_scenes = std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes";
const std::string scenes_env = "IMPULSE_SCENES_DIR=" + source_scenes;

// The conformance scenes as the library's rule picks them from the source tree.
std::vector<std::string> conformance_names() {
    std::vector<std::string> names;
    for (const auto& s : shipped_scenes(source_scenes)) {
        if (!s.exclusion) {
            names.push_back(s.scene.name);
        }
    }
    return names;
}

// The names listed between the markers of docs/conformance.md's scene list.
std::vector<std::string> documented_names() {
    const std::string doc = slurp(std::string(IMPULSE_SOURCE_DIR) + "/docs/conformance.md");
    const std::size_t begin = doc.find("<!-- conformance scenes -->");
    const std::size_t end = doc.find("<!-- end of conformance scenes -->");
    REQUIRE(begin != std::string::npos);
    REQUIRE(end != std::string::npos);
    std::vector<std::string> names;
    for (std::size_t at = doc.find("\n- `", begin); at < end; at = doc.find("\n- `", at + 1)) {
        const std::size_t from = at + 4;
        names.push_back(doc.substr(from, doc.find('`', from) - from));
    }
    return names;
}

std::string scene_with(const std::string& solver, const std::string& gravity,
                       const std::string& expectations) {
    return R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1,
               "gravity": )" +
           gravity + R"(, "restitution": 0.5, "solver": {)" + solver + R"(},
               "bodies": [{"name": "ground", "static": true, "shape": {"box": [5, 0.5]},
                           "position": [0, -0.5]},
                          {"name": "ball", "shape": {"circle": 0.5}, "position": [0, 1.5]}],
               "expectations": [)" +
           expectations + "]}";
}

const std::string drop = R"({"kind": "drop", "body": "ball", "impacts": 1, "atol": 1e-9})";
const std::string energy = R"({"kind": "energy-non-increasing", "atol": 1e-9})";

bool excluded(const std::string& text, const std::vector<std::string>& keys) {
    return conformance_exclusion(parse_scene(text, "t.json"), keys).has_value();
}

// drop-box's own parameters: a box of half-height hy resting its bottom h0
// above the ground's top, dropped from rest under g, restitution e.
struct DropBox {
    double g = 0.0, e = 0.0, h0 = 0.0, dt = 0.0;
};

DropBox drop_box() {
    const nlohmann::json file = nlohmann::json::parse(slurp(source_scenes + "/drop-box.json"));
    const auto& ground = file["bodies"][0];
    const auto& box = file["bodies"][1];
    const double ground_top =
        ground["position"][1].get<double>() + ground["shape"]["box"][1].get<double>();
    DropBox d;
    d.g = -file["gravity"][1].get<double>();
    d.e = file["restitution"];
    d.dt = file["dt"];
    d.h0 = box["position"][1].get<double>() - box["shape"]["box"][1].get<double>() - ground_top;
    return d;
}

// A fake engine in Python: replays `recorded` (a trajectory of the scene
// named `scene`) with every velocity after the first collision multiplied by
// `factor` (the frames' vx, vy and omega after it, every event's vn_after and
// the later events' vn_before), and refuses every other scene (exit 3).
std::string replay_engine(const TempDir& dir) {
    const fs::path script = dir.dir / "replay.py";
    spit(script, R"(import json, sys
recorded, scene_name, factor = sys.argv[1], sys.argv[2], float(sys.argv[3])
scene = json.load(open(sys.argv[-1]))
if scene["name"] != scene_name:
    sys.stderr.write("only " + scene_name + " is recorded\n")
    sys.exit(3)
run = json.load(open(recorded))
run.pop("digest")  # the harness never trusts an engine's digest; numbers change here
first_impact = run["events"][0]["t"]
for frame in run["frames"]:
    if frame[0] > first_impact:
        for c, name in enumerate(run["columns"]):
            if name.endswith((".vx", ".vy", ".omega")):
                frame[c] *= factor
for k, event in enumerate(run["events"]):
    event["vn_after"] *= factor
    if k > 0:
        event["vn_before"] *= factor
json.dump(run, sys.stdout)
)");
    return "python3 " + script.string();
}

// The scorecard of a run with --json FILE, parsed.
nlohmann::json scorecard(const fs::path& file) {
    return nlohmann::json::parse(slurp(file));
}

const nlohmann::json& scene_in(const nlohmann::json& card, const std::string& name) {
    for (const auto& s : card["scenes"]) {
        if (s["name"] == name) {
            return s;
        }
    }
    FAIL("no scene " << name << " in the scorecard");
    return card;
}

const nlohmann::json& result_in(const nlohmann::json& engine, const std::string& check) {
    for (const auto& r : engine["results"]) {
        if (r["check"] == check) {
            return r;
        }
    }
    FAIL("no check " << check << " for engine " << engine["engine"]);
    return engine;
}

// XML that Python's parser takes, or the test fails.
void require_well_formed_xml(const fs::path& file) {
    const std::string command =
        "python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' " +
        file.string();
    REQUIRE(std::system(command.c_str()) == 0);
}

std::size_t count_of(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
        ++n;
    }
    return n;
}

} // namespace

TEST_CASE("The conformance rule: physics in, a model or an integrator's error out", "[conform]") {
    SECTION("an exact answer under an integrator exact in free flight is physics") {
        CHECK_FALSE(
            excluded(scene_with(R"("integrator": "verlet")", "[0, -9.81]", drop), {"integrator"}));
        CHECK_FALSE(excluded(
            scene_with(R"("integrator": "rk4", "ccd": true, "toi": "secant")", "[0, -9.81]", drop),
            {"integrator", "ccd", "toi"}));
    }
    SECTION("naming a collision-model key is a choice of model, even its default value") {
        for (const char* key : impulse::harness::model_solver_keys) {
            const std::string k = key;
            const std::string value = k == "contacts"        ? R"("single")"
                                      : k == "vertex_normal" ? R"("reference-face")"
                                      : k == "stepping"      ? R"("world")"
                                                             : "false";
            const std::string solver = R"("integrator": "verlet", ")" + k + "\": " + value;
            CHECK(excluded(scene_with(solver, "[0, -9.81]", drop), {"integrator", k}));
        }
    }
    SECTION("an integrator that is not exact in free flight decides the answer under gravity") {
        CHECK(excluded(scene_with(R"("integrator": "symplectic-euler")", "[0, -9.81]", energy),
                       {"integrator"}));
        CHECK(
            excluded(scene_with(R"("integrator": "euler")", "[0, -9.81]", energy), {"integrator"}));
        // The seed's default integrator is euler: leaving it unnamed changes nothing.
        CHECK(excluded(scene_with("", "[0, -9.81]", energy), {}));
    }
    SECTION("without gravity every integrator moves bodies exactly") {
        CHECK_FALSE(excluded(scene_with(R"("integrator": "symplectic-euler")", "[0, 0]", energy),
                             {"integrator"}));
    }
    SECTION("a scene without expectations has nothing to score") {
        const std::string text = R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01,
            "duration": 1, "solver": {"integrator": "verlet"},
            "bodies": [{"name": "ball", "shape": {"circle": 0.5}}]})";
        CHECK(excluded(text, {"integrator"}));
    }
}

TEST_CASE("The documented conformance scenes are the ones the rule picks", "[conform]") {
    const std::vector<std::string> picked = conformance_names();
    CHECK(picked == documented_names());
    // The rule keeps the exact answers the issue names and drops the model studies.
    for (const char* in : {"drop-box", "drop-circle", "tilted-box", "head-on", "bullet"}) {
        CHECK(std::find(picked.begin(), picked.end(), in) != picked.end());
    }
    for (const char* out : {"cradle", "drop-flat", "stack", "gas-circles", "integrator-euler"}) {
        CHECK(std::find(picked.begin(), picked.end(), out) == picked.end());
    }
}

TEST_CASE("check_key drops what the run decides, so engines' checks line up", "[conform]") {
    ExpectationResult r;
    r.what = "conserved momentum (x), furthest from t = 0 at t = 1.25 s";
    CHECK(impulse::harness::check_key(r) == "conserved momentum");
    r.what = "drop of 'box': impact 2 time";
    CHECK(impulse::harness::check_key(r) == "drop of 'box': impact 2 time");
}

TEST_CASE("conform --engine impulse passes every conformance scene and names each", "[conform]") {
    const Outcome o =
        run_tool({"conform", "--engine", "impulse", "--with", "box2d-2.4"}, {scenes_env});
    INFO(o.out << o.err);
    REQUIRE(o.exited);
    CHECK(o.exit_code == 0);
    const std::vector<std::string> names = conformance_names();
    REQUIRE(names.size() >= 10);
    for (const std::string& name : names) {
        CHECK(o.out.find("\n" + name + " (") != std::string::npos);
        CHECK(o.out.find("ok      " + name) != std::string::npos);
    }
    CHECK(o.out.find("cradle") == std::string::npos);
    CHECK(o.out.find(std::to_string(names.size()) + " scenes: " + std::to_string(names.size()) +
                     " passed, 0 failed") != std::string::npos);
    // Fits 100 columns: every line of the tables (sentences aside).
    std::size_t start = 0;
    for (std::size_t end = o.out.find('\n'); end != std::string::npos;
         start = end + 1, end = o.out.find('\n', start)) {
        const std::string line = o.out.substr(start, end - start);
        if (line.find("error:") == std::string::npos && line.find("(") == std::string::npos &&
            line.find("unsupported by") == std::string::npos) {
            CHECK(line.size() <= 100);
        }
    }
}

TEST_CASE("conform --json: the documented fields, and drop-box's exact answers from physics",
          "[conform]") {
    const TempDir dir;
    const fs::path json = dir.dir / "card.json";
    const Outcome o = run_tool({"conform", "--engine", "impulse", "--with", "box2d-2.4", "drop-box",
                                "--json", json.string()},
                               {scenes_env});
    INFO(o.out << o.err);
    REQUIRE(o.exit_code == 0);
    const nlohmann::json card = scorecard(json);
    CHECK(card["schema"] == "impulse/conformance@1");
    CHECK(card["engine"] == "impulse");
    CHECK(card["passed"] == true);
    CHECK(card["counts"]["scenes"] == 1);
    CHECK(card["counts"]["passed"] == 1);
    const nlohmann::json& scene = scene_in(card, "drop-box");
    const nlohmann::json& mine = scene["engines"][0];
    CHECK(mine["engine"] == "impulse");
    CHECK(mine["outcome"] == "passed");
    CHECK(mine["checks"] == mine["results"].size());
    CHECK(mine["within"] == mine["checks"]);

    const auto [g, e, h0, dt] = drop_box();
    const double t1 = std::sqrt(2.0 * h0 / g);
    const double v1 = g * t1;
    double t = t1;
    for (int n = 1; n <= 3; ++n) {
        const std::string impact = "drop of 'box': impact " + std::to_string(n);
        const double rebound = std::pow(e, n) * v1;
        const double apex = std::pow(e, 2 * n) * h0;
        for (const auto& [check, exact] :
             {std::pair{impact + " time", t}, std::pair{impact + " rebound speed", rebound},
              std::pair{impact + " apex gap", apex}}) {
            const nlohmann::json& r = result_in(mine, check);
            INFO(check);
            CHECK(r["path"] == "expectations[0]");
            CHECK(r["exact"].get<double>() == Approx(exact).epsilon(1e-12));
            const double value = r["value"], off = std::abs(value - r["exact"].get<double>());
            CHECK(r["abs_error"].get<double>() == off);
            CHECK(r["rel_error"].get<double>() == off / std::abs(r["exact"].get<double>()));
            // The scene's allowance: atol 1e-12 + rtol 1e-9 x |exact|.
            CHECK(r["allowed"].get<double>() == Approx(1e-12 + 1e-9 * exact).epsilon(1e-12));
            CHECK(r["within"] == true);
            CHECK(r["detail"] == "");
        }
        t += 2.0 * rebound / g; // the flight to the next impact
    }
}

TEST_CASE("conform --junit with the impulse engine: well formed, one testcase per check",
          "[conform]") {
    const TempDir dir;
    const fs::path xml = dir.dir / "conform.xml", json = dir.dir / "card.json";
    const Outcome o = run_tool({"conform", "--engine", "impulse", "--no-box2d", "--junit",
                                xml.string(), "--json", json.string()},
                               {scenes_env});
    INFO(o.out << o.err);
    REQUIRE(o.exit_code == 0);
    require_well_formed_xml(xml);
    const std::string text = slurp(xml);
    const nlohmann::json card = scorecard(json);
    CHECK(count_of(text, "<testcase ") == card["counts"]["checks"].get<std::size_t>());
    CHECK(count_of(text, "<failure") == 0);
    CHECK(text.find("failures=\"0\" errors=\"0\" skipped=\"0\"") != std::string::npos);
}

TEST_CASE("conform's results do not depend on -j", "[conform]") {
    const Outcome one = run_tool(
        {"conform", "--engine", "impulse", "--with", "box2d-2.4", "-j", "1"}, {scenes_env});
    const Outcome two =
        run_tool({"conform", "--engine", "impulse", "--with", "box2d-2.4", "-j2"}, {scenes_env});
    CHECK(one.exit_code == 0);
    CHECK(one.out == two.out);
}

TEST_CASE("conform finds the shipped scenes: IMPULSE_SCENES_DIR, else the source tree",
          "[conform]") {
    const TempDir dir;
    const fs::path scenes = dir.dir / "scenes";
    spit(scenes / "drop-box.json", slurp(source_scenes + "/drop-box.json"));
    spit(scenes / "cradle.json", slurp(source_scenes + "/cradle.json"));
    const Outcome listed =
        run_tool({"conform", "--list"}, {"IMPULSE_SCENES_DIR=" + scenes.string()});
    CHECK(listed.exit_code == 0);
    CHECK(listed.out.find("  in   drop-box\n") != std::string::npos);
    CHECK(listed.out.find("  out  cradle") != std::string::npos);
    CHECK(listed.out.find("\"contacts\": \"simultaneous\"") != std::string::npos);
    CHECK(listed.out.find("1 of 2 scenes are in the conformance suite") != std::string::npos);

    const Outcome run = run_tool({"conform", "--engine", "impulse", "--with", "box2d-2.4"},
                                 {"IMPULSE_SCENES_DIR=" + scenes.string()});
    CHECK(run.exit_code == 0);
    CHECK(run.out.find("on 1 conformance scene from " + scenes.string()) != std::string::npos);

    // Unset (empty): a tool in a build tree falls back to its source tree.
    const Outcome fallback = run_tool({"conform", "--list"}, {"IMPULSE_SCENES_DIR="});
    CHECK(fallback.exit_code == 0);
    CHECK(fallback.out.find("shipped scenes in " + source_scenes + ":") != std::string::npos);
}

TEST_CASE("conform refuses bad input with one sentence and exit 2, running nothing", "[conform]") {
    const TempDir dir;
    auto refused = [&](const std::vector<std::string>& args, const std::string& env,
                       const std::string& words) {
        const Outcome o = run_tool(args, {env});
        INFO(o.out << o.err);
        CHECK(o.exit_code == 2);
        CHECK(o.err.find(words) != std::string::npos);
        CHECK(o.out.empty());
    };
    refused({"conform", "--engine", "nonesuch"}, scenes_env, "no engine is named 'nonesuch'");
    refused({"conform", "--engine", "impulse", "cradle"}, scenes_env,
            "'cradle' is not a conformance scene: its solver block chooses a collision model");
    refused({"conform", "--engine", "impulse", "nonesuch"}, scenes_env,
            "no shipped scene is named 'nonesuch'");
    refused({"conform", "--engine", "impulse", "-j", "0"}, scenes_env, "--jobs");
    refused({"conform", "--engine", "impulse", "--json", "/dev/null"}, scenes_env, "--json");
    refused({"conform", "--engine", "impulse", "--json", "-", "--junit", "-"}, scenes_env,
            "cannot both be standard output");
    refused({"conform", "--list"}, "IMPULSE_SCENES_DIR=" + (dir.dir / "missing").string(),
            "IMPULSE_SCENES_DIR");
    // A broken shipped scene is a broken installation, named.
    const fs::path scenes = dir.dir / "scenes";
    spit(scenes / "bad.json", "{\"schema\": \"impulse/scene@1\"");
    refused({"conform", "--engine", "impulse"}, "IMPULSE_SCENES_DIR=" + scenes.string(),
            "bad.json");
}

TEST_CASE("conform tells a subtly wrong engine from a correct one", "[conform-external]") {
    const TempDir dir;
    const fs::path recorded = dir.dir / "drop-box.json";
    REQUIRE(
        run_tool({"run", source_scenes + "/drop-box.json", "--out", recorded.string()}).exit_code ==
        0);
    const std::string engine = replay_engine(dir) + " " + recorded.string() + " drop-box";

    // The replay itself is faithful: unscaled, drop-box passes and the rest is skipped.
    const Outcome faithful =
        run_tool({"conform", "--engine", "replay", "--engine-command", engine + " 1", "--no-box2d"},
                 {scenes_env});
    INFO(faithful.out << faithful.err);
    CHECK(faithful.exit_code == 0);
    CHECK(faithful.out.find("ok      drop-box") != std::string::npos);

    // Every velocity after the first impact 10% low: the engine's
    // restitution is 0.9 e at the first impact, so its rebound speed and the
    // apex gap it leads to are wrong (the later impact times, replayed, are not).
    const TempDir out;
    const fs::path json = out.dir / "card.json";
    const Outcome wrong = run_tool({"conform", "--engine", "wrong", "--engine-command",
                                    engine + " 0.9", "--json", json.string()},
                                   {scenes_env});
    INFO(wrong.out << wrong.err);
    CHECK(wrong.exit_code == 1);
    CHECK(wrong.out.find("FAILED  drop-box") != std::string::npos);
    // Each failed check's reason right under its row; none under a passed one.
    const std::size_t section = wrong.out.find("\ndrop-box (");
    REQUIRE(section != std::string::npos);
    const std::string drop_box_rows = wrong.out.substr(section);
    CHECK(line_after(drop_box_rows, "impact 1 rebound speed ").rfind("NO: off by 0.35", 0) == 0);
    CHECK(line_after(drop_box_rows, "impact 1 apex gap ").rfind("NO: off by ", 0) == 0);
    CHECK(line_after(drop_box_rows, "impact 2 time ").rfind("impact 2 rebound speed ", 0) == 0);
    CHECK(wrong.out.find("skipped drop-circle ") != std::string::npos);
    CHECK(count_of(wrong.out, "\n  skipped ") == conformance_names().size() - 1);
    CHECK(wrong.out.find("unsupported by wrong: only drop-box is recorded") != std::string::npos);
    const nlohmann::json card = scorecard(json);
    CHECK(card["passed"] == false);
    CHECK(card["counts"]["failed"] == 1);
    const nlohmann::json& scene = scene_in(card, "drop-box");
    // From physics: the rebound e sqrt(2 g h0), its apex e^2 h0, each times
    // the engine's error (0.9 and 0.81) within the recording's own 1e-9.
    const DropBox d = drop_box();
    const double rebound = d.e * std::sqrt(2.0 * d.g * d.h0), apex = d.e * d.e * d.h0;
    for (const auto& [check, exact, factor] :
         {std::tuple{"drop of 'box': impact 1 rebound speed", rebound, 0.9},
          std::tuple{"drop of 'box': impact 1 apex gap", apex, 0.81}}) {
        INFO(check);
        const nlohmann::json& r = result_in(scene["engines"][0], check);
        CHECK(r["within"] == false);
        CHECK(r["exact"].get<double>() == Approx(exact).epsilon(1e-12));
        CHECK(r["value"].get<double>() == Approx(factor * exact).epsilon(1e-8));
        CHECK(r["rel_error"].get<double>() == Approx(1.0 - factor).epsilon(1e-6));
        CHECK(r["detail"].get<std::string>().find("more than the") != std::string::npos);
    }
    // The references are still scored beside it, for scale.
    CHECK(scene["engines"][1]["engine"] == "impulse");
    CHECK(scene["engines"][1]["outcome"] == "passed");
}

TEST_CASE("conform skips what an engine refuses; refusing everything shows nothing",
          "[conform-external]") {
    const TempDir dir;
    const fs::path script = dir.dir / "refuse.py";
    spit(script, "import sys\nsys.stderr.write('no rigid bodies here\\n')\nsys.exit(3)\n");
    const fs::path xml = dir.dir / "conform.xml", json = dir.dir / "card.json";
    const Outcome o = run_tool({"conform", "--engine", "refuser", "--engine-command",
                                "python3 " + script.string(), "--no-box2d", "--junit", xml.string(),
                                "--json", json.string()},
                               {scenes_env});
    INFO(o.out << o.err);
    // Documented: an engine that ran no scene has shown nothing, exit 1.
    CHECK(o.exit_code == 1);
    const std::size_t n = conformance_names().size();
    CHECK(count_of(o.out, "\n  skipped ") == n);
    CHECK(o.out.find("unsupported by refuser: no rigid bodies here") != std::string::npos);
    const nlohmann::json card = scorecard(json);
    CHECK(card["counts"]["unsupported"] == n);
    CHECK(card["passed"] == false);
    require_well_formed_xml(xml);
    const std::string text = slurp(xml);
    CHECK(count_of(text, "<skipped message=\"unsupported by refuser: no rigid bodies here\"/>") ==
          n);
    CHECK(text.find("skipped=\"" + std::to_string(n) + "\"") != std::string::npos);
}

TEST_CASE("conform turns an engine's crash into that scene's error row and exit 2",
          "[conform-external]") {
    const TempDir dir;
    const fs::path recorded = dir.dir / "drop-box.json";
    REQUIRE(
        run_tool({"run", source_scenes + "/drop-box.json", "--out", recorded.string()}).exit_code ==
        0);
    // Crashes (exit 5) on head-on, replays drop-box, refuses the rest.
    const fs::path script = dir.dir / "crash.py";
    spit(script, "import json, sys, subprocess\n"
                 "if json.load(open(sys.argv[-1]))['name'] == 'head-on':\n"
                 "    sys.stderr.write('segmentation fault in the solver\\n')\n"
                 "    sys.exit(5)\n"
                 "sys.exit(subprocess.call(sys.argv[1:-1] + [sys.argv[-1]]))\n");
    const std::string engine = "python3 " + script.string() + " " + replay_engine(dir) + " " +
                               recorded.string() + " drop-box 1";
    const TempDir out;
    const fs::path xml = out.dir / "conform.xml";
    const Outcome o = run_tool({"conform", "--engine", "crasher", "--engine-command", engine,
                                "--no-box2d", "--junit", xml.string()},
                               {scenes_env});
    INFO(o.out << o.err);
    CHECK(o.exit_code == 2);
    CHECK(o.out.find("ERROR   head-on") != std::string::npos);
    CHECK(o.out.find("segmentation fault in the solver") != std::string::npos);
    // The other scenes were still scored.
    CHECK(o.out.find("ok      drop-box") != std::string::npos);
    require_well_formed_xml(xml);
    CHECK(count_of(slurp(xml), "<error ") == 1);
}
