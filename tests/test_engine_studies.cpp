// The studies (impulse box2d, impulse sweep) with the engine under study
// named by --engine (issue 13): the impulse engine by name gives exactly what
// the verbs give without the option; any other engine runs through
// run_engine, its refusals are skips, and the sweep says where its cost came
// from.
//
// The tests tagged [engine-external] run an external engine through the
// protocol (docs/engine-protocol.md). They are hidden until the protocol
// runner (harness/engines/, another branch) lands; until then run_engine
// throws "cannot be run yet" for an external engine. Run them with
//     impulse_tests "[engine-external]"
// Their engines wrap the built tool (`impulse run SCENE` writes the
// trajectory to standard output), so their numbers are the impulse engine's,
// computed the long way round: what the external path must reproduce.
#include "scene.h"
#include "support/tool.h"
#include "sweep.h"
#include "sweep_csv.h"
#include "sweep_plot.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

using namespace impulse;
using namespace impulse::harness;
using impulse::test::run_tool;
using impulse::test::spit;
using impulse::test::TempDir;

namespace {

const std::string root = IMPULSE_SOURCE_DIR;

std::string scene_path(const std::string& name) {
    return root + "/harness/scenes/" + name + ".json";
}

std::size_t occurrences(const std::string& text, const std::string& part) {
    std::size_t n = 0;
    for (std::size_t at = text.find(part); at != std::string::npos;
         at = text.find(part, at + part.size())) {
        ++n;
    }
    return n;
}

// A Python engine in `dir` that refuses (exit 3, `refusal` on stderr) a scene
// whose solver.integrator is `refused`, runs every other scene in the built
// tool and passes its trajectory on, with a "cost" block when `cost` is
// given. Each run appends the integrator it was asked for to DIR/calls.
std::string python_engine(const TempDir& dir, const std::string& refused,
                          const std::string& refusal, const std::string& cost,
                          int refusal_exit = 3) {
    const std::string script = (dir.dir / "engine.py").string();
    spit(script, "import json, subprocess, sys\n"
                 "scene = json.load(open(sys.argv[-1]))\n"
                 "integrator = scene.get('solver', {}).get('integrator', '')\n"
                 "with open('" +
                     (dir.dir / "calls").string() +
                     "', 'a') as calls:\n"
                     "    calls.write(integrator + '\\n')\n"
                     "if integrator == '" +
                     refused +
                     "':\n"
                     "    sys.stderr.write('" +
                     refusal +
                     "\\n')\n"
                     "    sys.exit(" +
                     std::to_string(refusal_exit) +
                     ")\n"
                     "run = subprocess.run(['" +
                     impulse::test::tool_under_test() +
                     "', 'run', '--quiet', sys.argv[-1]], capture_output=True, text=True)\n"
                     "if run.returncode != 0:\n"
                     "    sys.stderr.write(run.stderr)\n"
                     "    sys.exit(run.returncode)\n"
                     "trajectory = json.loads(run.stdout)\n" +
                     (cost.empty() ? "" : "trajectory['cost'] = " + cost + "\n") +
                     "json.dump(trajectory, sys.stdout)\n");
    return "python3 " + script;
}

// The sweep's points by (family-free) settings: integrator, dt, tolerance.
const nlohmann::json& point_at(const nlohmann::json& sweep, const std::string& integrator,
                               double dt) {
    for (const nlohmann::json& p : sweep.at("points")) {
        if (p.at("integrator") == integrator && p.at("dt").get<double>() == dt) {
            return p;
        }
    }
    FAIL("no point " << integrator << " at dt " << dt);
    return sweep;
}

} // namespace

#ifdef IMPULSE_WITH_BOX2D
TEST_CASE("box2d --engine impulse prints exactly what box2d prints", "[engine-studies]") {
    for (const std::string format : {"", "--json"}) {
        std::vector<std::string> args = {"box2d",  "head-on", "corner-to-corner",
                                         "--root", root,      "--quiet"};
        if (!format.empty()) {
            args.push_back(format);
        }
        const test::Outcome plain = run_tool(args);
        args.insert(args.end(), {"--engine", "impulse"});
        const test::Outcome named = run_tool(args);
        REQUIRE(plain.exited);
        CHECK(plain.exit_code == 0);
        CHECK(named.exit_code == plain.exit_code);
        CHECK(named.out == plain.out);
        CHECK(named.err == plain.err);
        // Not two empty outputs: both compared the scenes' observables.
        CHECK(occurrences(plain.out, "impact 1 time of") >= 2);
    }
}
#endif

TEST_CASE("sweep --engine impulse measures what sweep measures", "[engine-studies]") {
    std::vector<std::string> args = {"sweep",
                                     "drop-box",
                                     "--root",
                                     root,
                                     "--json",
                                     "--quiet",
                                     "--no-box2d",
                                     "--dt",
                                     "0.01",
                                     "--integrator",
                                     "verlet,euler",
                                     "--toi",
                                     "bisection,secant",
                                     "--toi-tolerance",
                                     "1e-9",
                                     "--repeats",
                                     "1"};
    const test::Outcome plain = run_tool(args);
    args.insert(args.end(), {"--engine", "impulse"});
    const test::Outcome named = run_tool(args);
    REQUIRE(plain.exit_code == 0);
    REQUIRE(named.exit_code == 0);
    const nlohmann::json a = nlohmann::json::parse(plain.out);
    const nlohmann::json b = nlohmann::json::parse(named.out);
    // The impulse engine's output has no cost source: its cost is measured
    // as it always was.
    CHECK_FALSE(b.contains("cost_source"));
    CHECK_FALSE(b.contains("engine"));
    REQUIRE(a.at("points").size() == 4);
    REQUIRE(b.at("points").size() == a.at("points").size());
    for (std::size_t i = 0; i < a.at("points").size(); ++i) {
        const nlohmann::json& p = a.at("points")[i];
        const nlohmann::json& q = b.at("points")[i];
        CHECK(q.at("engine") == "impulse");
        CHECK(q.at("family") == p.at("family"));
        CHECK(q.at("ok") == true);
        // Error and work are deterministic; only the wall-clock cost varies.
        CHECK(q.at("error") == p.at("error"));
        CHECK(q.at("work") == p.at("work"));
    }
}

TEST_CASE("An engine the studies do not know, or a setting it cannot vary, is a usage error",
          "[engine-studies]") {
    for (const std::string verb : {"box2d", "sweep"}) {
        const test::Outcome o = run_tool({verb, "head-on", "--root", root, "--engine", "nope"});
        CHECK(o.exit_code == 2);
        CHECK(o.out.empty());
        CHECK(o.err.find("no engine is named 'nope' (--engine)") != std::string::npos);

        const test::Outcome empty =
            run_tool({verb, "head-on", "--root", root, "--engine-command", " "});
        CHECK(empty.exit_code == 2);
        CHECK(empty.err.find("--engine-command needs a program") != std::string::npos);

        const test::Outcome taken = run_tool(
            {verb, "head-on", "--root", root, "--engine", "impulse", "--engine-command", "x"});
        CHECK(taken.exit_code == 2);
        CHECK(taken.err.find("not impulse, box2d or chipmunk, got 'impulse'") != std::string::npos);
    }
    // The toi method and ccd are the impulse engine's own grid dimensions.
    for (const std::string option : {"--toi", "--ccd"}) {
        const test::Outcome o = run_tool({"sweep", "head-on", "--root", root, "--engine", "ext",
                                          "--engine-command", "true", option, "on"});
        CHECK(o.exit_code == 2);
        CHECK(o.err.find(option + " varies the impulse engine's own settings; the grid of ext "
                                  "is --dt, --integrator and --toi-tolerance") !=
              std::string::npos);
    }
}

TEST_CASE("Another engine's sweep says in its CSV and plot where its cost came from",
          "[engine-studies]") {
    SweepResult r;
    r.scene = "s";
    r.engine = "mine";
    r.cost_source = "cost: process wall time (the engine reports none)";
    SweepPoint measured;
    measured.kind = EngineSpec::Kind::external;
    measured.engine = "mine";
    measured.integrator = Integrator::verlet;
    measured.dt = 0.01;
    measured.toi_tolerance = 1e-9;
    measured.family = sweep_family(measured);
    measured.ok = true;
    measured.error = 1e-6;
    measured.cost_median = 0.5;
    measured.cost_source = SweepCost::process_time;
    measured.work_counted = false;
    SweepPoint skipped = measured;
    skipped.integrator = Integrator::rk4;
    skipped.family = sweep_family(skipped);
    skipped.ok = false;
    skipped.skipped = true;
    skipped.failure = "unsupported by mine: no rk4";
    r.points = {measured, skipped};
    CHECK(measured.family == "mine verlet");

    const std::string csv = sweep_csv(r);
    const std::vector<std::string> lines = [&] {
        std::vector<std::string> l;
        std::size_t from = 0;
        for (std::size_t at = csv.find('\n'); at != std::string::npos; at = csv.find('\n', from)) {
            l.push_back(csv.substr(from, at - from));
            from = at + 1;
        }
        return l;
    }();
    REQUIRE(lines.size() == 3);
    CHECK(lines[0].substr(lines[0].size() - 20) == ",failure,cost_source");
    // engine, family, dt, integrator, toi and ccd empty (the scene's own),
    // no Box2D settings, the cost, no steps counted, the source.
    CHECK(lines[1] == "mine,mine verlet,0.01,verlet,,1e-09,,,,,true,1e-06,0.5,0,,0,0,0,false,,"
                      "process");
    CHECK(lines[2] == "mine,mine rk4,0.01,rk4,,1e-09,,,,,false,,,,,0,0,0,false,unsupported by "
                      "mine: no rk4,");
    CHECK(sweep_svg(r).find("cost: process wall time (the engine reports none) per simulated "
                            "second (s/s, log)") != std::string::npos);

    // The impulse engine's CSV keeps its columns.
    SweepResult own = r;
    own.cost_source.clear();
    CHECK(sweep_csv(own).find("cost_source") == std::string::npos);
    CHECK(sweep_svg(own).find("cost: wall time per simulated second") != std::string::npos);
}

#ifdef IMPULSE_WITH_BOX2D
TEST_CASE("box2d compares an external engine's trajectory with Box2D's", "[engine-external]") {
    const std::string tool = impulse::test::tool_under_test();
    const TempDir out;
    const std::vector<std::string> scenes = {"head-on", "corner-to-corner"};
    std::vector<std::string> args = {"box2d", "--root", root, "--quiet", "--json"};
    args.insert(args.begin() + 1, scenes.begin(), scenes.end());
    const test::Outcome own = run_tool(args);
    args.insert(args.end(), {"--engine", "wrapped", "--engine-command", tool + " run --quiet",
                             "--out", out.dir.string()});
    const test::Outcome wrapped = run_tool(args);
    INFO(wrapped.err);
    REQUIRE(own.exit_code == 0);
    REQUIRE(wrapped.exit_code == 0);
    const nlohmann::json a = nlohmann::json::parse(own.out);
    const nlohmann::json b = nlohmann::json::parse(wrapped.out);
    CHECK(b.at("engine") == "wrapped");
    CHECK(b.at("engine_integrator") == "symplectic-euler");
    REQUIRE(b.at("scenes").size() == scenes.size());
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        const nlohmann::json& rows = a.at("scenes")[s].at("rows");
        const nlohmann::json& wrapped_rows = b.at("scenes")[s].at("rows");
        CHECK(b.at("scenes")[s].at("engine").at("name") == "wrapped");
        REQUIRE(rows.size() > 0);
        REQUIRE(wrapped_rows.size() == rows.size());
        for (std::size_t i = 0; i < rows.size(); ++i) {
            // The same physics by another road: the same numbers.
            CHECK(wrapped_rows[i].at("engine") == rows[i].at("impulse"));
            CHECK(wrapped_rows[i].at("box2d") == rows[i].at("box2d"));
            CHECK(wrapped_rows[i].at("within") == rows[i].at("within"));
        }
        CHECK(std::filesystem::is_regular_file(out.dir / (scenes[s] + ".wrapped.json")));
        CHECK(std::filesystem::is_regular_file(out.dir / (scenes[s] + ".box2d.json")));
    }

    // The text names the engine in its columns.
    const test::Outcome text = run_tool({"box2d", "head-on", "--root", root, "--quiet", "--engine",
                                         "wrapped", "--engine-command", tool + " run --quiet"});
    CHECK(text.exit_code == 0);
    CHECK(text.out.find("Box2D - wrapped") != std::string::npos);
}

TEST_CASE("box2d skips a scene whose settings the engine refuses", "[engine-external]") {
    const TempDir dir;
    const std::string command = python_engine(dir, "symplectic-euler", "no symplectic-euler", "");
    const test::Outcome o = run_tool({"box2d", "head-on", "--root", root, "--quiet", "--engine",
                                      "picky", "--engine-command", command});
    INFO(o.err);
    CHECK(o.exit_code == 0); // a skip is not a failure
    CHECK(o.out.find("skipped, unsupported by picky: no symplectic-euler") != std::string::npos);
    CHECK(o.out.find("1 scene: 0 passed, 0 failed, 1 skipped") != std::string::npos);

    const test::Outcome j = run_tool({"box2d", "head-on", "--root", root, "--quiet", "--json",
                                      "--engine", "picky", "--engine-command", command});
    const nlohmann::json scene = nlohmann::json::parse(j.out).at("scenes").at(0);
    CHECK(scene.at("passed").is_null());
    CHECK(scene.at("skipped") == "unsupported by picky: no symplectic-euler");
}
#endif

TEST_CASE("sweep runs an external engine over its grid; without a reported cost it times the "
          "process and says so",
          "[engine-external]") {
    const std::string tool = impulse::test::tool_under_test();
    const Scene scene = load_scene(scene_path("head-on"));
    const std::vector<std::string> grid = {"--no-box2d",   "--dt",      "0.01,0.005",
                                           "--integrator", "verlet",    "--toi-tolerance",
                                           "1e-9",         "--repeats", "2"};
    std::vector<std::string> args = {"sweep", "head-on", "--root", root, "--quiet", "--json"};
    args.insert(args.end(), grid.begin(), grid.end());
    std::vector<std::string> own_args = args;
    own_args.insert(own_args.end(), {"--toi", toi_method_name(scene.solver.toi)});
    const test::Outcome own = run_tool(own_args);
    args.insert(args.end(), {"--engine", "wrapped", "--engine-command", tool + " run --quiet"});
    const test::Outcome wrapped = run_tool(args);
    INFO(wrapped.err);
    REQUIRE(own.exit_code == 0);
    REQUIRE(wrapped.exit_code == 0);
    const nlohmann::json a = nlohmann::json::parse(own.out);
    const nlohmann::json b = nlohmann::json::parse(wrapped.out);
    CHECK(b.at("engine") == "wrapped");
    CHECK(b.at("cost_source") == "cost: process wall time (the engine reports none)");
    REQUIRE(b.at("points").size() == 2);
    for (const double dt : {0.01, 0.005}) {
        const nlohmann::json& p = point_at(b, "verlet", dt);
        CHECK(p.at("family") == "wrapped verlet");
        CHECK(p.at("ok") == true);
        CHECK(p.at("cost_source") == "process");
        CHECK(p.at("cost_median").get<double>() > 0.0);
        CHECK(p.at("work").is_null()); // the engine counts no work
        // The engine is the impulse engine behind the protocol: same error.
        CHECK(p.at("error") == point_at(a, "verlet", dt).at("error"));
    }

    std::vector<std::string> text_args = args;
    text_args.erase(std::find(text_args.begin(), text_args.end(), "--json"));
    const test::Outcome text = run_tool(text_args);
    CHECK(text.out.find("cost: process wall time (the engine reports none), in seconds per "
                        "simulated second") != std::string::npos);
    std::vector<std::string> csv_args = text_args;
    csv_args.push_back("--csv");
    const test::Outcome csv = run_tool(csv_args);
    CHECK(occurrences(csv.out, ",process\n") == 2);
}

TEST_CASE("sweep uses the cost an external engine reports", "[engine-external]") {
    const TempDir dir;
    // 0.3 s of work for every run, 1234 steps: head-on's 1.5 s at dt 0.01 is
    // 150 steps of 0.01 s, so 0.3 / 1.5 = 0.2 s per simulated second.
    const std::string command = python_engine(dir, "none", "", "{'seconds': 0.3, 'steps': 1234}");
    const test::Outcome o =
        run_tool({"sweep", "head-on", "--root", root, "--quiet", "--json", "--no-box2d", "--dt",
                  "0.01", "--integrator", "verlet", "--toi-tolerance", "1e-9", "--repeats", "3",
                  "--engine", "costly", "--engine-command", command});
    INFO(o.err);
    REQUIRE(o.exit_code == 0);
    const nlohmann::json j = nlohmann::json::parse(o.out);
    CHECK(j.at("cost_source") == "cost: the engine's own (its trajectory's cost.seconds)");
    const nlohmann::json& p = point_at(j, "verlet", 0.01);
    CHECK(p.at("cost_source") == "engine");
    CHECK(p.at("cost_median").get<double>() == Approx(0.3 / 1.5).epsilon(1e-12));
    CHECK(p.at("cost_spread").get<double>() == 0.0);
    CHECK(p.at("work").at("steps") == 1234);
    CHECK(p.at("work_identical") == true);
}

TEST_CASE("sweep marks a grid point failed where an external engine's model stops (exit 1) and "
          "goes on, and a crash ends it naming the point",
          "[engine-external]") {
    const TempDir dir;
    const std::vector<std::string> sweep = {
        "sweep",     "head-on", "--root",       root,         "--quiet",         "--no-references",
        "--dt",      "0.01",    "--integrator", "verlet,rk4", "--toi-tolerance", "1e-9",
        "--repeats", "1",       "--engine",     "picky",      "--engine-command"};
    std::vector<std::string> stops = sweep;
    stops.push_back(python_engine(dir, "rk4", "a cascade I cannot end", "", 1));
    const test::Outcome stopped = run_tool(stops);
    INFO(stopped.out << stopped.err);
    CHECK(stopped.exit_code == 0);
    CHECK(stopped.out.find("1 point measured, 1 failed") != std::string::npos);
    CHECK(stopped.out.find("a cascade I cannot end") != std::string::npos);

    std::vector<std::string> crashes = sweep;
    crashes.push_back(python_engine(dir, "rk4", "broken", "", 2));
    const test::Outcome crashed = run_tool(crashes);
    INFO(crashed.out << crashed.err);
    CHECK(crashed.exit_code == 2);
    CHECK(crashed.err.find("engine 'picky' failed on ") != std::string::npos);
    CHECK(crashed.err.find("head-on.json (with dt 0.01, integrator rk4, toi_tolerance 1e-09): "
                           "exit status 2: broken") != std::string::npos);
}

TEST_CASE("sweep lists the grid points an external engine refuses as skipped, once each",
          "[engine-external]") {
    const TempDir dir;
    const std::string command = python_engine(dir, "rk4", "rk4 is not modelled here", "");
    const test::Outcome o =
        run_tool({"sweep", "head-on", "--root", root, "--quiet", "--no-box2d", "--dt", "0.01,0.005",
                  "--integrator", "verlet,rk4", "--toi-tolerance", "1e-9", "--repeats", "3",
                  "--engine", "picky", "--engine-command", command});
    INFO(o.err);
    CHECK(o.exit_code == 0); // a refusal is a skip, not an error
    CHECK(o.out.find("2 points measured, 0 failed, 2 skipped") != std::string::npos);
    CHECK(occurrences(o.out, "unsupported by picky: rk4 is not modelled here") == 1);
    CHECK(o.out.find("skipped 2 points: unsupported by picky: rk4 is not modelled here") !=
          std::string::npos);
    // A refused point is asked once, not once per repeat: 2 verlet points
    // x 3 repeats, 2 rk4 points x 1.
    const std::string calls = impulse::test::slurp(dir.dir / "calls");
    CHECK(occurrences(calls, "verlet\n") == 6);
    CHECK(occurrences(calls, "rk4\n") == 2);
}

TEST_CASE("sweep runs an integrator or tolerance an external engine ignores once, and says so",
          "[engine-external]") {
    const TempDir dir;
    // An engine with one integrator and one tolerance of its own, whatever
    // the scene names: the built tool on the scene with those two replaced.
    const std::string script = (dir.dir / "fixed.py").string();
    spit(script, "import json, subprocess, sys\n"
                 "scene = json.load(open(sys.argv[-1]))\n"
                 "with open('" +
                     (dir.dir / "calls").string() +
                     "', 'a') as calls:\n"
                     "    calls.write('run\\n')\n"
                     "scene['solver']['integrator'] = 'verlet'\n"
                     "scene['solver']['toi_tolerance'] = 1e-9\n"
                     "json.dump(scene, open('" +
                     (dir.dir / "own.json").string() +
                     "', 'w'))\n"
                     "run = subprocess.run(['" +
                     impulse::test::tool_under_test() + "', 'run', '--quiet', '" +
                     (dir.dir / "own.json").string() +
                     "'], capture_output=True, text=True)\n"
                     "sys.stdout.write(run.stdout)\n"
                     "sys.exit(run.returncode)\n");
    const std::vector<std::string> grid = {"sweep",
                                           "drop-box",
                                           "--root",
                                           root,
                                           "--quiet",
                                           "--no-box2d",
                                           "--no-references",
                                           "--dt",
                                           "0.01,0.005",
                                           "--integrator",
                                           "rk4,euler,verlet",
                                           "--toi-tolerance",
                                           "1e-6,1e-9",
                                           "--repeats",
                                           "1"};
    std::vector<std::string> fixed = grid;
    fixed.insert(fixed.end(), {"--engine", "fixed", "--engine-command", "python3 " + script});
    const test::Outcome o = run_tool(fixed);
    INFO(o.out << o.err);
    REQUIRE(o.exit_code == 0);
    // The first dt's 6 points show it; the second dt runs rk4 at 1e-6 alone.
    CHECK(o.out.find("2 points measured, 0 failed, 10 skipped") != std::string::npos);
    CHECK(o.out.find("skipped 8 points: fixed gave the same trajectory under every integrator at "
                     "dt 0.01 (it ignores solver.integrator, or it changes nothing here), so "
                     "only rk4 is run") != std::string::npos);
    CHECK(o.out.find("skipped 2 points: fixed gave the same trajectory under every toi_tolerance "
                     "at dt 0.01") != std::string::npos);
    CHECK(occurrences(impulse::test::slurp(dir.dir / "calls"), "run\n") == 7);

    // An engine that honours the integrator (the built tool itself) keeps
    // each: euler, verlet and rk4 follow a fall differently. (Its search for
    // drop-box's impacts ends on the same bits at 1e-6 s and 1e-9 s, so a
    // tolerance grid of those two would rightly be one run here too.)
    std::vector<std::string> honest = grid;
    *std::find(honest.begin(), honest.end(), "1e-6,1e-9") = "1e-9";
    honest.insert(honest.end(), {"--engine", "wrapped", "--engine-command",
                                 impulse::test::tool_under_test() + " run --quiet"});
    const test::Outcome h = run_tool(honest);
    INFO(h.out << h.err);
    REQUIRE(h.exit_code == 0);
    CHECK(h.out.find("6 points measured, 0 failed\n") != std::string::npos);
    CHECK(h.out.find("skipped") == std::string::npos);
}
