// Scene loading, the top level (docs/design.md, "Scene format"): every documented
// default, the fingerprint, the file, the text, the top-level keys, the solver
// block and stepping, each rejected input checked for the file name, the exact
// JSON path and the reason (support/scene_text.h).
#include "input_error.h"
#include "scene.h"
#include "sha256.h"
#include "support/scene_text.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

using impulse::Integrator;
using impulse::ShapeType;
using impulse::Vec2;
using impulse::harness::InputError;
using impulse::harness::load_scene;
using impulse::harness::parse_scene;
using impulse::harness::Scene;
using impulse::harness::step_count;
using namespace impulse::test;

namespace {

std::filesystem::path unique_temp_path(const std::string& stem) {
    std::random_device random;
    return std::filesystem::temp_directory_path() /
           (stem + "-" + std::to_string(random()) + std::to_string(random()));
}

} // namespace

// ---------------------------------------------------------------- accepted scenes

TEST_CASE("a minimal scene gets every documented default", "[scene]") {
    const Scene scene = parse_scene(R"({
        "schema": "impulse/scene@1", "name": "minimal", "dt": 0.01, "duration": 1,
        "bodies": [{"name": "ball", "shape": {"circle": 0.5}}]
    })",
                                    test_file);
    CHECK(scene.file == test_file);
    CHECK(scene.name == "minimal");
    CHECK(scene.description.empty());
    CHECK(scene.gravity.x == 0.0);
    CHECK(scene.gravity.y == -9.81);
    CHECK(scene.restitution == 1.0);
    CHECK(scene.dt == 0.01);
    CHECK(scene.duration == 1.0);
    CHECK(scene.solver.integrator == Integrator::euler);
    CHECK(scene.solver.toi == impulse::TimeOfImpactMethod::bisection);
    CHECK(scene.solver.toi_tolerance == 1e-12);
    CHECK(scene.solver.contact_tolerance == 1e-9);
    CHECK(scene.solver.contacts == impulse::ContactMode::single);
    CHECK_FALSE(scene.solver.ccd);
    CHECK_FALSE(scene.solver.resting);
    CHECK(scene.warnings.empty());
    CHECK(scene.sha256.size() == 64);

    REQUIRE(scene.bodies.size() == 1);
    const impulse::harness::SceneBody& ball = scene.bodies[0];
    CHECK(ball.name == "ball");
    CHECK_FALSE(ball.is_static);
    CHECK(ball.shape.type == ShapeType::circle);
    CHECK(ball.shape.radius == 0.5);
    CHECK(ball.position == Vec2{0.0, 0.0});
    CHECK(ball.angle == 0.0);
    CHECK(ball.velocity == Vec2{0.0, 0.0});
    CHECK(ball.angular_velocity == 0.0);
    CHECK(ball.rotation);
    // Neither mass nor density: density 1 kg/m^2.
    const double pi = 3.141592653589793;
    CHECK(ball.mass == Approx(pi * 0.25).epsilon(1e-15));
    CHECK(ball.inertia == Approx(ball.mass * 0.25 / 2.0).epsilon(1e-14));
}

TEST_CASE("the design's example scene loads with every value it states", "[scene]") {
    const Scene scene = parse_scene(R"({
  "schema": "impulse/scene@1",
  "name": "drop-tilted",
  "description": "2x1 box, 30 degrees, dropped onto static ground; e = 0.8",
  "gravity": [0, -9.81],
  "restitution": 0.8,
  "dt": 0.016666666666666666,
  "duration": 3.0,
  "solver": { "integrator": "symplectic-euler", "toi": "bisection",
              "toi_tolerance": 1e-12, "contact_tolerance": 1e-9 },
  "bodies": [
    { "name": "ground", "static": true, "shape": { "box": [50, 0.5] }, "position": [0, -0.5] },
    { "name": "box", "shape": { "box": [1, 0.5] }, "mass": 1, "position": [0, 3],
      "angle": 0.5235987755982988, "velocity": [0, 0], "angular_velocity": 0 }
  ]
})",
                                    "harness/scenes/drop-tilted.json");
    CHECK(scene.name == "drop-tilted");
    CHECK(scene.description == "2x1 box, 30 degrees, dropped onto static ground; e = 0.8");
    CHECK(scene.restitution == 0.8);
    CHECK(scene.solver.integrator == Integrator::symplectic_euler);
    CHECK(step_count(scene) == 180);
    REQUIRE(scene.bodies.size() == 2);
    const auto& ground = scene.bodies[0];
    CHECK(ground.is_static);
    CHECK(ground.mass == 0.0);
    CHECK(ground.inertia == 0.0);
    CHECK(ground.position == Vec2{0.0, -0.5});
    const auto& box = scene.bodies[1];
    CHECK(box.mass == 1.0);
    CHECK(box.angle == 0.5235987755982988);
    CHECK(box.shape.type == ShapeType::polygon);
    CHECK(box.shape.polygon.count == 4);
}

TEST_CASE("every integrator name is accepted and round-trips", "[scene]") {
    for (const Integrator integrator :
         {Integrator::euler, Integrator::symplectic_euler, Integrator::verlet, Integrator::rk4}) {
        const std::string name = impulse::harness::integrator_name(integrator);
        const Scene scene =
            parse_scene(scene_with(R"("solver": {"integrator": ")" + name + R"("},)"), test_file);
        CHECK(scene.solver.integrator == integrator);
        Integrator back = Integrator::euler;
        CHECK(impulse::harness::integrator_from_name(name, back));
        CHECK(back == integrator);
    }
    Integrator unchanged = Integrator::rk4;
    CHECK_FALSE(impulse::harness::integrator_from_name("leapfrog", unchanged));
    CHECK(unchanged == Integrator::rk4);
    CHECK(std::string(impulse::harness::toi_method_name(impulse::TimeOfImpactMethod::bisection)) ==
          "bisection");
    CHECK(std::string(impulse::harness::contact_mode_name(impulse::ContactMode::single)) ==
          "single");
}

TEST_CASE("settings that have one value in this version may be stated", "[scene]") {
    const Scene scene = parse_scene(
        scene_with(
            R"("solver": {"toi": "bisection", "contacts": "single", "ccd": false, "resting": false,
                          "toi_tolerance": 1e-10, "contact_tolerance": 1e-6},)"),
        test_file);
    CHECK(scene.solver.toi_tolerance == 1e-10);
    CHECK(scene.solver.contact_tolerance == 1e-6);
}

TEST_CASE("the fingerprint is of the content, not the layout", "[scene]") {
    const std::string compact =
        R"({"schema":"impulse/scene@1","name":"t","dt":0.01,"duration":1,"bodies":[{"name":"ball","shape":{"circle":0.5}}]})";
    const std::string spread = R"({
        "bodies": [ { "shape": { "circle": 0.5 }, "name": "ball" } ],
        "duration": 1,
        "dt": 0.01,
        "name": "t",
        "schema": "impulse/scene@1"
    })";
    const std::string changed =
        R"({"schema":"impulse/scene@1","name":"t","dt":0.01,"duration":2,"bodies":[{"name":"ball","shape":{"circle":0.5}}]})";
    const Scene a = parse_scene(compact, test_file);
    const Scene b = parse_scene(spread, "other.json");
    const Scene c = parse_scene(changed, test_file);
    CHECK(a.sha256 == b.sha256);
    CHECK(a.sha256 != c.sha256);
    // `1` and `1.0` are the same number, so the same scene.
    std::string as_float = compact;
    as_float.replace(as_float.find("\"duration\":1"), 12, "\"duration\":1.0");
    CHECK(parse_scene(as_float, test_file).sha256 == a.sha256);
    // Canonical: keys sorted, no whitespace, every number written as a double.
    CHECK(
        a.sha256 ==
        impulse::harness::sha256_hex(
            R"({"bodies":[{"name":"ball","shape":{"circle":0.5}}],"dt":0.01,"duration":1.0,"name":"t","schema":"impulse/scene@1"})"));
}

TEST_CASE("step_count rounds a near-integer ratio and otherwise rounds up", "[scene]") {
    Scene scene;
    scene.duration = 3.0;
    scene.dt = 1.0 / 60.0;
    CHECK(step_count(scene) == 180);
    scene.duration = 1.0;
    scene.dt = 0.3;
    CHECK(step_count(scene) == 4);
    scene.duration = 1.0;
    scene.dt = 0.1;
    CHECK(step_count(scene) == 10);
}

// ---------------------------------------------------------------- the file

TEST_CASE("load_scene reads a file and names it", "[scene]") {
    const std::filesystem::path path = unique_temp_path("impulse-scene");
    {
        std::ofstream out(path, std::ios::binary);
        out << scene_with("");
    }
    const Scene scene = load_scene(path.string());
    CHECK(scene.file == path.string());
    CHECK(scene.name == "t");
    std::filesystem::remove(path);
}

TEST_CASE("load_scene refuses what it cannot read", "[scene]") {
    SECTION("a missing file") {
        const std::string path = unique_temp_path("impulse-missing").string();
        CHECK_THROWS_AS(load_scene(path), InputError);
        CHECK_THROWS_WITH(load_scene(path), Catch::StartsWith(path + ": cannot be read ("));
    }
    SECTION("a directory") {
        const std::string path = std::filesystem::temp_directory_path().string();
        CHECK_THROWS_AS(load_scene(path), InputError);
        CHECK_THROWS_WITH(load_scene(path), Catch::StartsWith(path + ": cannot be read ("));
    }
    SECTION("a file over 16 MiB") {
        const std::filesystem::path path = unique_temp_path("impulse-large");
        {
            std::ofstream out(path, std::ios::binary);
            const std::string block(1024 * 1024, ' ');
            for (int i = 0; i < 16; ++i) {
                out << block;
            }
            out << "{}";
        }
        CHECK_THROWS_WITH(load_scene(path.string()),
                          Catch::StartsWith(path.string() + ": is too large"));
        std::filesystem::remove(path);
    }
}

// ---------------------------------------------------------------- rejected: the text

TEST_CASE("text that is not a JSON scene document is refused", "[scene]") {
    SECTION("merge-conflict marker") {
        require_rejected("{\n<<<<<<< HEAD\n  \"name\": \"a\",\n=======\n  \"name\": "
                         "\"b\",\n>>>>>>> branch\n}",
                         "", "has a merge-conflict marker at line 2");
    }
    SECTION("nested deeper than 64 levels") {
        require_rejected(std::string(65, '[') + std::string(65, ']'), "", "nested too deeply");
    }
    SECTION("64 levels is not too deep") {
        require_rejected(std::string(64, '[') + std::string(64, ']'), "", "must be a JSON object");
    }
    SECTION("brackets inside strings do not count as nesting") {
        CHECK(
            rejection(scene_with(R"("description": ")" + std::string(100, '[') + R"(",)")).empty());
    }
    SECTION("not JSON") {
        require_rejected(R"({"schema": "impulse/scene@1", "name": tru})", "",
                         "not valid JSON: line 1, column");
    }
    SECTION("empty") {
        require_rejected("", "", "not valid JSON");
    }
    SECTION("a number too large for a double") {
        require_rejected(scene_with(R"("restitution": 1e400,)"), "", "not valid JSON");
    }
    SECTION("duplicate top-level key") {
        require_rejected(scene_with(R"("dt": 0.02,)"), "dt", "more than once");
    }
    SECTION("duplicate key deep inside") {
        require_rejected(scene_with_bodies(R"([{"name": "a", "shape": {"circle": 1}},
            {"name": "b", "shape": {"box": [1, 1]}, "position": [5, 0], "mass": 1, "mass": 2}])"),
                         "bodies[1].mass", "more than once");
    }
    SECTION("duplicate key in a polygon's object-valued sibling") {
        require_rejected(scene_with_body(R"("shape": {"polygon": [[-1, -1], [1, -1], [0, 1]],
                                                      "polygon": [[-1, -1], [1, -1], [0, 1]]})"),
                         "bodies[0].shape.polygon", "more than once");
    }
    SECTION("top level not an object") {
        require_rejected("[1, 2]", "", "must be a JSON object, got an array");
    }
}

// ---------------------------------------------------------------- rejected: scene keys

TEST_CASE("unknown top-level keys are refused", "[scene]") {
    SECTION("a typo") {
        require_rejected(scene_with(R"("gravty": [0, -1],)"), "gravty",
                         "unknown key (did you mean gravity?)");
    }
    SECTION("a key that is not an identifier is quoted in the path") {
        require_rejected(scene_with(R"("we ird": 1,)"), R"(["we ird"])", "unknown key");
    }
}

TEST_CASE("schema", "[scene]") {
    SECTION("missing") {
        require_rejected(R"({"name": "t"})", "schema", "is required");
    }
    SECTION("a later version") {
        require_rejected(R"({"schema": "impulse/scene@2", "name": "t"})", "schema",
                         "unsupported scene version");
    }
    SECTION("another kind of file") {
        require_rejected(R"({"schema": "impulse/trajectory@1", "frames": []})", "schema",
                         "not a scene");
    }
    SECTION("not a string") {
        require_rejected(R"({"schema": 1})", "schema", "not a scene");
    }
}

TEST_CASE("scene name", "[scene]") {
    const std::string rest = R"(, "dt": 0.01, "duration": 1,
        "bodies": [{"name": "ball", "shape": {"circle": 0.5}}]})";
    SECTION("missing") {
        require_rejected(R"({"schema": "impulse/scene@1")" + rest, "name", "is required");
    }
    SECTION("not a string") {
        require_rejected(R"({"schema": "impulse/scene@1", "name": 7)" + rest, "name",
                         "must be a string");
    }
    SECTION("a path") {
        require_rejected(R"({"schema": "impulse/scene@1", "name": "../escape")" + rest, "name",
                         "letters, digits");
    }
    SECTION("a leading dot") {
        require_rejected(R"({"schema": "impulse/scene@1", "name": ".hidden")" + rest, "name",
                         "starting with a letter or digit");
    }
    SECTION("empty") {
        require_rejected(R"({"schema": "impulse/scene@1", "name": "")" + rest, "name",
                         "letters, digits");
    }
    SECTION("65 characters") {
        require_rejected(R"({"schema": "impulse/scene@1", "name": ")" + std::string(65, 'a') +
                             "\"" + rest,
                         "name", "1 to 64");
    }
    SECTION("64 characters is allowed") {
        CHECK(rejection(R"({"schema": "impulse/scene@1", "name": ")" + std::string(64, 'a') + "\"" +
                        rest)
                  .empty());
    }
}

TEST_CASE("description, gravity and restitution", "[scene]") {
    SECTION("description not a string") {
        require_rejected(scene_with(R"("description": ["x"],)"), "description", "must be a string");
    }
    SECTION("gravity not a pair") {
        require_rejected(scene_with(R"("gravity": [1],)"), "gravity", "two numbers [x, y]");
    }
    SECTION("gravity component not a number") {
        require_rejected(scene_with(R"("gravity": [0, "down"],)"), "gravity[1]",
                         "must be a number, got \"down\"");
    }
    SECTION("restitution above 1") {
        require_rejected(scene_with(R"("restitution": 1.5,)"), "restitution",
                         "must be between 0 and 1, got 1.5");
    }
    SECTION("restitution below 0") {
        require_rejected(scene_with(R"("restitution": -0.1,)"), "restitution",
                         "must be between 0 and 1, got -0.1");
    }
    SECTION("restitution not a number") {
        require_rejected(scene_with(R"("restitution": null,)"), "restitution",
                         "must be a number, got null");
    }
}

TEST_CASE("dt and duration", "[scene]") {
    const std::string head = R"({"schema": "impulse/scene@1", "name": "t", )";
    const std::string bodies = R"("bodies": [{"name": "ball", "shape": {"circle": 0.5}}]})";
    SECTION("dt missing") {
        require_rejected(head + R"("duration": 1, )" + bodies, "dt", "is required");
    }
    SECTION("dt zero") {
        require_rejected(head + R"("dt": 0, "duration": 1, )" + bodies, "dt", "must be > 0, got 0");
    }
    SECTION("dt negative") {
        require_rejected(head + R"("dt": -0.5, "duration": 1, )" + bodies, "dt",
                         "must be > 0, got -0.5");
    }
    SECTION("dt a string") {
        require_rejected(head + R"("dt": "0.01", "duration": 1, )" + bodies, "dt",
                         "must be a number");
    }
    SECTION("duration missing") {
        require_rejected(head + R"("dt": 0.01, )" + bodies, "duration", "is required");
    }
    SECTION("duration zero") {
        require_rejected(head + R"("dt": 0.01, "duration": 0, )" + bodies, "duration",
                         "must be > 0");
    }
    SECTION("duration shorter than dt") {
        require_rejected(head + R"("dt": 0.1, "duration": 0.05, )" + bodies, "duration",
                         "must be >= dt (0.1), got 0.05");
    }
    SECTION("too many steps") {
        require_rejected(head + R"("dt": 1e-8, "duration": 1, )" + bodies, "duration",
                         "duration / dt gives 100000000 steps; at most 10000000 are allowed");
    }
    SECTION("an absurd number of steps is still reported") {
        require_rejected(head + R"("dt": 1e-300, "duration": 1e300, )" + bodies, "duration",
                         "at most 10000000 are allowed");
    }
}

TEST_CASE("solver", "[scene]") {
    SECTION("not an object") {
        require_rejected(scene_with(R"("solver": "rk4",)"), "solver", "must be an object");
    }
    SECTION("unknown key") {
        require_rejected(scene_with(R"("solver": {"integrater": "rk4"},)"), "solver.integrater",
                         "unknown key (did you mean integrator?)");
    }
    SECTION("unknown integrator") {
        require_rejected(scene_with(R"("solver": {"integrator": "leapfrog"},)"),
                         "solver.integrator", "must be one of \"euler\"");
    }
    SECTION("integrator not a string") {
        require_rejected(scene_with(R"("solver": {"integrator": 4},)"), "solver.integrator",
                         "got 4");
    }
    SECTION("another time-of-impact method") {
        require_rejected(scene_with(R"("solver": {"toi": "newton"},)"), "solver.toi",
                         "must be \"bisection\"");
    }
    SECTION("toi_tolerance zero") {
        require_rejected(scene_with(R"("solver": {"toi_tolerance": 0},)"), "solver.toi_tolerance",
                         "must be > 0");
    }
    SECTION("contact_tolerance negative") {
        require_rejected(scene_with(R"("solver": {"contact_tolerance": -1e-9},)"),
                         "solver.contact_tolerance", "must be > 0, got -1e-09");
    }
    SECTION("an unknown contact model") {
        require_rejected(scene_with(R"("solver": {"contacts": "all"},)"), "solver.contacts",
                         "must be \"single\" (the seed's) or \"simultaneous\", got \"all\"");
    }
    SECTION("an unknown vertex normal") {
        require_rejected(scene_with(R"("solver": {"vertex_normal": "average"},)"),
                         "solver.vertex_normal", "must be \"reference-face\" (the seed's)");
    }
    SECTION("ccd not a bool") {
        require_rejected(scene_with(R"("solver": {"ccd": "no"},)"), "solver.ccd",
                         "must be true or false");
    }
    SECTION("resting not a bool") {
        require_rejected(scene_with(R"("solver": {"resting": 1},)"), "solver.resting",
                         "must be true or false");
    }
    SECTION("simultaneous contacts with local stepping") {
        require_rejected(
            scene_with(R"("solver": {"stepping": "local", "contacts": "simultaneous"},)"),
            "solver.contacts", "is not available with \"stepping\": \"local\"");
    }
    SECTION("ccd with local stepping") {
        require_rejected(scene_with(R"("solver": {"stepping": "local", "ccd": true},)"),
                         "solver.ccd", "is not available with \"stepping\": \"local\"");
    }
    SECTION("ccd with local stepping and resting") {
        // ccd sweeps the whole world's motion at once, local stepping one pair.
        require_rejected(
            scene_with(R"("solver": {"stepping": "local", "resting": true, "ccd": true},)"),
            "solver.ccd", "is not available with \"stepping\": \"local\"");
    }
}

TEST_CASE("the models past the seed are one setting away", "[scene]") {
    const Scene scene = parse_scene(
        scene_with(R"("solver": {"contacts": "simultaneous", "vertex_normal": "bisector",
                                 "ccd": true, "resting": true},)"),
        test_file);
    CHECK(scene.solver.contacts == impulse::ContactMode::simultaneous);
    CHECK(scene.solver.vertex_normal == impulse::VertexNormal::bisector);
    CHECK(scene.solver.ccd);
    CHECK(scene.solver.resting);
    const Scene seed = parse_scene(scene_with(""), test_file);
    CHECK(seed.solver.contacts == impulse::ContactMode::single);
    CHECK(seed.solver.vertex_normal == impulse::VertexNormal::reference_face);
    CHECK_FALSE(seed.solver.ccd);
    CHECK_FALSE(seed.solver.resting);
}

// ---------------------------------------------------------------- stepping

TEST_CASE("stepping: world by default, local when asked, and the names round-trip", "[scene]") {
    using impulse::Stepping;
    CHECK(parse_scene(scene_with(""), test_file).solver.stepping == Stepping::world);
    CHECK(
        parse_scene(scene_with(R"("solver": {"stepping": "world"},)"), test_file).solver.stepping ==
        Stepping::world);
    CHECK(
        parse_scene(scene_with(R"("solver": {"stepping": "local"},)"), test_file).solver.stepping ==
        Stepping::local);
    for (const Stepping stepping : {Stepping::world, Stepping::local}) {
        Stepping back = stepping == Stepping::world ? Stepping::local : Stepping::world;
        CHECK(
            impulse::harness::stepping_from_name(impulse::harness::stepping_name(stepping), back));
        CHECK(back == stepping);
    }
    CHECK(std::string(impulse::harness::stepping_name(Stepping::local)) == "local");
    Stepping unchanged = Stepping::local;
    CHECK_FALSE(impulse::harness::stepping_from_name("global", unchanged));
    CHECK(unchanged == Stepping::local);
}

TEST_CASE("rejected stepping", "[scene]") {
    SECTION("an unknown mode") {
        require_rejected(scene_with(R"("solver": {"stepping": "global"},)"), "solver.stepping",
                         "must be \"world\" (the seed's) or \"local\", got \"global\"");
    }
    SECTION("not a string") {
        require_rejected(scene_with(R"("solver": {"stepping": 1},)"), "solver.stepping",
                         "must be \"world\" (the seed's) or \"local\", got 1");
    }
    SECTION("a typo of the key") {
        require_rejected(scene_with(R"("solver": {"steping": "local"},)"), "solver.steping",
                         "unknown key (did you mean stepping?)");
    }
}
