// solver.resting_method (issue 14; docs/formats.md, the solver table;
// docs/refusals-and-progress.md, "Dense contact"): the loader reads each name
// and refuses each impossible combination at its key. Through the real tool:
// each refusal is one sentence naming the file and the JSON path, exit 2,
// nothing written and no output file destroyed; resting with local stepping
// runs; the key is written into a golden's solver block and the normalized
// scene only when it is not "auto"; a step failure names the setting that
// carries the scene on; auto's switch is noted once; a scene that time-steps
// from its start, or under auto, is not refused for tunnelling.
#include "scene.h"
#include "scene_writer.h"
#include "support.h"
#include "support/files.h"
#include "support/outcome.h"
#include "support/scene_text.h"
#include "support/tool.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using impulse::harness::parse_scene;
using impulse::harness::Scene;
using namespace impulse::test;

namespace {

// A disc of radius 0.5 at height `y` (its centre) above static ground whose
// top is at y = 0, under the given solver block, for `duration` seconds.
std::string disc_scene(const std::string& solver, double y = 5.0,
                       const std::string& duration = "0.1", const std::string& extra = "") {
    return R"({"schema":"impulse/scene@1","name":"m","dt":0.01,"duration":)" + duration + extra +
           R"(,"solver":)" + solver +
           R"(,"bodies":[{"name":"ground","static":true,"shape":{"box":[5,0.5]},"position":[0,-0.5]},)"
           R"({"name":"ball","shape":{"circle":0.5},"mass":1,"position":[0,)" +
           std::to_string(y) + "]}]}";
}

// `run` refuses the scene with "FILE: PATH: ..." containing `words`, and the
// output file it was given keeps its bytes.
void require_refused(const std::string& scene_text, const std::string& path,
                     const std::string& words) {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "m.json";
    spit(scene, scene_text);
    const fs::path out = tmp.dir / "out.json";
    spit(out, "an earlier run's bytes");
    const Outcome o = run_tool({"run", scene.string(), "--out", out.string()});
    INFO(scene_text);
    require_one_sentence(o);
    CHECK(o.err.rfind(scene.string() + ": " + path + ": ", 0) == 0);
    CHECK(has(o.err, words));
    CHECK(slurp(out) == "an earlier run's bytes");
}

} // namespace

// ---------------------------------------------------------------- the loader (parse_scene)

TEST_CASE("resting_method: auto by default, each name read and written back",
          "[scene][resting-method]") {
    using impulse::RestingMethod;
    using impulse::harness::resting_method_from_name;
    using impulse::harness::resting_method_name;
    CHECK(parse_scene(scene_with(R"("solver": {"resting": true},)"), test_file)
              .solver.resting_method == RestingMethod::automatic);
    const std::pair<const char*, RestingMethod> names[] = {
        {"auto", RestingMethod::automatic},
        {"events", RestingMethod::events},
        {"time-stepping", RestingMethod::time_stepping}};
    for (const auto& [name, method] : names) {
        INFO(name);
        const Scene scene = parse_scene(
            scene_with(std::string(R"("solver": {"resting": true, "resting_method": ")") + name +
                       R"("},)"),
            test_file);
        CHECK(scene.solver.resting_method == method);
        CHECK(std::string(resting_method_name(method)) == name);
        RestingMethod back = RestingMethod::events;
        CHECK(resting_method_from_name(name, back));
        CHECK(back == method);
    }
    RestingMethod unchanged = RestingMethod::time_stepping;
    CHECK_FALSE(resting_method_from_name("time_stepping", unchanged));
    CHECK(unchanged == RestingMethod::time_stepping);
}

TEST_CASE("resting with local stepping loads, and is time-stepping from the start",
          "[scene][resting-method]") {
    using impulse::harness::time_stepping_from_start;
    const Scene local =
        parse_scene(scene_with(R"("solver": {"stepping": "local", "resting": true},)"), test_file);
    CHECK(local.solver.resting);
    CHECK(local.solver.stepping == impulse::Stepping::local);
    CHECK(time_stepping_from_start(local.solver));
    const Scene explicit_method = parse_scene(
        scene_with(
            R"("solver": {"stepping": "local", "resting": true, "resting_method": "time-stepping"},)"),
        test_file);
    CHECK(time_stepping_from_start(explicit_method.solver));
    // world stepping: auto starts with events, and events never time-steps.
    CHECK_FALSE(time_stepping_from_start(
        parse_scene(scene_with(R"("solver": {"resting": true},)"), test_file).solver));
    CHECK_FALSE(time_stepping_from_start(
        parse_scene(scene_with(R"("solver": {"resting": true, "resting_method": "events"},)"),
                    test_file)
            .solver));
    CHECK(time_stepping_from_start(
        parse_scene(
            scene_with(R"("solver": {"resting": true, "resting_method": "time-stepping"},)"),
            test_file)
            .solver));
    // Events and ccd with world stepping are one model, as before.
    CHECK(parse_scene(scene_with(R"("solver": {"resting": true, "resting_method": "events",
                                               "ccd": true},)"),
                      test_file)
              .solver.ccd);
}

TEST_CASE("rejected resting_method", "[scene][resting-method]") {
    SECTION("an unknown method") {
        require_rejected(
            scene_with(R"("solver": {"resting": true, "resting_method": "baraff"},)"),
            "solver.resting_method",
            "must be \"auto\" (the default), \"events\" or \"time-stepping\", got \"baraff\"");
    }
    SECTION("not a string") {
        require_rejected(scene_with(R"("solver": {"resting": true, "resting_method": true},)"),
                         "solver.resting_method", "or \"time-stepping\", got true");
    }
    SECTION("without resting") {
        require_rejected(scene_with(R"("solver": {"resting_method": "time-stepping"},)"),
                         "solver.resting_method", "needs \"resting\": true in the solver block");
        require_rejected(scene_with(R"("solver": {"resting": false, "resting_method": "auto"},)"),
                         "solver.resting_method",
                         "add \"resting\": true or remove \"resting_method\"");
    }
    SECTION("events with local stepping") {
        require_rejected(
            scene_with(
                R"("solver": {"stepping": "local", "resting": true, "resting_method": "events"},)"),
            "solver.resting_method",
            "\"events\" is not available with \"stepping\": \"local\" (the event model holds "
            "every resting pair of the world at once); use \"resting_method\": \"auto\" or "
            "\"time-stepping\" with local stepping, or \"stepping\": \"world\" with events");
    }
    SECTION("ccd with time-stepping, and with auto where it time-steps from the start") {
        // ccd then sweeps each time step's motion (docs/engine.md, "Tunnelling").
        CHECK(parse_scene(scene_with(R"("solver": {"resting": true, "ccd": true,
                                                   "resting_method": "time-stepping"},)"),
                          "s.json")
                  .solver.ccd);
        const auto discs = [](int count) {
            std::string text =
                R"({"schema":"impulse/scene@1","name":"row","dt":0.01,"duration":0.05,)"
                R"("solver":{"resting":true,"ccd":true},"bodies":[{"name":"ground",)"
                R"("static":true,"shape":{"box":[20,0.5]},"position":[0,-0.5]})";
            for (int i = 0; i < count; ++i) {
                text += R"(,{"name":"d)" + std::to_string(i) +
                        R"(","shape":{"circle":0.25},"mass":1,"position":[)" +
                        std::to_string(i - count / 2) + ",1]}";
            }
            return text + "]}";
        };
        CHECK(parse_scene(discs(17), "row.json").solver.ccd);
        CHECK(parse_scene(discs(16), "row.json").solver.ccd);
    }
    SECTION("a typo of the key") {
        require_rejected(scene_with(R"("solver": {"resting": true, "resting_methods": "auto"},)"),
                         "solver.resting_methods", "unknown key (did you mean resting_method?)");
    }
}

// ---------------------------------------------------------------- refusals at load, through the
// tool

TEST_CASE("run refuses each impossible resting_method with the file and the key",
          "[resting-method]") {
    SECTION("a value that is none of the three") {
        require_refused(
            disc_scene(R"({"resting":true,"resting_method":"baraff"})"), "solver.resting_method",
            R"(must be "auto" (the default), "events" or "time-stepping", got "baraff")");
    }
    SECTION("without resting") {
        require_refused(disc_scene(R"({"resting_method":"time-stepping"})"),
                        "solver.resting_method", R"(needs "resting": true in the solver block)");
    }
    SECTION("events with local stepping, naming both keys and what to use") {
        require_refused(
            disc_scene(R"({"resting":true,"stepping":"local","resting_method":"events"})"),
            "solver.resting_method",
            R"("events" is not available with "stepping": "local" (the event model holds every resting pair of the world at once); use "resting_method": "auto" or "time-stepping" with local stepping, or "stepping": "world" with events)");
    }
    SECTION("ccd with resting and local stepping: ccd needs world stepping") {
        require_refused(disc_scene(R"({"resting":true,"stepping":"local","ccd":true})"),
                        "solver.ccd", R"(is not available with "stepping": "local")");
    }
}

TEST_CASE("resting with local stepping loads and runs", "[resting-method]") {
    // Until this issue the loader refused it; 0.1 s of free fall never
    // reaches the ground (4.5 m below), so any engine version runs it.
    const TempDir tmp;
    const fs::path scene = tmp.dir / "m.json";
    spit(scene, disc_scene(R"({"resting":true,"stepping":"local"})"));
    const fs::path out = tmp.dir / "out.json";
    const Outcome o = run_tool({"run", scene.string(), "--out", out.string()});
    INFO(o.err);
    CHECK(o.exit_code == 0);
    CHECK(has(slurp(out), R"("resting": true)"));
    CHECK(has(slurp(out), R"("stepping": "local")"));
}

// ---------------------------------------------------------------- goldens and the normalized scene

TEST_CASE("a golden's solver block names resting_method only when it is not auto",
          "[resting-method]") {
    const TempDir root;
    const std::string r = root.dir.string();
    fs::create_directories(root.dir / "goldens");
    const std::vector<std::pair<std::string, std::string>> scenes = {
        {"default", R"({"resting":true})"},
        {"auto", R"({"resting":true,"resting_method":"auto"})"},
        {"events", R"({"resting":true,"resting_method":"events"})"},
        {"time-stepping", R"({"resting":true,"resting_method":"time-stepping"})"}};
    for (const auto& [name, solver] : scenes) {
        // A scene's name is its file's.
        std::string text = disc_scene(solver);
        text.replace(text.find(R"("name":"m")"), 10, R"("name":")" + name + "\"");
        spit(root.dir / "harness" / "scenes" / (name + ".json"), text);
    }
    const Outcome blessed = run_tool({"bless", "--root", r});
    INFO(blessed.out << blessed.err);
    REQUIRE(blessed.exit_code == 0);
    for (const char* name : {"default", "auto"}) {
        const std::string golden = slurp(root.dir / "goldens" / (std::string(name) + ".json"));
        INFO(name);
        REQUIRE(has(golden, R"("resting": true)"));
        CHECK_FALSE(has(golden, "resting_method"));
    }
    CHECK(has(slurp(root.dir / "goldens" / "events.json"), R"("resting_method": "events")"));
    CHECK(has(slurp(root.dir / "goldens" / "time-stepping.json"),
              R"("resting_method": "time-stepping")"));
    // The goldens just written are what check compares against.
    const Outcome checked = run_tool({"check", "--root", r});
    INFO(checked.out << checked.err);
    CHECK(checked.exit_code == 0);
}

TEST_CASE("the normalized scene keeps resting_method, and leaves out auto", "[resting-method]") {
    using impulse::RestingMethod;
    using impulse::harness::write_normalized_scene;
    const std::pair<const char*, RestingMethod> methods[] = {
        {"auto", RestingMethod::automatic},
        {"events", RestingMethod::events},
        {"time-stepping", RestingMethod::time_stepping}};
    for (const auto& [name, method] : methods) {
        INFO(name);
        const std::string solver =
            std::string(R"({"resting":true,"resting_method":")") + name + R"("})";
        const std::string text = write_normalized_scene(parse_scene(disc_scene(solver), "m.json"));
        CHECK(has(text, "resting_method") == (method != RestingMethod::automatic));
        if (method != RestingMethod::automatic) {
            CHECK(has(text, std::string(R"("resting_method": ")") + name + "\""));
        }
        const Scene back = parse_scene(text, "normalized");
        CHECK(back.solver.resting);
        CHECK(back.solver.resting_method == method);
    }
}

// ---------------------------------------------------------------- step failures name a setting

TEST_CASE("without resting, the end of a cascade names \"resting\": true", "[resting-method]") {
    // A disc dropped 4.5 m at e = 0.5 bounces ever lower and comes to rest
    // at t_inf = 3 sqrt(2 h / g) = 2.87 s, inside the 4 s run: collisions
    // alone cannot go on there.
    const TempDir tmp;
    const fs::path scene = tmp.dir / "m.json";
    spit(scene, disc_scene(R"({"integrator":"verlet"})", 5.0, "4", R"(,"restitution":0.5)"));
    const fs::path out = tmp.dir / "out.json";
    const Outcome o = run_tool({"run", scene.string(), "--out", out.string()});
    require_one_sentence(o);
    INFO(o.err);
    CHECK(o.err.rfind(scene.string() + ": ", 0) == 0);
    CHECK((has(o.err, "(a Zeno cascade)") || has(o.err, "are in resting contact")));
    CHECK(has(o.err, R"(set "resting": true in the solver block)"));
    CHECK_FALSE(has(o.err, "seed's"));
    // What was simulated up to the stop is written, marked partial (docs/formats.md).
    REQUIRE(fs::exists(out));
    CHECK(has(slurp(out), "\"partial\": {\"reason\": "));
}

TEST_CASE("without resting, a pair left touching by e = 0 in free space is named as such, "
          "and resting carries it on at the common velocity",
          "[resting-method]") {
    // Two discs (0.61 and 42.4 kg) meet head-on with no gravity and e = 0:
    // the exact answer is one impact, then both move at the common velocity
    // (m_a v_a + m_b v_b) / (m_a + m_b). Found by an outside review: the
    // approach left after the impact, -1.4e-16 m/s, is below what an impulse
    // changes, and 4097 collisions that changed nothing were reported as
    // bounces that no longer end.
    const double ma = 0.6145168313025501;
    const double mb = 42.441858965473;
    const double vax = -0.15393893904223369;
    const double vay = 0.5616413853022502;
    const double vbx = 0.6099186632974831;
    const double vby = -2.2252690911564215;
    const auto scene_text = [&](const std::string& resting) {
        return std::string(
                   R"({"schema":"impulse/scene@1","name":"e0","gravity":[0,0],"restitution":0,)"
                   R"("dt":0.016666666666666666,"duration":0.75,"solver":{"integrator":"euler",)"
                   R"("toi":"secant")") +
               resting +
               R"(},"bodies":[{"name":"A","shape":{"circle":1.1224102988433897},)"
               R"("mass":0.6145168313025501,"position":[1.9044214964253392,-1.2834582051012635],)"
               R"("velocity":[-0.15393893904223369,0.5616413853022502]},)"
               R"({"name":"B","shape":{"circle":1.3240068342624978},"mass":42.441858965473,)"
               R"("position":[1.1932364713801724,1.3112780270550313],)"
               R"("velocity":[0.6099186632974831,-2.2252690911564215]}]})";
    };
    const TempDir tmp;
    const fs::path scene = tmp.dir / "e0.json";
    spit(scene, scene_text(""));
    const fs::path out = tmp.dir / "out.json";
    const Outcome o = run_tool({"run", scene.string(), "--out", out.string()});
    require_one_sentence(o);
    INFO(o.err);
    CHECK(o.exit_code == 2);
    CHECK(has(o.err, "the impulses no longer separate them"));
    CHECK_FALSE(has(o.err, "(a Zeno cascade)"));
    CHECK(has(o.err, R"(set "resting": true in the solver block)"));

    spit(scene, scene_text(R"(,"resting":true)"));
    const Outcome held = run_tool({"run", scene.string(), "--out", out.string()});
    INFO(held.err);
    REQUIRE(held.exit_code == 0);
    // One impact; along its normal both discs then move at the common
    // velocity (m_a v_a + m_b v_b) . n / (m_a + m_b), and across it each
    // keeps its own (frictionless).
    const auto trajectory = nlohmann::json::parse(slurp(out));
    REQUIRE(trajectory["events"].size() == 1);
    const auto& normal = trajectory["events"][0]["normal"];
    const double nx = normal[0].get<double>();
    const double ny = normal[1].get<double>();
    const auto& last = trajectory["frames"].back();
    const auto& columns = trajectory["columns"];
    std::map<std::string, double> at;
    for (std::size_t c = 0; c < columns.size(); ++c) {
        at[columns[c].get<std::string>()] = last[c].get<double>();
    }
    const double common = ((ma * vax + mb * vbx) * nx + (ma * vay + mb * vby) * ny) / (ma + mb);
    CHECK(std::fabs(at["A.vx"] * nx + at["A.vy"] * ny - common) <= 1e-12);
    CHECK(std::fabs(at["B.vx"] * nx + at["B.vy"] * ny - common) <= 1e-12);
    CHECK(std::fabs(at["A.vy"] * nx - at["A.vx"] * ny - (vay * nx - vax * ny)) <= 1e-12);
    CHECK(std::fabs(at["B.vy"] * nx - at["B.vx"] * ny - (vby * nx - vbx * ny)) <= 1e-12);
}

// The plan's five discs of mixed sizes (1:5) and masses (1:100) in an open
// box, e = 0.5 (docs/engine.md, "Dense contact"): a contact begins at rest
// within a step, which the event model cannot hold.
const std::string pile_of_five =
    R"({"schema":"impulse/scene@1","name":"pile","restitution":0.5,"dt":0.016666666666666666,)"
    R"("duration":6,"solver":{"integrator":"verlet","toi":"secant","resting":true,)"
    R"("resting_method":"events"},"bodies":[)"
    R"({"name":"floor","static":true,"shape":{"box":[2,0.5]},"position":[0,-0.5]},)"
    R"({"name":"left","static":true,"shape":{"box":[0.25,1.5]},"position":[-2.25,1.5]},)"
    R"({"name":"right","static":true,"shape":{"box":[0.25,1.5]},"position":[2.25,1.5]},)"
    R"({"name":"p0","shape":{"circle":0.1},"mass":0.05,"position":[-0.9,0.6]},)"
    R"({"name":"p1","shape":{"circle":0.5},"mass":5,"position":[0,0.8]},)"
    R"({"name":"p2","shape":{"circle":0.25},"mass":1.2,"position":[0.7,1.6]},)"
    R"({"name":"p3","shape":{"circle":0.3},"mass":1.8,"position":[-0.5,1.9]},)"
    R"({"name":"p4","shape":{"circle":0.15},"mass":0.4,"position":[0.2,2.6]}]})";

TEST_CASE("with resting_method events, a pile's failure names auto and time-stepping",
          "[resting-method]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "pile.json";
    spit(scene, pile_of_five);
    const fs::path out = tmp.dir / "out.json";
    const Outcome o = run_tool({"run", scene.string(), "--out", out.string()});
    require_one_sentence(o);
    INFO(o.err);
    CHECK(o.err.rfind(scene.string() + ": ", 0) == 0);
    CHECK((has(o.err, "(a Zeno cascade)") || has(o.err, "are in resting contact") ||
           has(o.err, "contact problem")));
    CHECK(has(o.err, R"(use "resting_method": "auto" or "time-stepping")"));
    CHECK_FALSE(has(o.err, "seed's"));
    // What was simulated up to the stop is written, marked partial (docs/formats.md).
    REQUIRE(fs::exists(out));
    CHECK(has(slurp(out), "\"partial\": {\"reason\": "));
}

// The time a sentence states after `marker` ("at t = "), in seconds.
double time_after(const std::string& text, const std::string& marker) {
    const std::size_t at = text.find(marker);
    REQUIRE(at != std::string::npos);
    return std::stod(text.substr(at + marker.size()));
}

TEST_CASE("auto notes once where it leaves events for time-stepping", "[resting-method]") {
    const TempDir tmp;
    const fs::path events = tmp.dir / "events.json";
    spit(events, pile_of_five);
    const Outcome stopped = run_tool({"run", events.string(), "--out", "-"});
    INFO(stopped.err);
    REQUIRE(stopped.exit_code == 2);
    // The same pile with resting_method left at auto.
    std::string text = pile_of_five;
    const std::string method = R"(,"resting_method":"events")";
    text.erase(text.find(method), method.size());
    const fs::path automatic = tmp.dir / "auto.json";
    spit(automatic, text);
    const fs::path out = tmp.dir / "out.json";
    const Outcome o = run_tool({"run", automatic.string(), "--out", out.string()});
    INFO(o.err);
    CHECK(o.exit_code == 0);
    const std::string note = "note: " + automatic.string() +
                             R"(: "resting_method": "auto" switched from events to time-stepping)";
    CHECK(o.err.rfind(note, 0) == 0);
    CHECK(o.err.find('\n') == o.err.size() - 1); // once
    CHECK(has(o.err, R"(set "resting_method": "time-stepping" to use it from the start)"));
    // The switch is the step (of dt = 1/60 s) in which events stopped: that
    // step's start, so the failure lies within one dt after it.
    const double failed = time_after(stopped.err, "at t = ");
    const double switched = time_after(o.err, "at t = ");
    CHECK(switched <= failed);
    CHECK(failed < switched + 0.016666666666666666);
    // Standard error only: the trajectory is as any run's.
    CHECK_FALSE(has(slurp(out), "note"));
    CHECK_FALSE(has(slurp(out), "resting_method"));

    // Time-stepping from the first step is no switch, and says nothing.
    for (const std::string& solver :
         {std::string(R"("resting":true,"stepping":"local")"),
          std::string(R"("resting":true,"resting_method":"time-stepping")")}) {
        std::string from_start = text;
        const std::string resting = R"("resting":true)";
        from_start.replace(from_start.find(resting), resting.size(), solver);
        spit(automatic, from_start);
        const Outcome quiet = run_tool({"run", automatic.string(), "--out", out.string()});
        INFO(solver << ": " << quiet.err);
        CHECK(quiet.exit_code == 0);
        CHECK(quiet.err.empty());
    }
}

TEST_CASE("a scene that time-steps from its start is not refused for tunnelling",
          "[resting-method]") {
    // Under g = 1e9 the ball can reach the ground at sqrt(2 g 0.5) m/s, 316 m
    // per 0.01 s step against a 2 m thickness: refused without ccd under the
    // event model (test_refusals.cpp), not under time-stepping.
    const std::string heavy = R"(,"gravity":[0,-1e9])";
    const auto outcome = [&](const std::string& solver) {
        const TempDir tmp;
        const fs::path scene = tmp.dir / "m.json";
        spit(scene, disc_scene(solver, 1.0, "0.01", heavy));
        return run_tool({"run", scene.string(), "--out", (tmp.dir / "out.json").string()});
    };
    for (const char* solver : {R"({"resting":true,"resting_method":"time-stepping"})",
                               R"({"resting":true,"stepping":"local"})"}) {
        INFO(solver);
        CHECK_FALSE(has(outcome(solver).err, "tunnelling"));
    }
    // auto with world stepping runs events only in steps where no pair can
    // pass through, and takes time-stepping from this one's first step: run,
    // not refused. Events asked for by name are refused, naming both cures.
    const Outcome automatic = outcome(R"({"resting":true})");
    INFO(automatic.err);
    CHECK(automatic.exit_code == 0);
    CHECK_FALSE(has(automatic.err, "tunnelling"));
    const Outcome events = outcome(R"({"resting":true,"resting_method":"events"})");
    require_one_sentence(events);
    CHECK(has(events.err, "tunnelling"));
    CHECK(has(events.err, R"(set "ccd": true or "resting_method": "auto" or "time-stepping" in )"
                          R"(the solver block)"));
}

TEST_CASE("auto with more than 16 dynamic bodies time-steps from its start, so it is not "
          "refused for tunnelling",
          "[resting-method][dense-robust]") {
    // The engine starts "auto" in time-stepping above 16 dynamic bodies,
    // whatever the stepping (starts_in_time_stepping, solver_settings.h); the
    // loader used to count only local stepping, so a pile of 17 falling discs
    // with "resting": true alone was refused for tunnelling the engine cannot
    // do. Discs of radius 0.5 at 0.5 m above the ground under g = 1e9 reach
    // sqrt(2 g 0.5) = 3.2e4 m/s, 316 m per 0.01 s step against their 2 m
    // combined thickness.
    const auto pile = [](int discs) {
        std::string text =
            R"({"schema":"impulse/scene@1","name":"m","dt":0.01,"duration":0.01,"gravity":[0,-1e9],)"
            R"("solver":{"resting":true},"bodies":[)"
            R"({"name":"ground","static":true,"shape":{"box":[50,0.5]},"position":[0,-0.5]})";
        for (int i = 0; i < discs; ++i) {
            text += R"(,{"name":"d)" + std::to_string(i) +
                    R"(","shape":{"circle":0.5},"mass":1,"position":[)" + std::to_string(2 * i) +
                    ",1]}";
        }
        return text + "]}";
    };
    const auto outcome = [](const std::string& text) {
        const TempDir tmp;
        const fs::path scene = tmp.dir / "m.json";
        spit(scene, text);
        return run_tool({"run", scene.string(), "--out", (tmp.dir / "out.json").string()});
    };
    const Outcome seventeen = outcome(pile(17));
    INFO(seventeen.err);
    CHECK(seventeen.exit_code == 0);
    CHECK_FALSE(has(seventeen.err, "tunnelling"));
    // 16 would run events, which test pairs at the ends of a step only; auto
    // takes time-stepping for any step in which a pair could pass through
    // (the next test), so they run too. Asked for by name, events are refused.
    const Outcome sixteen = outcome(pile(16));
    INFO(sixteen.err);
    CHECK(sixteen.exit_code == 0);
    CHECK_FALSE(has(sixteen.err, "tunnelling"));
    std::string events = pile(16);
    const std::string resting = R"("resting":true)";
    events.replace(events.find(resting), resting.size(),
                   R"("resting":true,"resting_method":"events")");
    const Outcome refused = outcome(events);
    require_one_sentence(refused);
    CHECK(has(refused.err, "tunnelling"));
}

TEST_CASE("auto takes time-stepping for a step in which a pair could pass through unseen, "
          "where events would tunnel",
          "[resting-method][dense-robust]") {
    // A disc of radius 0.05 m falling at 20 m/s onto a plate 0.02 m thick (top
    // at y = 0), g = 9.81, dt = 1/60 s: over 1/3 m per step against their
    // combined thickness 0.12 m. From y = 2.15, explicit Euler (the default
    // integrator) puts its centre at 0.109 after 6 steps (0.059 m above the
    // plate) and at -0.241 after 7 (0.19 m below its bottom): neither end of
    // that step overlaps. World stepping, 1 dynamic body: auto
    // begins with events. With e = 0 the disc must end at rest on the plate,
    // its centre r above the plate's top (within the contact tolerance d =
    // 1e-9 m) and its velocity 0. Engine level, 1 s:
    // The world after 1 s (60 steps) under the given resting method.
    const auto one_second = [](impulse::RestingMethod method) {
        impulse::SolverSettings solver; // world stepping, the default
        solver.resting = true;
        solver.resting_method = method;
        impulse::World world = impulse::make_world(
            {impulse::test::static_body(impulse::make_box(1.0, 0.01), {0, -0.01}),
             impulse::test::dynamic_body(impulse::make_circle(0.05), 1.0, {0, 2.15}, 0.0,
                                         {0, -20})},
            {0, -9.81}, 0.0, solver);
        const double dt = 1.0 / 60.0;
        std::vector<impulse::CollisionEvent> events;
        double t = 0.0;
        for (int k = 0; k < 60; ++k) {
            REQUIRE_FALSE(impulse::step(world, t, dt, events));
            t += dt;
        }
        return world;
    };
    const impulse::World automatic = one_second(impulse::RestingMethod::automatic);
    const impulse::BodyState& disc = automatic.bodies[1].state;
    CHECK(automatic.work.time_stepping_for_speed == 1);
    CHECK(automatic.work.time_stepping_from_step > 0); // events carried the first steps
    CHECK(std::abs(disc.position.y - 0.05) <= 1e-9);
    CHECK(disc.velocity.y == 0.0);
    CHECK(disc.position.x == 0.0);

    // The same world under events alone passes through the plate: the tunnel
    // that the loader refuses for "events" (above) and auto avoids.
    const impulse::World events = one_second(impulse::RestingMethod::events);
    CHECK(events.bodies[1].state.position.y < -10.0); // about 2.15 - 20 - 9.81 / 2 m
    CHECK(events.work.collisions == 0);

    // Through the tool: the same scene runs, and the switch is noted once,
    // naming why and ccd as the way to keep the event model.
    const TempDir tmp;
    const fs::path scene = tmp.dir / "plate.json";
    spit(scene, R"({"schema":"impulse/scene@1","name":"plate","dt":0.016666666666666666,)"
                R"("duration":1,"restitution":0,"solver":{"resting":true},"bodies":[)"
                R"({"name":"plate","static":true,"shape":{"box":[1,0.01]},"position":[0,-0.01]},)"
                R"({"name":"disc","shape":{"circle":0.05},"mass":1,"position":[0,2.15],)"
                R"("velocity":[0,-20]}]})");
    const Outcome o = run_tool({"run", scene.string(), "--out", (tmp.dir / "out.json").string()});
    INFO(o.err);
    CHECK(o.exit_code == 0);
    CHECK(o.err.rfind("note: " + scene.string() + R"(: "resting_method": "auto" switched)", 0) ==
          0);
    CHECK(o.err.find('\n') == o.err.size() - 1); // once
    CHECK(has(o.err, "could pass through each other within one step"));
    CHECK(has(o.err, R"(set "ccd": true to keep the event model)"));

    // Started 0.15 m above the plate, within the 0.34 m the first step can
    // close: the switch is that first step, and is noted as any other.
    std::string near = slurp(scene);
    const std::string start = R"("position":[0,2.15])";
    near.replace(near.find(start), start.size(), R"("position":[0,0.2])");
    spit(scene, near);
    const Outcome first = run_tool({"run", scene.string(), "--out", "-"});
    INFO(first.err);
    CHECK(first.exit_code == 0);
    CHECK(first.err.rfind("note: " + scene.string() +
                              R"(: "resting_method": "auto" switched from events to )"
                              R"(time-stepping at t = 0 s, where two bodies could pass through)",
                          0) == 0);
    CHECK(first.err.find('\n') == first.err.size() - 1); // once
}
