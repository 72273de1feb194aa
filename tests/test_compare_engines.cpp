// `impulse compare` (harness/cli/compare.cpp) through the real binary: one
// column per engine beside the exact answer, the reference registry
// (harness/engines/reference_engines.h) found through IMPULSE_REFERENCES_DIR
// with fake Node references written here (one replays a Box2D run the test
// made, one refuses every scene), a requested reference that is missing, the
// trajectories of --out, JUnit, and conform's reference columns. The numbers
// asserted come from drop-box's physics (h0 = 1 m, g = 9.81, e = 0.8) or from
// the runs the test itself prepared.
#include "reference_engines.h"
#include "support/files.h"
#include "support/tool.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

const std::string root = IMPULSE_SOURCE_DIR;
const std::string scenes_env = "IMPULSE_SCENES_DIR=" + root + "/harness/scenes";
constexpr double g = 9.81, h0 = 1.0, dt = 1.0 / 60.0;

// A references folder as npm ci leaves it, with `box2d3` and `rapier` as the
// two programs (JavaScript run by node); node_modules holds only the package
// files the registry looks for.
struct FakeReferences {
    TempDir dir;
    FakeReferences(const std::string& box2d3, const std::string& rapier) {
        for (const char* package : {"box2d3-wasm", "@dimforge/rapier2d-deterministic-compat"}) {
            fs::create_directories(dir.dir / "node_modules" / package);
            spit(dir.dir / "node_modules" / package / "package.json", "{}\n");
        }
        fs::create_directories(dir.dir / "box2d-v3");
        fs::create_directories(dir.dir / "rapier");
        spit(dir.dir / "box2d-v3" / "engine.mjs", box2d3);
        spit(dir.dir / "rapier" / "engine.mjs", rapier);
    }
    std::string env() const { return "IMPULSE_REFERENCES_DIR=" + dir.dir.string(); }
};

// A program that writes the trajectory at `path` whatever scene it is given.
std::string replay(const fs::path& path) {
    return "import { readFileSync } from 'node:fs';\n"
           "process.stdout.write(readFileSync(" +
           nlohmann::json(path.string()).dump() + "));\n";
}

const std::string refuse = "process.stderr.write('no rapier here\\n');\nprocess.exit(3);\n";

// Box2D 2.4.1's run of drop-box, as `impulse run --engine box2d` writes it
// (exit 1: Box2D misses the scene's exact expectations; the run is written).
fs::path box2d_run(const TempDir& dir) {
    const fs::path out = dir.dir / "box2d-run.json";
    const Outcome o =
        run_tool({"run", "--engine", "box2d", "drop-box", "--root", root, "--out", out.string()});
    INFO(o.err);
    REQUIRE(fs::exists(out));
    return out;
}

nlohmann::json json_of(const Outcome& o) {
    INFO(o.out << o.err);
    return nlohmann::json::parse(o.out);
}

const nlohmann::json& row_named(const nlohmann::json& scene, const std::string& name) {
    for (const nlohmann::json& row : scene["rows"]) {
        if (row["name"] == name) {
            return row;
        }
    }
    FAIL("no row " << name);
    return scene;
}

} // namespace

TEST_CASE("compare --with box2d-2.4: the JSON has one column per engine and every setting",
          "[compare-engines]") {
    const Outcome o = run_tool(
        {"compare", "drop-box", "head-on", "--root", root, "--with", "box2d-2.4", "--json"});
    CHECK(o.exit_code == 0);
    const nlohmann::json doc = json_of(o);
    CHECK(doc["schema"] == "impulse/engine-comparison@1");
    CHECK(doc["engine"] == "impulse");
    REQUIRE(doc["references"].size() == 1);
    CHECK(doc["references"][0]["name"] == "box2d-2.4");
    CHECK(doc["skipped_references"].empty()); // --with names them: nothing else is listed
    const nlohmann::json& drop = doc["scenes"][0];
    REQUIRE(drop["engines"].size() == 2);
    CHECK(drop["engines"][0]["name"] == "impulse");
    CHECK(drop["engines"][0]["settings"]["integrator"] == "symplectic-euler");
    const nlohmann::json& box2d = drop["engines"][1];
    CHECK(box2d["name"] == "box2d-2.4");
    // The fairness settings, from the scene: friction off, restitution its e.
    const nlohmann::json scene =
        nlohmann::json::parse(slurp(root + "/harness/scenes/drop-box.json"));
    CHECK(box2d["settings"]["friction"] == 0);
    CHECK(box2d["settings"]["restitution"] == scene["restitution"]);
    CHECK(box2d["settings"]["dt"] == scene["dt"]);
    for (const nlohmann::json& row : drop["rows"]) {
        CHECK(row["values"].size() == 2);
        CHECK(row["values"].contains("impulse"));
        CHECK(row["values"].contains("box2d-2.4"));
        CHECK(row["within"].is_boolean());
    }
    // The first impact of a drop from h0: t1 = sqrt(2 h0 / g); a stepping
    // engine sees it at the end of the step it falls in, or one later.
    const nlohmann::json& t1 = row_named(drop, "impact 1 time of 'box' (s)");
    const double exact = std::sqrt(2.0 * h0 / g);
    CHECK(t1["exact"].get<double>() == Approx(exact).epsilon(1e-12));
    const double box2d_t1 = t1["values"]["box2d-2.4"];
    CHECK(box2d_t1 >= exact);
    CHECK(box2d_t1 <= exact + 2.0 * dt);
    CHECK(t1["errors"]["box2d-2.4"].get<double>() == Approx(box2d_t1 - exact));
    // head-on has no exact impact time: null, and so is each error.
    const nlohmann::json& head_on = doc["scenes"][1]["rows"][0];
    CHECK(head_on["exact"].is_null());
    CHECK(head_on["errors"]["box2d-2.4"].is_null());
}

TEST_CASE("compare's first line says an engine other than impulse is only given the integrator",
          "[compare-engines]") {
    // impulse integrates with what it is given; another engine receives it as
    // solver.integrator and may have none to choose (chipmunk has one).
    const Outcome own = run_tool({"compare", "head-on", "--root", root, "--with", "box2d-2.4"});
    CHECK(own.out.rfind("compare: 1 scene; impulse (symplectic-euler, Box2D's integrator) beside "
                        "box2d-2.4\n",
                        0) == 0);
    const Outcome other = run_tool(
        {"compare", "head-on", "--root", root, "--engine", "chipmunk", "--with", "box2d-2.4"});
    CHECK(other.out.rfind("compare: 1 scene; chipmunk (given symplectic-euler, Box2D's "
                          "integrator, which an engine without integrators ignores) beside "
                          "box2d-2.4\n",
                          0) == 0);
}

TEST_CASE("compare's box2d-2.4 and impulse columns are impulse box2d's numbers",
          "[compare-engines]") {
    const std::vector<std::string> scenes = {"drop-box", "head-on", "tilted-box"};
    std::vector<std::string> compare = {"compare", "--root", root, "--with", "box2d-2.4", "--json"};
    std::vector<std::string> box2d = {"box2d", "--root", root, "--json"};
    compare.insert(compare.end(), scenes.begin(), scenes.end());
    box2d.insert(box2d.end(), scenes.begin(), scenes.end());
    const nlohmann::json c = json_of(run_tool(compare));
    const nlohmann::json b = json_of(run_tool(box2d));
    REQUIRE(c["scenes"].size() == scenes.size());
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        const nlohmann::json& rows = c["scenes"][s]["rows"];
        REQUIRE(rows.size() == b["scenes"][s]["rows"].size());
        for (std::size_t r = 0; r < rows.size(); ++r) {
            const nlohmann::json& old = b["scenes"][s]["rows"][r];
            INFO(scenes[s] << ": " << old["name"]);
            CHECK(rows[r]["name"] == old["name"]);
            CHECK(rows[r]["exact"] == old["exact"]);
            CHECK(rows[r]["values"]["impulse"] == old["impulse"]);
            CHECK(rows[r]["values"]["box2d-2.4"] == old["box2d"]);
            CHECK(rows[r]["within"] == old["within"]);
        }
    }
}

TEST_CASE("compare with fake Node references: a replayed column and an unsupported one",
          "[compare-engines]") {
    const TempDir work;
    const FakeReferences refs(replay(box2d_run(work)), refuse);
    SECTION("JSON: the replay of Box2D's run has Box2D's values; the refusal has none") {
        const Outcome o = run_tool({"compare", "drop-box", "--root", root, "--json"}, {refs.env()});
        CHECK(o.exit_code == 0); // a refusal is not a failure
        const nlohmann::json doc = json_of(o);
        const nlohmann::json& scene = doc["scenes"][0];
        std::vector<std::string> names;
        for (const nlohmann::json& e : scene["engines"]) {
            names.push_back(e["name"]);
        }
        // Every reference on this machine, in the registry's order (chipmunk
        // when this build has it).
        std::vector<std::string> expected = {"impulse"};
        for (const auto& r : impulse::harness::reference_engines()) {
            if (r.available) {
                expected.push_back(r.name);
            }
        }
        CHECK(names == expected);
        CHECK(scene["engines"][2]["command"].size() == 2); // node and the program
        const std::string refused = scene["engines"].back()["unsupported"];
        CHECK(refused == "unsupported by rapier: no rapier here");
        CHECK(scene["engines"].back()["settings"].is_null());
        REQUIRE_FALSE(scene["rows"].empty());
        for (const nlohmann::json& row : scene["rows"]) {
            INFO(row["name"]);
            CHECK(row["values"]["box2d-3"] == row["values"]["box2d-2.4"]);
            CHECK(row["values"]["rapier"].is_null());
        }
    }
    SECTION("text: a column each, 'unsupported' in the refusing one, a summary line each") {
        const Outcome o = run_tool({"compare", "drop-box", "--root", root}, {refs.env()});
        CHECK(o.exit_code == 0);
        const std::string header = o.out.substr(o.out.find("  observable"));
        const std::string first_line = header.substr(0, header.find('\n'));
        for (const char* column : {"exact", "impulse", "box2d-2.4", "box2d-3", "rapier"}) {
            CHECK(first_line.find(column) != std::string::npos);
        }
        CHECK(o.out.find("unsupported by rapier: no rapier here") != std::string::npos);
        CHECK(o.out.find("  unsupported\n") != std::string::npos); // the rapier cells
        for (const char* engine : {"impulse ", "box2d-2.4 ", "box2d-3 ", "rapier "}) {
            CHECK(o.out.find("\n  " + std::string(engine)) != std::string::npos);
        }
        CHECK(o.out.find("1 scene: 1 passed, 0 failed") != std::string::npos);
    }
    SECTION("--box2d-3-substeps N reaches its program and is printed with its command") {
        const Outcome o = run_tool({"compare", "drop-box", "--root", root, "--with", "box2d-3",
                                    "--box2d-3-substeps", "2", "--json"},
                                   {refs.env()});
        CHECK(o.exit_code == 0);
        const nlohmann::json command = json_of(o)["scenes"][0]["engines"][1]["command"];
        REQUIRE(command.size() == 4);
        CHECK(command[2] == "--substeps");
        CHECK(command[3] == "2");
    }
    SECTION("--summary: the summary lines, no table") {
        const Outcome o =
            run_tool({"compare", "drop-box", "--root", root, "--summary"}, {refs.env()});
        CHECK(o.exit_code == 0);
        CHECK(o.out.find("observable") == std::string::npos);
        CHECK(o.out.find("box2d-3    ran 1 scene") != std::string::npos);
        CHECK(o.out.find("rapier     ran 0 scenes, 1 unsupported") != std::string::npos);
    }
}

TEST_CASE("compare: a reference not on this machine", "[compare-engines]") {
    const TempDir empty;
    const std::string env = "IMPULSE_REFERENCES_DIR=" + empty.dir.string();
    SECTION("asked for: one sentence with the install command, exit 2, nothing written") {
        const TempDir out;
        const Outcome o = run_tool({"compare", "drop-box", "--root", root, "--with",
                                    "box2d-2.4,box2d-3", "--out", out.dir.string()},
                                   {env});
        CHECK(o.exit_code == 2);
        CHECK(o.out.empty());
        CHECK(o.err.find("reference 'box2d-3'") != std::string::npos);
        CHECK(o.err.find("install it with: scripts/setup") != std::string::npos);
        CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
        CHECK(fs::is_empty(out.dir));
    }
    SECTION("not asked for: listed as skipped with the install command") {
        const Outcome o = run_tool({"compare", "drop-box", "--root", root}, {env});
        CHECK(o.exit_code == 0);
        for (const char* name : {"box2d-3", "rapier"}) {
            INFO(name);
            const std::size_t at = o.out.find("\n  " + std::string(name));
            REQUIRE(at != std::string::npos);
            const std::string line = o.out.substr(at + 1, o.out.find('\n', at + 1) - at - 1);
            CHECK(line.find("skipped, not on this machine") != std::string::npos);
            CHECK(line.find("install it with: scripts/setup") != std::string::npos);
        }
    }
    SECTION("a name that is no reference is a usage error") {
        const Outcome o = run_tool({"compare", "drop-box", "--root", root, "--with", "bullet"});
        CHECK(o.exit_code == 2);
        CHECK(o.err.find("no reference engine is named 'bullet'") != std::string::npos);
    }
    SECTION("IMPULSE_REFERENCES_DIR that is not a folder is an error, not a silent skip") {
        const Outcome o = run_tool({"compare", "drop-box", "--root", root},
                                   {"IMPULSE_REFERENCES_DIR=" + (empty.dir / "nowhere").string()});
        CHECK(o.exit_code == 2);
        CHECK(o.err.find("IMPULSE_REFERENCES_DIR") != std::string::npos);
    }
}

TEST_CASE("compare --out writes every engine's run, never over what it must not",
          "[compare-engines]") {
    const TempDir work;
    const FakeReferences refs(replay(box2d_run(work)), refuse);
    const fs::path out = work.dir / "runs";
    SECTION("one trajectory per engine that ran, each readable") {
        const Outcome o =
            run_tool({"compare", "drop-box", "--root", root, "--out", out.string(), "--quiet"},
                     {refs.env()});
        INFO(o.err);
        CHECK(o.exit_code == 0);
        for (const char* engine : {"impulse", "box2d-2.4", "box2d-3"}) {
            const fs::path file = out / ("drop-box." + std::string(engine) + ".json");
            INFO(file);
            REQUIRE(fs::exists(file));
            CHECK_NOTHROW(impulse::harness::read_trajectory_file(file.string(), "a trajectory"));
        }
        CHECK_FALSE(fs::exists(out / "drop-box.rapier.json")); // it refused: no run
        // The replay and Box2D's own run are the same motion.
        const Outcome diff = run_tool({"diff", (out / "drop-box.box2d-2.4.json").string(),
                                       (out / "drop-box.box2d-3.json").string()});
        CHECK(diff.exit_code == 0);
    }
    SECTION("a link where a run would go: exit 2, the link and its target untouched, no file") {
        fs::create_directories(out);
        const fs::path target = work.dir / "precious.txt";
        spit(target, "keep me\n");
        fs::create_symlink(target, out / "drop-box.box2d-2.4.json");
        const Outcome o =
            run_tool({"compare", "drop-box", "--root", root, "--out", out.string()}, {refs.env()});
        CHECK(o.exit_code == 2);
        CHECK(o.err.find("drop-box.box2d-2.4.json") != std::string::npos);
        CHECK(o.out.empty());
        CHECK(slurp(target) == "keep me\n");
        CHECK(fs::is_symlink(out / "drop-box.box2d-2.4.json"));
        CHECK_FALSE(fs::exists(out / "drop-box.impulse.json"));
    }
    SECTION("never into goldens/") {
        const Outcome o =
            run_tool({"compare", "drop-box", "--root", root, "--out", root + "/goldens"});
        CHECK(o.exit_code == 2);
        CHECK(o.err.find("--out") != std::string::npos);
    }
}

TEST_CASE("compare --junit: a testcase per scene and engine, a refusal skipped",
          "[compare-engines]") {
    const TempDir work;
    const FakeReferences refs(replay(box2d_run(work)), refuse);
    const fs::path xml = work.dir / "compare.xml";
    const Outcome o = run_tool(
        {"compare", "drop-box", "--root", root, "--junit", xml.string(), "--quiet"}, {refs.env()});
    CHECK(o.exit_code == 0);
    const std::string text = slurp(xml);
    REQUIRE(std::system(("python3 -c 'import sys, xml.dom.minidom; "
                         "xml.dom.minidom.parse(sys.argv[1])' " +
                         xml.string())
                            .c_str()) == 0);
    for (const char* engine : {"impulse", "box2d-2.4", "box2d-3", "rapier"}) {
        CHECK(text.find("classname=\"impulse.compare.drop-box\" name=\"" + std::string(engine) +
                        "\"") != std::string::npos);
    }
    CHECK(text.find("<skipped message=\"unsupported by rapier: no rapier here\"/>") !=
          std::string::npos);
    CHECK(text.find("failures=\"0\"") != std::string::npos);

    // "-": the XML alone on standard output, the table on standard error.
    const Outcome piped =
        run_tool({"compare", "drop-box", "--root", root, "--junit", "-", "--quiet"}, {refs.env()});
    CHECK(piped.exit_code == 0);
    CHECK(piped.out.rfind("<?xml", 0) == 0);
    CHECK(piped.out.find("observable") == std::string::npos);
    CHECK(piped.err.find("observable") != std::string::npos);
}

TEST_CASE("compare: a box2d-2.4 row outside the scene's tolerance fails with exit 1",
          "[compare-engines]") {
    // Box2D finds the impact a step late: with atol 0 its impact time is off.
    const TempDir dir;
    const fs::path scene = dir.dir / "strict.json";
    spit(scene, R"({"schema": "impulse/scene@1", "name": "strict", "dt": 0.016666666666666666,
        "duration": 0.6, "restitution": 0.5,
        "bodies": [
          {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
          {"name": "box", "shape": {"box": [0.5, 0.5]}, "rotation": false, "position": [0, 1.5]}],
        "box2d": {"observables": [{"kind": "impact-times", "body": "box", "count": 1, "atol": 0}]}})");
    const Outcome o = run_tool({"compare", scene.string(), "--with", "box2d-2.4", "--summary"});
    CHECK(o.exit_code == 1);
    CHECK(o.out.find("FAILED  strict  1 of 1 box2d-2.4 rows outside tolerance") !=
          std::string::npos);
}

TEST_CASE("conform scores every reference beside the engine under test", "[compare-engines]") {
    const TempDir work;
    const FakeReferences refs(replay(box2d_run(work)), refuse);
    const fs::path json = work.dir / "card.json", xml = work.dir / "conform.xml";
    const Outcome o = run_tool({"conform", "--engine", "impulse", "drop-box", "--json",
                                json.string(), "--junit", xml.string(), "--quiet"},
                               {scenes_env, refs.env()});
    INFO(o.out << o.err);
    CHECK(o.exit_code == 0); // the references never change it
    const nlohmann::json card = nlohmann::json::parse(slurp(json));
    const std::vector<std::string> references = card["references"];
    CHECK(references.front() == "box2d-2.4");
    CHECK(std::find(references.begin(), references.end(), "box2d-3") != references.end());
    CHECK(references.back() == "rapier");
    REQUIRE(card["reference_counts"].size() == references.size());
    const nlohmann::json& engines = card["scenes"][0]["engines"];
    REQUIRE(engines.size() == 1 + references.size());
    // The replay of Box2D's run scores as Box2D does; the refusal is a skip.
    const std::size_t box2d3 = static_cast<std::size_t>(
        std::find(references.begin(), references.end(), "box2d-3") - references.begin() + 1);
    CHECK(engines[box2d3]["within"] == engines[1]["within"]);
    CHECK(engines.back()["outcome"] == "unsupported");
    CHECK(o.out.find("for scale, box2d-3: ") != std::string::npos);
    CHECK(slurp(xml).find("<property name=\"reference rapier\"") != std::string::npos);

    SECTION("--with none: no reference; a requested one missing is exit 2") {
        const Outcome none =
            run_tool({"conform", "--engine", "impulse", "drop-box", "--with", "none"},
                     {scenes_env, refs.env()});
        CHECK(none.exit_code == 0);
        CHECK(none.out.find("for scale: none") != std::string::npos);
        const TempDir empty;
        const Outcome missing =
            run_tool({"conform", "--engine", "impulse", "drop-box", "--with", "rapier"},
                     {scenes_env, "IMPULSE_REFERENCES_DIR=" + empty.dir.string()});
        CHECK(missing.exit_code == 2);
        CHECK(missing.err.find("install it with: scripts/setup") != std::string::npos);
    }
}

TEST_CASE("compare drop-box with the real references: a column each, the impact where physics "
          "puts it",
          "[compare-engines]") {
    // Whatever this machine has (scripts/setup installs them all): each one
    // available is a column, each other one is skipped with its install command.
    const Outcome o = run_tool({"compare", "drop-box", "--root", root, "--json"});
    REQUIRE(o.exit_code == 0);
    const nlohmann::json doc = json_of(o);
    const nlohmann::json& scene = doc["scenes"][0];
    const nlohmann::json& t1 = row_named(scene, "impact 1 time of 'box' (s)");
    const double exact = std::sqrt(2.0 * h0 / g);
    for (const auto& r : impulse::harness::reference_engines()) {
        INFO(r.name);
        if (!r.available) {
            bool listed = false;
            for (const nlohmann::json& s : doc["skipped_references"]) {
                listed = listed || (s["name"] == r.name && s["install"] == r.install);
            }
            CHECK(listed);
            continue;
        }
        REQUIRE(t1["values"].contains(r.name));
        // Every reference steps at dt and finds the contact once the box
        // overlaps the ground at the end of a step: at or after the exact
        // time, within two steps of it.
        const double t = t1["values"][r.name];
        CHECK(t >= exact);
        CHECK(t <= exact + 2.0 * dt);
    }
}
