// examples/engines/python-seed behind the gate, as a user of another
// repository runs it (issue 13's "done when"): a project whose impulse.json
// names `python3 engine/engine.py`, copies of canonical scenes, then bless,
// check, a change of the engine's physics that check names down to body,
// channel, time and size, regen, and conform telling the correct engine from
// the changed one. Every number asserted comes from the scene's physics
// (harness/scene/exact_answers.h), never from the engine's earlier output.
#include "exact_answers.h"
#include "scene.h"
#include "support/files.h"
#include "support/outcome.h"
#include "support/tool.h"
#include "support/tool_in_folder.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using impulse::harness::DropLadder;
using impulse::harness::Scene;
using namespace impulse::test;

namespace {

const fs::path source_dir = IMPULSE_SOURCE_DIR;
const fs::path seed_dir = source_dir / "examples" / "engines" / "python-seed";

// The user's repository: python-seed copied to engine/, impulse.json naming
// it, and in scenes/ copies of drop-circle and head-on (with their exact
// answers) and `bounce`, drop-circle renamed and without expectations: a
// scene of the user's own, whose golden alone says what the engine does.
struct SeedProject {
    TempDir temp;
    fs::path dir = temp.dir / "project";
    fs::path engine = dir / "engine" / "engine.py";

    SeedProject() {
        REQUIRE(fs::exists(IMPULSE_PYTHON3)); // scripts/setup installs python3
        for (const char* file : {"engine.py", "README.md"}) {
            spit(dir / "engine" / file, slurp(seed_dir / file));
        }
        spit(dir / "impulse.json", R"({"schema": "impulse/project@1", "scenes": ["scenes"],
            "engines": [{"name": "python-seed", "command": ["python3", "engine/engine.py"],
                         "time_limit": 60}]})");
        for (const char* name : {"drop-circle", "head-on"}) {
            spit(dir / "scenes" / (std::string(name) + ".json"),
                 slurp(source_dir / "harness" / "scenes" / (std::string(name) + ".json")));
        }
        nlohmann::json bounce =
            nlohmann::json::parse(slurp(source_dir / "harness" / "scenes" / "drop-circle.json"));
        bounce["name"] = "bounce";
        bounce.erase("expectations");
        spit(dir / "scenes" / "bounce.json", bounce.dump(2));
    }

    fs::path golden(const std::string& name) const { return dir / "goldens" / (name + ".json"); }

    // Eq. 9's marked line with (1 + e) made (1 + factor e): the restitution
    // the engine applies is factor e, and nothing else changes.
    void scale_restitution(const std::string& factor) const {
        const std::string marker = "# Eq. 9: j (tests/test_python_seed.cpp breaks this line)";
        std::string source = slurp(seed_dir / "engine.py");
        const std::size_t line = source.find(marker);
        REQUIRE(line != std::string::npos);
        const std::size_t at = source.find("(1.0 + e)", source.rfind('\n', line) + 1);
        REQUIRE(at < line);
        source.replace(at, 9, "(1.0 + " + factor + " * e)");
        spit(engine, source);
    }
    void restore_engine() const { spit(engine, slurp(seed_dir / "engine.py")); }
};

// The drop of drop-circle's ball, from the scene's own parameters.
DropLadder drop_circle_ladder(const fs::path& scene_file) {
    const Scene scene = impulse::harness::load_scene(scene_file.string());
    for (const impulse::harness::SceneBody& body : scene.bodies) {
        if (body.name == "ball") {
            return *impulse::harness::drop_ladder(scene, body);
        }
    }
    FAIL("drop-circle has no ball");
    throw;
}

// Height of the ball's centre `s` seconds after impact 1, rebounding at `v`:
// its radius above the ground (the ground's top is y = 0), then the parabola.
double centre_after_impact(const Scene& scene, double v, double s) {
    double radius = 0.0;
    for (const impulse::harness::SceneBody& body : scene.bodies) {
        radius = body.name == "ball" ? body.shape.radius : radius;
    }
    return radius + v * s + 0.5 * scene.gravity.y * s * s;
}

// One line of check's "first divergence per body and channel" table:
// "  CHANNEL  t = T  golden A  new B  ...", in the section of `scene`.
struct Divergence {
    double t = 0.0, golden = 0.0, now = 0.0;
};
Divergence divergence(const std::string& out, const std::string& scene,
                      const std::string& channel) {
    const std::size_t section = out.find("\n" + scene + " (");
    REQUIRE(section != std::string::npos);
    const std::size_t line = out.find("\n  " + channel + " ", section);
    REQUIRE(line != std::string::npos);
    std::istringstream in(out.substr(line, out.find('\n', line + 1) - line));
    std::string name, t_word, equals, golden_word, new_word;
    Divergence d;
    in >> name >> t_word >> equals >> d.t >> golden_word >> d.golden >> new_word >> d.now;
    REQUIRE(!in.fail());
    CHECK(name == channel);
    CHECK(golden_word == "golden");
    CHECK(new_word == "new");
    return d;
}

const nlohmann::json& result_of(const nlohmann::json& card, const std::string& scene,
                                const std::string& check) {
    for (const nlohmann::json& s : card["scenes"]) {
        if (s["name"] == scene) {
            for (const nlohmann::json& r : s["engines"][0]["results"]) {
                if (r["check"] == check) {
                    return r;
                }
            }
        }
    }
    FAIL("no check '" << check << "' of " << scene << " in the scorecard");
    throw;
}

} // namespace

TEST_CASE("python-seed behind the gate: bless, check, a change of physics named, regen, check",
          "[python-seed-gate]") {
    const SeedProject p;
    const Outcome blessed = run_tool_in(p.dir, {"bless"});
    require_exit(blessed, 0);
    for (const char* name : {"bounce", "drop-circle", "head-on"}) {
        INFO(name);
        CHECK(has(blessed.out, std::string("new        ") + name));
        REQUIRE(fs::is_regular_file(p.golden(name)));
        // The golden is the harness's, in canonical form, naming the engine.
        CHECK(has(slurp(p.golden(name)), "\"engine\": \"python-seed 1.0\""));
    }
    require_exit(run_tool_in(p.dir, {"check"}), 0);

    // A subtle change of physics: restitution 1.1 e at every impact.
    // (README's "breaking it on purpose" uses 0.9 e, but then the drop's
    // bounces die out within drop-circle's 3 s, a Zeno cascade the seed's
    // loop stops on with exit 1: an engine failure, not a changed answer.)
    p.scale_restitution("1.1");
    const std::string drop_golden = slurp(p.golden("drop-circle"));
    const Outcome changed = run_tool_in(p.dir, {"check"});
    require_exit(changed, 1);
    CHECK(has(changed.out, "FAILED drop-circle "));
    CHECK(has(changed.out, "FAILED bounce "));
    CHECK(has(changed.out, "3 scenes: 0 passed, 3 failed, 0 errors"));
    // head-on's row names body, channel, time and size in one line.
    const std::size_t row = changed.out.find("FAILED head-on ");
    REQUIRE(row != std::string::npos);
    const std::string head_on = changed.out.substr(row, changed.out.find('\n', row) - row);
    CHECK(has(head_on, "first divergence: "));
    CHECK(has(head_on, " at t = "));
    CHECK(has(head_on, " s (golden "));
    CHECK(has(head_on, ", new "));
    // drop-circle's table: the ball's height in the first frame after impact
    // 1, rebounding at e v1 in the golden and 1.1 e v1 now.
    const Scene scene = impulse::harness::load_scene((p.dir / "scenes/drop-circle.json").string());
    const DropLadder drop = drop_circle_ladder(p.dir / "scenes/drop-circle.json");
    const Divergence y = divergence(changed.out, "drop-circle", "ball.y");
    CHECK(y.t > drop.t1());
    CHECK(y.t <= drop.t1() + scene.dt * (1.0 + 1e-9));
    const double s = y.t - drop.t1();
    CHECK(y.golden == Approx(centre_after_impact(scene, drop.rebound_speed(1), s)).epsilon(1e-9));
    CHECK(y.now ==
          Approx(centre_after_impact(scene, 1.1 * drop.rebound_speed(1), s)).epsilon(1e-9));

    // regen refuses to bless a run that breaks the scene's own exact
    // answers, and then writes no golden at all (all or nothing).
    const std::string bounce_golden = slurp(p.golden("bounce"));
    const Outcome regen = run_tool_in(p.dir, {"regen"});
    require_exit(regen, 1);
    CHECK(has(regen.out, "held back  bounce: would be changed"));
    CHECK(has(regen.out, "REFUSED    drop-circle: the run breaks "));
    CHECK(has(regen.out, "REFUSED    head-on: the run breaks "));
    CHECK(has(regen.out, "no golden was written"));
    CHECK(slurp(p.golden("bounce")) == bounce_golden);
    // --partial accepts the change where no exact answer says otherwise.
    const Outcome partial = run_tool_in(p.dir, {"regen", "--partial"});
    require_exit(partial, 1);
    CHECK(has(partial.out, "changed    bounce"));
    CHECK(has(partial.out, "drop-circle and head-on were not regenerated"));
    CHECK(slurp(p.golden("drop-circle")) == drop_golden);
    require_exit(run_tool_in(p.dir, {"check", "bounce"}), 0);

    // Back to the seed's physics: bounce's accepted golden is now the change.
    p.restore_engine();
    const Outcome back = run_tool_in(p.dir, {"check"});
    require_exit(back, 1);
    CHECK(has(back.out, "  ok     drop-circle "));
    CHECK(has(back.out, "  ok     head-on "));
    CHECK(has(back.out, "FAILED bounce "));
    const Outcome regen_back = run_tool_in(p.dir, {"regen"});
    require_exit(regen_back, 0);
    CHECK(has(regen_back.out, "changed    bounce"));
    CHECK(has(regen_back.out, "unchanged  drop-circle"));
    const Outcome passes = run_tool_in(p.dir, {"check"});
    require_exit(passes, 0);
    CHECK(has(passes.out, "3 scenes: 3 passed, 0 failed, 0 errors"));
}

TEST_CASE("conform tells python-seed from python-seed with its restitution changed",
          "[python-seed-gate]") {
    const SeedProject p;
    // bullet asks for continuous collision detection, which the seed refuses:
    // a skip, and the other scenes decide.
    const Outcome correct =
        run_tool_in(p.dir, {"conform", "--engine", "python-seed", "drop-circle", "head-on",
                            "bullet", "--no-box2d", "--junit", "conform.xml"});
    require_exit(correct, 0);
    CHECK(has(correct.out, "  ok      drop-circle "));
    CHECK(has(correct.out, "  ok      head-on "));
    CHECK(has(correct.out, "  skipped bullet "));
    CHECK(has(correct.out, "unsupported by python-seed: solver.ccd"));
    CHECK(has(correct.out, "3 scenes: 2 passed, 0 failed, 1 unsupported, 0 errors"));
    const std::string xml = slurp(p.dir / "conform.xml");
    CHECK(has(xml, "<testsuite name=\"impulse.conform.python-seed\""));
    CHECK(has(xml, "<skipped message=\"unsupported by python-seed: solver.ccd"));
    CHECK_FALSE(has(xml, "<failure"));

    // Without --engine, the project's first engine.
    p.scale_restitution("1.1");
    const Outcome wrong =
        run_tool_in(p.dir, {"conform", "drop-circle", "--no-box2d", "--json", "card.json"});
    require_exit(wrong, 1);
    CHECK(has(wrong.out, "FAILED  drop-circle "));
    CHECK(line_after(wrong.out, "impact 1 rebound speed ").rfind("NO: off by ", 0) == 0);
    const nlohmann::json card = nlohmann::json::parse(slurp(p.dir / "card.json"));
    CHECK(card["engine"] == "python-seed");
    CHECK(card["passed"] == false);
    // The rebound: exact e v1, the engine's 1.1 e v1 (within the bisection's 1e-9).
    const DropLadder drop = drop_circle_ladder(p.dir / "scenes/drop-circle.json");
    const nlohmann::json& r =
        result_of(card, "drop-circle", "drop of 'ball': impact 1 rebound speed");
    CHECK(r["within"] == false);
    CHECK(r["exact"].get<double>() == Approx(drop.rebound_speed(1)).epsilon(1e-12));
    CHECK(r["value"].get<double>() == Approx(1.1 * drop.rebound_speed(1)).epsilon(1e-9));
    CHECK(r["rel_error"].get<double>() == Approx(0.1).epsilon(1e-6));
    // The impulse engine beside it, for scale, passes the same checks.
    const nlohmann::json& scene = card["scenes"][0];
    CHECK(scene["engines"][1]["engine"] == "impulse");
    CHECK(scene["engines"][1]["outcome"] == "passed");
}
