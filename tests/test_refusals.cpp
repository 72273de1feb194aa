// Refusals through the real tool (issue items 2, 7 and 9):
//  - a scene a single-precision reference (Box2D) cannot represent is that
//    scene's error, exit 2 with one sentence, never Box2D's abort;
//  - an expectation whose quantity or tolerance is not finite fails;
//  - a scene that could tunnel without ccd is refused (run, check, bless,
//    render, box2d) or warned about (sweep), with the safe dt.
#include "support/files.h"
#include "support/outcome.h"
#include "support/tool.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

// The issue's scene: a ball on the ground, both given here in full so each
// test changes one thing. `ball` is the ball's JSON body without braces.
std::string ball_scene(const std::string& ball, const std::string& extra = "") {
    return R"({"schema":"impulse/scene@1","name":"m","dt":0.01,"duration":0.5)" + extra +
           R"(,"bodies":[{"name":"ground","static":true,"shape":{"box":[5,0.5]},"position":[0,-0.5]},{"name":"ball",)" +
           ball + R"(}],"box2d":{"observables":[{"kind":"energy","atol":1}]}})";
}

const std::string plain_ball = R"("shape":{"circle":0.5},"mass":1,"position":[0,1])";

std::string four_digits(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

} // namespace

// ---------------------------------------------------------------- item 2: single precision

TEST_CASE("box2d refuses a 1e39 kg ball with a sentence instead of aborting", "[refusals]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "m.json";
    spit(scene, ball_scene(R"("shape":{"circle":0.5},"mass":1e39,"position":[0,1])"));

    const Outcome o = run_tool({"box2d", scene.string()});
    require_one_sentence(o);
    CHECK(o.err.rfind(scene.string() + ": bodies[1].mass: ", 0) == 0);
    CHECK(o.err.find("1e39 kg") != std::string::npos);
    CHECK(o.err.find("beyond Box2D's single precision (max 3.4e38") != std::string::npos);

    // The impulse engine is double precision: the same scene runs there.
    const Outcome run = run_tool({"run", scene.string()});
    INFO(run.err);
    CHECK(run.exit_code == 0);
}

TEST_CASE("box2d refuses the issue's scene as given, with no observables", "[refusals]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "m.json";
    spit(
        scene,
        R"({"schema":"impulse/scene@1","name":"m","dt":0.01,"duration":0.5,"bodies":[{"name":"ground","static":true,"shape":{"box":[5,0.5]},"position":[0,-0.5]},{"name":"ball","shape":{"circle":0.5},"mass":1e39,"position":[0,1]}]})");
    const Outcome o = run_tool({"box2d", scene.string()});
    require_one_sentence(o);
    CHECK(o.err.rfind(scene.string() + ": bodies[1].mass: ", 0) == 0);
}

TEST_CASE("sweep refuses a scene Box2D cannot represent before any point runs", "[refusals]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "m.json";
    spit(scene, ball_scene(R"("shape":{"circle":0.5},"mass":1e39,"position":[0,1])"));
    const Outcome o = run_tool({"sweep", scene.string(), "--dt", "0.01", "--integrator", "verlet",
                                "--toi", "secant", "--toi-tolerance", "1e-9", "--repeats", "1"});
    require_one_sentence(o);
    CHECK(o.err.find("bodies[1].mass") != std::string::npos);
    CHECK(o.out.empty());
}

TEST_CASE("every quantity Box2D would hold in a float is checked, huge and tiny", "[refusals]") {
    struct Case {
        const char* what;
        std::string ball;       // the ball's body
        std::string scene_keys; // extra top-level keys
        const char* path;       // the JSON path the sentence must name
    };
    // Inertia and momentum are products: each factor alone fits in a float.
    const std::vector<Case> cases = {
        {"tiny mass", R"("shape":{"circle":0.5},"mass":1e-39,"position":[0,1])", "",
         "bodies[1].mass"},
        {"mass whose inverse overflows", R"("shape":{"circle":0.5},"mass":1e-33,"position":[0,1])",
         "", "bodies[1].mass"},
        {"huge density", R"("shape":{"circle":0.5},"density":1e38,"position":[0,1])", "",
         "bodies[1].mass"},
        {"huge box: inertia m (w^2 + h^2) / 3 overflows",
         R"("shape":{"box":[1e30,1e30]},"mass":1,"position":[0,1e30])",
         // a contact tolerance that resolves a body this large (2^48 d beyond 2.4e30 m)
         R"(,"solver":{"contact_tolerance":1e20})", "bodies[1].inertia"},
        {"heavy wide disc: inertia m r^2 / 2 overflows",
         R"("shape":{"circle":1e5},"mass":1e30,"position":[0,100000])", "", "bodies[1].inertia"},
        {"huge velocity", R"("shape":{"circle":0.5},"mass":1,"position":[0,1],"velocity":[1e39,0])",
         "", "bodies[1].velocity"},
        {"denormal velocity",
         R"("shape":{"circle":0.5},"mass":1,"position":[0,1],"velocity":[1e-40,0])", "",
         "bodies[1].velocity"},
        {"momentum overflows",
         R"("shape":{"circle":0.5},"mass":1e20,"position":[0,1],"velocity":[1e20,0])", "",
         "bodies[1].velocity"},
        {"huge angular velocity",
         R"("shape":{"circle":0.5},"mass":1,"position":[0,1],"angular_velocity":1e39)", "",
         "bodies[1].angular_velocity"},
        {"huge gravity", plain_ball, R"(,"gravity":[0,-1e39])", "gravity"},
        {"tiny radius", R"("shape":{"circle":1e-39},"mass":1,"position":[0,1])", "",
         "bodies[1].shape"},
        {"radius under Box2D's linear slop",
         R"("shape":{"circle":0.001},"mass":1,"position":[0,1])", "", "bodies[1].shape"},
    };
    for (const Case& c : cases) {
        SECTION(c.what) {
            const TempDir tmp;
            const fs::path scene = tmp.dir / "m.json";
            spit(scene, ball_scene(c.ball, c.scene_keys));
            const Outcome o = run_tool({"box2d", scene.string()});
            INFO(c.what << ": " << o.err);
            require_one_sentence(o);
            CHECK(o.err.rfind(scene.string() + ": " + c.path + ": ", 0) == 0);
            CHECK(o.err.find("Box2D") != std::string::npos);
        }
    }
}

TEST_CASE("a listed body beyond 2^48 contact tolerances of the origin is refused at its position",
          "[refusals]") {
    // A double holds x to within x 2^-52, so beyond 2^48 d of the origin a
    // position is held to worse than d / 16 (d = solver.contact_tolerance):
    // touching is decided by rounding there (an outside review moved the
    // canonical pile 1e15 m out and every expectation passed). The refusal
    // comes at load, for every engine and verb (it used to be Box2D's float
    // range alone, at 1e39 m). With d = 1e-9 the limit is 2^48 1e-9 =
    // 281,475 m; the ball reaches |x| + r from the origin.
    const auto ball_at = [](const std::string& x, const std::string& solver) {
        return ball_scene(R"("shape":{"circle":0.5},"mass":1,"position":[)" + x + ",1]", solver);
    };
    for (const char* x : {"1e39", "1e15", "281475"}) {
        const TempDir tmp;
        const fs::path scene = tmp.dir / "m.json";
        spit(scene, ball_at(x, ""));
        for (const char* verb : {"run", "box2d"}) {
            const Outcome o = run_tool({verb, scene.string()});
            INFO(verb << " " << x << ": " << o.err);
            require_one_sentence(o);
            CHECK(o.err.rfind(scene.string() + ": bodies[1].position: puts the body ", 0) == 0);
            CHECK(o.err.find("within 281474.976710656 m of it") != std::string::npos);
        }
    }
    // Just inside (281,474 m, reaching 281,474.5), and 1e6 m out with d = 1e-8
    // (limit 2,814,750 m): both run.
    const TempDir tmp;
    const fs::path inside = tmp.dir / "inside.json", coarser = tmp.dir / "coarser.json";
    spit(inside, ball_at("281474", ""));
    spit(coarser, ball_at("1e6", R"(,"solver":{"contact_tolerance":1e-8})"));
    for (const fs::path& scene : {inside, coarser}) {
        const Outcome o = run_tool({"run", scene.string(), "--out", (tmp.dir / "o.json").string()});
        INFO(scene << ": " << o.err);
        CHECK(o.exit_code == 0);
    }
}

TEST_CASE("box2d still runs a plain scene", "[refusals]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "m.json";
    spit(scene, ball_scene(plain_ball));
    const Outcome o = run_tool({"box2d", scene.string()});
    INFO(o.err);
    CHECK(o.exit_code == 0);
}

// ---------------------------------------------------------------- item 7: non-finite expectations

namespace {

std::string free_scene(const std::string& body, const std::string& expectation,
                       const std::string& solver = "") {
    return R"({"schema":"impulse/scene@1","name":"x","dt":0.01,"duration":1,"gravity":[0,0])" +
           solver + R"(,"bodies":[{"name":"a","shape":{"circle":0.5},)" + body +
           R"(}],"expectations":[)" + expectation + "]}";
}

} // namespace

TEST_CASE("an expectation whose quantity overflows to infinity fails", "[refusals]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "x.json";
    const std::string euler = R"(,"solver":{"integrator":"euler"})";
    const std::string energy = R"({"kind":"energy-non-increasing","rtol":1e-15})";

    SECTION("energy-non-increasing: 1/2 1e300 kg (1e5 m/s)^2 is inf") {
        spit(scene, free_scene(R"("mass":1e300,"velocity":[1e5,0])", energy, euler));
        const Outcome o = run_tool({"run", scene.string(), "--out", (tmp.dir / "t").string()});
        INFO(o.err);
        CHECK(o.exit_code == 1);
        CHECK(o.err.find("expectations[0]") != std::string::npos);
        CHECK(o.err.find("not finite") != std::string::npos);
    }
    SECTION("the same expectation with mass 1 holds (free flight keeps its energy)") {
        spit(scene, free_scene(R"("mass":1,"velocity":[1e5,0])", energy, euler));
        const Outcome o = run_tool({"run", scene.string(), "--out", (tmp.dir / "t").string()});
        INFO(o.err);
        CHECK(o.exit_code == 0);
    }
    SECTION("conserved momentum: 1e300 kg at 1e10 m/s is inf") {
        spit(scene, free_scene(R"("mass":1e300,"velocity":[1e10,0])",
                               R"({"kind":"conserved","quantities":["momentum"],"rtol":1e-12})"));
        const Outcome o = run_tool({"run", scene.string(), "--out", (tmp.dir / "t").string()});
        INFO(o.err);
        CHECK(o.exit_code == 1);
        CHECK(o.err.find("momentum") != std::string::npos);
    }
    SECTION("state: a tolerance atol + rtol |x| that overflows lets nothing pass") {
        // x = 2 exactly, but 1.7e308 + 1.7e308 * 2 is inf: the check cannot be computed.
        spit(
            scene,
            free_scene(R"("mass":1,"position":[2,0])",
                       R"({"kind":"state","body":"a","t":1,"x":2,"atol":1.7e308,"rtol":1.7e308})"));
        const Outcome o = run_tool({"run", scene.string(), "--out", (tmp.dir / "t").string()});
        INFO(o.err);
        CHECK(o.exit_code == 1);
        CHECK(o.err.find("not finite") != std::string::npos);
    }
}

TEST_CASE("an event expectation whose tolerance overflows fails", "[refusals]") {
    // Whatever impulse the landing takes, the allowance 1.7e308 + 1.7e308 x
    // |1| (the expected value is the scale) overflows double's 1.8e308 to
    // inf, and the comparison cannot be computed.
    const TempDir tmp;
    const fs::path scene = tmp.dir / "m.json";
    spit(
        scene,
        R"({"schema":"impulse/scene@1","name":"m","dt":0.01,"duration":0.5,"solver":{"integrator":"verlet"},"bodies":[{"name":"ground","static":true,"shape":{"box":[5,0.5]},"position":[0,-0.5]},{"name":"ball","shape":{"circle":0.5},"mass":1,"position":[0,1]}],"expectations":[{"kind":"event","index":0,"impulse":1,"atol":1.7e308,"rtol":1.7e308}]})");
    const Outcome o = run_tool({"run", scene.string(), "--out", (tmp.dir / "t").string()});
    INFO(o.err);
    CHECK(o.exit_code == 1);
    CHECK(o.err.find("not finite") != std::string::npos);
}

TEST_CASE("bless refuses a scene whose expectation overflows, and writes no golden", "[refusals]") {
    const TempDir root;
    spit(
        root.dir / "harness" / "scenes" / "euler-gain-big.json",
        R"({"schema":"impulse/scene@1","name":"euler-gain-big","dt":0.01,"duration":1,"solver":{"integrator":"euler"},"bodies":[{"name":"a","shape":{"circle":0.5},"mass":1e300,"velocity":[1e5,0]}],"expectations":[{"kind":"energy-non-increasing","rtol":1e-15}]})");
    fs::create_directories(root.dir / "goldens");
    const Outcome o = run_tool({"bless", "--root", root.dir.string()});
    INFO(o.out << o.err);
    CHECK(o.exit_code == 1);
    CHECK(o.out.find("REFUSED") != std::string::npos);
    CHECK_FALSE(fs::exists(root.dir / "goldens" / "euler-gain-big.json"));
}

// ---------------------------------------------------------------- item 9: tunnelling

namespace {

// A 0.05 m disc at 1e15 m/s toward a 0.04 m wall 10 m away, no gravity.
std::string bullet_scene(const std::string& name, bool ccd) {
    return R"({"schema":"impulse/scene@1","name":")" + name +
           R"(","dt":0.01,"duration":0.05,"gravity":[0,0],"solver":{"integrator":"verlet","ccd":)" +
           (ccd ? "true" : "false") +
           R"(},"bodies":[{"name":"wall","static":true,"shape":{"box":[0.02,1]},"position":[0,0]},{"name":"bullet","shape":{"circle":0.05},"mass":1,"position":[-10,0],"velocity":[1e15,0]}],"box2d":{"observables":[{"kind":"energy","atol":1}]}})";
}

} // namespace

TEST_CASE("run refuses a scene that gravity makes tunnel, with the safe dt", "[refusals]") {
    // Under g = 1e9 the ball's lowest point falls from y = 0.5 to the
    // ground's top, y = 0: h = 0.5 m, so it can arrive at sqrt(2 g h) m/s
    // (g * duration = 5e8 is larger). The pair's thickness is 2 (0.5 + 0.5)
    // = 2 m, so dt must be below 2 / sqrt(2 g h).
    const TempDir tmp;
    const fs::path scene = tmp.dir / "m.json";
    spit(scene, ball_scene(plain_ball, R"(,"gravity":[0,-1e9])"));
    const fs::path out = tmp.dir / "out.json";
    const Outcome o = run_tool({"run", scene.string(), "--out", out.string()});
    require_one_sentence(o);
    CHECK(o.err.rfind(scene.string() + ": bodies[1]: ", 0) == 0);
    CHECK(o.err.find("'ball' and 'ground'") != std::string::npos);
    CHECK(o.err.find("dt below " + four_digits(2.0 / std::sqrt(2.0 * 1e9 * 0.5)) + " s") !=
          std::string::npos);
    CHECK(o.err.find("\"ccd\": true") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("a long run under gravity is bounded by its drop, not by g times its duration",
          "[refusals]") {
    // 60 s at 1/60: g * duration is 589 m/s, 9.8 m per step, past the 2 m
    // thickness; but a ball bouncing on the ground never falls more than
    // h = 0.5 m, sqrt(2 g h) = 3.1 m/s, 0.05 m per step: not refused.
    const TempDir tmp;
    const fs::path scene = tmp.dir / "m.json";
    spit(
        scene,
        R"({"schema":"impulse/scene@1","name":"m","dt":0.016666666666666666,"duration":60,"restitution":1,"solver":{"integrator":"verlet"},"bodies":[{"name":"ground","static":true,"shape":{"box":[5,0.5]},"position":[0,-0.5]},{"name":"ball","shape":{"circle":0.5},"mass":1,"position":[0,1]}]})");
    const Outcome o = run_tool({"run", scene.string(), "--out", (tmp.dir / "t").string()});
    INFO(o.err);
    CHECK(o.exit_code == 0);
}

TEST_CASE("every verb that simulates refuses a disc at 1e15 m/s through a wall", "[refusals]") {
    const TempDir root;
    const fs::path scene = root.dir / "harness" / "scenes" / "fast.json";
    spit(scene, bullet_scene("fast", false));
    fs::create_directories(root.dir / "goldens");
    const std::string safe = "dt below " + four_digits(2.0 * (0.05 + 0.02) / 1e15) + " s";
    const std::string r = root.dir.string();

    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {"run", scene.string()},
             {"bless", "--root", r, "fast"},
             {"box2d", "--root", r, "fast"},
             {"render", scene.string(), "--out", (root.dir / "fast.svg").string()}}) {
        const Outcome o = run_tool(args);
        INFO(args.front() << ": " << o.err);
        require_one_sentence(o);
        CHECK(o.err.find(scene.string() + ": bodies[1]: 'bullet' and 'wall'") != std::string::npos);
        CHECK(o.err.find(safe) != std::string::npos);
    }
    CHECK_FALSE(fs::exists(root.dir / "goldens" / "fast.json"));
    CHECK_FALSE(fs::exists(root.dir / "fast.svg"));

    // check puts the sentence in the scene's ERROR row.
    const Outcome check = run_tool({"check", "--root", r, "fast"});
    INFO(check.out);
    CHECK(check.exit_code == 2);
    CHECK(check.out.find("ERROR") != std::string::npos);
    CHECK(check.out.find(safe) != std::string::npos);
}

TEST_CASE("with ccd on the same disc is not refused for tunnelling", "[refusals]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "fast.json";
    spit(scene, bullet_scene("fast", true));
    const Outcome o = run_tool({"run", scene.string(), "--out", (tmp.dir / "t").string()});
    INFO(o.err);
    CHECK(o.err.find("tunnelling") == std::string::npos);
}

TEST_CASE("sweep warns per time step that can tunnel and still runs", "[refusals]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "fast.json";
    spit(scene, bullet_scene("fast", false));
    const Outcome o = run_tool({"sweep", scene.string(), "--dt", "0.01,0.005", "--integrator",
                                "verlet", "--toi", "secant", "--toi-tolerance", "1e-9", "--ccd",
                                "off,on", "--no-box2d", "--repeats", "1"});
    INFO(o.err);
    CHECK(o.exit_code == 0);
    // One warning per dt run with ccd off, none for the ccd points.
    std::size_t warnings = 0;
    for (std::size_t at = o.err.find("warning: "); at != std::string::npos;
         at = o.err.find("warning: ", at + 1)) {
        ++warnings;
    }
    CHECK(warnings == 2);
    CHECK(o.err.find("dt 0.01, ccd off") != std::string::npos);
    CHECK(o.err.find("dt 0.005, ccd off") != std::string::npos);
}
