// Scene loading and validation (DESIGN.md, "Scene format"): every documented
// default, the derived mass properties, polygon recentring, the fingerprint,
// and one case per rejected input, each checked for the file name, the exact
// JSON path and the reason.
#include "gas.h"
#include "input_error.h"
#include "manifold.h"
#include "rotation.h"
#include "scene.h"
#include "sha256.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
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

namespace {

const std::string test_file = "scenes/test.json";

// A valid scene with one dynamic disc; `extra` is spliced in among the
// top-level keys (end it with a comma).
std::string scene_with(const std::string& extra) {
    return R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1, )" + extra +
           R"( "bodies": [{"name": "ball", "shape": {"circle": 0.5}}]})";
}

// A valid scene header around the given bodies array.
std::string scene_with_bodies(const std::string& bodies) {
    return R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1, "bodies": )" +
           bodies + "}";
}

// A scene whose only body is {"name": "b", FIELDS}.
std::string scene_with_body(const std::string& fields) {
    return scene_with_bodies(R"([{"name": "b", )" + fields + "}]");
}

// The InputError message parse_scene gives for `text`, or "" when it accepts
// the scene. Any other exception escapes and fails the test.
std::string rejection(const std::string& text, const std::string& file = test_file) {
    try {
        parse_scene(text, file);
    } catch (const InputError& error) {
        return error.what();
    }
    return "";
}

// parse_scene refuses `text` with "FILE: PATH: ..." (or "FILE: ..." for an
// empty path) and a message containing `reason`.
void require_rejected(const std::string& text, const std::string& path, const std::string& reason) {
    INFO("scene: " << text);
    CHECK_THROWS_AS(parse_scene(text, test_file), InputError);
    const std::string message = rejection(text);
    INFO("message: " << message);
    const std::string where = path.empty() ? test_file + ": " : test_file + ": " + path + ": ";
    CHECK(message.rfind(where, 0) == 0);
    CHECK(message.find(reason) != std::string::npos);
}

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

TEST_CASE("mass comes from mass, or from density times area", "[scene]") {
    SECTION("density") {
        const Scene scene =
            parse_scene(scene_with_body(R"("shape": {"box": [1, 0.5]}, "density": 2)"), test_file);
        CHECK(scene.bodies[0].mass == Approx(4.0).epsilon(1e-15));
    }
    SECTION("mass") {
        const Scene scene =
            parse_scene(scene_with_body(R"("shape": {"box": [1, 0.5]}, "mass": 3)"), test_file);
        CHECK(scene.bodies[0].mass == 3.0);
    }
    SECTION("neither: density 1") {
        const Scene scene =
            parse_scene(scene_with_body(R"("shape": {"box": [1, 0.5]})"), test_file);
        CHECK(scene.bodies[0].mass == Approx(2.0).epsilon(1e-15));
    }
}

TEST_CASE("inertia defaults from the shape, or is taken as given", "[scene]") {
    SECTION("box 2a x 2b: I = M (4a^2 + 4b^2) / 12") {
        const double a = 1.5;
        const double b = 0.25;
        const double mass = 3.0;
        const Scene scene =
            parse_scene(scene_with_body(R"("shape": {"box": [1.5, 0.25]}, "mass": 3)"), test_file);
        const double expected = mass * (4 * a * a + 4 * b * b) / 12.0;
        CHECK(std::abs(scene.bodies[0].inertia - expected) <= 1e-14 * expected);
    }
    SECTION("disc: I = M r^2 / 2") {
        const Scene scene =
            parse_scene(scene_with_body(R"("shape": {"circle": 2}, "mass": 3)"), test_file);
        CHECK(std::abs(scene.bodies[0].inertia - 6.0) <= 1e-14 * 6.0);
    }
    SECTION("given") {
        const Scene scene = parse_scene(
            scene_with_body(R"("shape": {"circle": 2}, "mass": 3, "inertia": 7)"), test_file);
        CHECK(scene.bodies[0].inertia == 7.0);
    }
    SECTION("rotation false: infinite inertia, stored as 0") {
        const Scene scene = parse_scene(
            scene_with_body(R"("shape": {"circle": 2}, "mass": 3, "rotation": false)"), test_file);
        CHECK_FALSE(scene.bodies[0].rotation);
        CHECK(scene.bodies[0].inertia == 0.0);
    }
}

TEST_CASE("a polygon off its centroid is recentred without moving in the world", "[scene]") {
    const Vec2 given[3] = {{0, 0}, {3, 0}, {0, 3}};
    const Vec2 position{2, 5};
    const double angle = 0.7;
    const Scene scene =
        parse_scene(scene_with_body(R"("shape": {"polygon": [[0, 0], [3, 0], [0, 3]]},
                                                     "position": [2, 5], "angle": 0.7)"),
                    test_file);
    const auto& body = scene.bodies[0];
    REQUIRE(body.shape.polygon.count == 3);
    const impulse::Rotation q = impulse::rotation_of(angle);
    for (int i = 0; i < 3; ++i) {
        const Vec2 before = impulse::rotate(q, given[i]) + position;
        const Vec2 after = impulse::rotate(q, body.shape.polygon.vertices[i]) + body.position;
        CHECK(std::abs(after.x - before.x) <= 1e-12);
        CHECK(std::abs(after.y - before.y) <= 1e-12);
    }
    const Vec2 centroid = impulse::mass_properties(body.shape).centroid;
    CHECK(std::abs(centroid.x) <= 1e-15);
    CHECK(std::abs(centroid.y) <= 1e-15);
    REQUIRE(scene.warnings.size() == 1);
    CHECK(scene.warnings[0].rfind(test_file + ": bodies[0].shape.polygon: centroid is at (", 0) ==
          0);
    CHECK(scene.warnings[0].find("not at the origin; vertices recentred and position moved") !=
          std::string::npos);
}

TEST_CASE("a polygon already centred is left alone", "[scene]") {
    const Scene scene =
        parse_scene(scene_with_body(R"("shape": {"polygon": [[-1, -1], [1, -1], [1, 1], [-1, 1]]},
                            "position": [2, 5])"),
                    test_file);
    CHECK(scene.warnings.empty());
    CHECK(scene.bodies[0].position == Vec2{2, 5});
    CHECK(scene.bodies[0].shape.polygon.vertices[0] == Vec2{-1, -1});
}

TEST_CASE("bodies may touch at t = 0, and static bodies may overlap", "[scene]") {
    SECTION("a box resting exactly on the ground") {
        CHECK(rejection(scene_with_bodies(R"([
            {"name": "ground", "static": true, "shape": {"box": [5, 0.5]}, "position": [0, -0.5]},
            {"name": "box", "shape": {"box": [1, 0.5]}, "position": [0, 0.5]}])"))
                  .empty());
    }
    SECTION("two discs touching") {
        CHECK(rejection(scene_with_bodies(R"([
            {"name": "a", "shape": {"circle": 1}, "position": [0, 0]},
            {"name": "b", "shape": {"circle": 1}, "position": [2, 0]}])"))
                  .empty());
    }
    SECTION("walls meeting in a corner") {
        CHECK(rejection(scene_with_bodies(R"([
            {"name": "floor", "static": true, "shape": {"box": [5, 0.5]}},
            {"name": "wall", "static": true, "shape": {"box": [0.5, 5]}},
            {"name": "ball", "shape": {"circle": 1}, "position": [3, 3]}])"))
                  .empty());
    }
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
    SECTION("resting with local stepping") {
        require_rejected(scene_with(R"("solver": {"stepping": "local", "resting": true},)"),
                         "solver.resting", "is not available with \"stepping\": \"local\"");
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

// ---------------------------------------------------------------- rejected: bodies

TEST_CASE("the bodies list", "[scene]") {
    SECTION("missing") {
        require_rejected(R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1})",
                         "bodies", "is required");
    }
    SECTION("not an array") {
        require_rejected(scene_with_bodies(R"({"ball": {}})"), "bodies", "must be an array");
    }
    SECTION("empty") {
        require_rejected(scene_with_bodies("[]"), "bodies", "at least one body");
    }
    SECTION("a body that is not an object") {
        require_rejected(scene_with_bodies("[1]"), "bodies[0]", "must be an object");
    }
    SECTION("every body static") {
        require_rejected(
            scene_with_bodies(R"([{"name": "floor", "static": true, "shape": {"box": [5, 1]}}])"),
            "bodies", "static");
    }
}

TEST_CASE("body keys and names", "[scene]") {
    SECTION("unknown key") {
        require_rejected(scene_with_body(R"("shape": {"circle": 1}, "mas": 1)"), "bodies[0].mas",
                         "unknown key (did you mean mass?)");
    }
    SECTION("name missing") {
        require_rejected(scene_with_bodies(R"([{"shape": {"circle": 1}}])"), "bodies[0].name",
                         "is required");
    }
    SECTION("name with a slash") {
        require_rejected(scene_with_bodies(R"([{"name": "a/b", "shape": {"circle": 1}}])"),
                         "bodies[0].name", "letters, digits");
    }
    SECTION("name starting with '-'") {
        require_rejected(scene_with_bodies(R"([{"name": "-a", "shape": {"circle": 1}}])"),
                         "bodies[0].name", "starting with a letter or digit");
    }
    SECTION("duplicate name") {
        require_rejected(scene_with_bodies(R"([{"name": "a", "shape": {"circle": 1}},
                                              {"name": "b", "shape": {"circle": 1}, "position": [5, 0]},
                                              {"name": "a", "shape": {"circle": 1}, "position": [9, 0]}])"),
                         "bodies[2].name", "already the name of bodies[0]");
    }
    SECTION("static not a bool") {
        require_rejected(scene_with_body(R"("static": 1, "shape": {"circle": 1})"),
                         "bodies[0].static", "must be true or false");
    }
}

TEST_CASE("body shape", "[scene]") {
    SECTION("missing") {
        require_rejected(scene_with_body(R"("mass": 1)"), "bodies[0].shape", "is required");
    }
    SECTION("not an object") {
        require_rejected(scene_with_body(R"("shape": "circle")"), "bodies[0].shape",
                         "must be an object");
    }
    SECTION("no kind") {
        require_rejected(scene_with_body(R"("shape": {})"), "bodies[0].shape",
                         "one of box, circle or polygon");
    }
    SECTION("two kinds") {
        require_rejected(scene_with_body(R"("shape": {"box": [1, 1], "circle": 1})"),
                         "bodies[0].shape.circle", "exactly one of box, circle or polygon");
    }
    SECTION("unknown kind") {
        require_rejected(scene_with_body(R"("shape": {"sphere": 1})"), "bodies[0].shape.sphere",
                         "unknown key");
    }
    SECTION("box not a pair") {
        require_rejected(scene_with_body(R"("shape": {"box": [1]})"), "bodies[0].shape.box",
                         "half extents [hx, hy]");
    }
    SECTION("box with a zero half extent") {
        require_rejected(scene_with_body(R"("shape": {"box": [1, 0]})"), "bodies[0].shape.box[1]",
                         "must be > 0, got 0");
    }
    SECTION("box with a string") {
        require_rejected(scene_with_body(R"("shape": {"box": ["1", 1]})"), "bodies[0].shape.box[0]",
                         "must be a number");
    }
    SECTION("circle radius negative") {
        require_rejected(scene_with_body(R"("shape": {"circle": -1})"), "bodies[0].shape.circle",
                         "must be > 0, got -1");
    }
    SECTION("circle radius not a number") {
        require_rejected(scene_with_body(R"("shape": {"circle": [1]})"), "bodies[0].shape.circle",
                         "must be a number, got an array");
    }
}

TEST_CASE("polygon vertices", "[scene]") {
    const std::string path = "bodies[0].shape.polygon";
    auto polygon = [](const std::string& vertices) {
        return scene_with_body(R"("shape": {"polygon": )" + vertices + "}");
    };
    SECTION("not an array") {
        require_rejected(polygon("3"), path, "must be an array");
    }
    SECTION("two vertices") {
        require_rejected(polygon("[[0, 0], [1, 0]]"), path, "must have 3 to 16 vertices, got 2");
    }
    SECTION("seventeen vertices") {
        std::string vertices = "[";
        for (int i = 0; i < 17; ++i) {
            const double a = 2 * 3.141592653589793 * i / 17;
            vertices += (i ? ", [" : "[") + std::to_string(std::cos(a)) + ", " +
                        std::to_string(std::sin(a)) + "]";
        }
        require_rejected(polygon(vertices + "]"), path, "got 17");
    }
    SECTION("a vertex that is not a pair") {
        require_rejected(polygon("[[0, 0], [1], [0, 1]]"), path + "[1]", "two numbers [x, y]");
    }
    SECTION("a coordinate that is not a number") {
        require_rejected(polygon(R"([[0, 0], [1, 0], [true, 1]])"), path + "[2][0]",
                         "must be a number, got true");
    }
    SECTION("repeated consecutive vertex") {
        require_rejected(polygon("[[0, 0], [0, 0], [1, 0], [0, 1]]"), path + "[1]",
                         "repeats vertex 0");
    }
    SECTION("last vertex repeating the first") {
        require_rejected(polygon("[[0, 0], [1, 0], [0, 1], [0, 0]]"), path + "[0]",
                         "repeats vertex 3");
    }
    SECTION("clockwise") {
        require_rejected(polygon("[[0, 0], [0, 1], [1, 0]]"), path, "counter-clockwise");
    }
    SECTION("collinear vertex") {
        require_rejected(polygon("[[0, 0], [1, 0], [2, 0], [2, 2], [0, 2]]"), path + "[1]",
                         "collinear");
    }
    SECTION("reflex vertex") {
        require_rejected(polygon("[[0, 0], [2, 0], [2, 2], [1, 1], [0, 2]]"), path + "[3]",
                         "reflex");
    }
    SECTION("a star that winds round twice") {
        require_rejected(polygon("[[0, 1], [-0.5878, -0.809], [0.9511, 0.309], [-0.9511, 0.309], "
                                 "[0.5878, -0.809]]"),
                         path, "winds around more than once");
    }
}

TEST_CASE("static bodies take no mass or motion", "[scene]") {
    for (const std::string key :
         {"mass", "density", "inertia", "velocity", "angular_velocity", "rotation"}) {
        const std::string value = key == "velocity" ? "[0, 0]" : key == "rotation" ? "true" : "1";
        require_rejected(
            scene_with_bodies(R"([{"name": "ball", "shape": {"circle": 1}, "position": [0, 5]},
                                              {"name": "floor", "static": true, "shape": {"box": [5, 1]}, ")" +
                              key + "\": " + value + "}]"),
            "bodies[1]." + key, "a static body has infinite mass and does not move; remove " + key);
    }
}

TEST_CASE("dynamic body mass, inertia and motion", "[scene]") {
    SECTION("the design's example: negative mass") {
        const std::string message = rejection(scene_with_bodies(R"([
            {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
            {"name": "box", "shape": {"box": [1, 0.5]}, "mass": -1, "position": [0, 3]}])"),
                                              "harness/scenes/drop.json");
        CHECK(message == "harness/scenes/drop.json: bodies[1].mass: must be > 0, got -1");
    }
    SECTION("mass and density together") {
        require_rejected(scene_with_body(R"("shape": {"circle": 1}, "mass": 1, "density": 1)"),
                         "bodies[0].density", "mass or density, not both");
    }
    SECTION("density zero") {
        require_rejected(scene_with_body(R"("shape": {"circle": 1}, "density": 0)"),
                         "bodies[0].density", "must be > 0, got 0");
    }
    SECTION("inertia negative") {
        require_rejected(scene_with_body(R"("shape": {"circle": 1}, "inertia": -2)"),
                         "bodies[0].inertia", "must be > 0, got -2");
    }
    SECTION("inertia on a non-rotating body") {
        require_rejected(
            scene_with_body(R"("shape": {"circle": 1}, "rotation": false, "inertia": 2)"),
            "bodies[0].inertia", "infinite inertia");
    }
    SECTION("spin on a non-rotating body") {
        require_rejected(
            scene_with_body(R"("shape": {"circle": 1}, "rotation": false, "angular_velocity": 1)"),
            "bodies[0].angular_velocity", "must be 0");
    }
    SECTION("rotation not a bool") {
        require_rejected(scene_with_body(R"("shape": {"circle": 1}, "rotation": "no")"),
                         "bodies[0].rotation", "must be true or false");
    }
    SECTION("position not a pair") {
        require_rejected(scene_with_body(R"("shape": {"circle": 1}, "position": [0, 1, 2])"),
                         "bodies[0].position", "two numbers");
    }
    SECTION("angle not a number") {
        require_rejected(scene_with_body(R"("shape": {"circle": 1}, "angle": "30deg")"),
                         "bodies[0].angle", "must be a number");
    }
    SECTION("velocity component null") {
        require_rejected(scene_with_body(R"("shape": {"circle": 1}, "velocity": [1, null])"),
                         "bodies[0].velocity[1]", "must be a number, got null");
    }
    SECTION("angular velocity not a number") {
        require_rejected(scene_with_body(R"("shape": {"circle": 1}, "angular_velocity": {})"),
                         "bodies[0].angular_velocity", "must be a number, got an object");
    }
    SECTION("a mass too large for a double") {
        require_rejected(scene_with_body(R"("shape": {"box": [1e200, 1e200]}, "density": 1e300)"),
                         "bodies[0]", "must be finite and > 0");
    }
}

TEST_CASE("bodies overlapping at t = 0", "[scene]") {
    SECTION("two discs") {
        require_rejected(scene_with_bodies(R"([
            {"name": "a", "shape": {"circle": 1}, "position": [0, 0]},
            {"name": "b", "shape": {"circle": 1}, "position": [1.5, 0]}])"),
                         "bodies[1]", "'b' overlaps bodies[0] 'a' at t = 0 by 0.5 m");
    }
    SECTION("a box sunk into static ground, named at the later body") {
        require_rejected(scene_with_bodies(R"([
            {"name": "ball", "shape": {"circle": 1}, "position": [0, 10]},
            {"name": "box", "shape": {"box": [1, 0.5]}, "position": [0, 0.25]},
            {"name": "ground", "static": true, "shape": {"box": [5, 0.5]}, "position": [0, -0.5]}])"),
                         "bodies[2]", "'ground' overlaps bodies[1] 'box' at t = 0 by 0.25 m");
    }
}

// Whatever a value is replaced with, the loader either accepts the scene or
// throws InputError: never a nlohmann exception or anything else.
TEST_CASE("only InputError escapes, whatever type a value has", "[scene]") {
    const std::string base = R"({
        "schema": "impulse/scene@1", "name": "t", "description": "d", "gravity": [0, -1],
        "restitution": 0.5, "dt": 0.01, "duration": 1,
        "solver": {"integrator": "rk4", "toi": "bisection", "toi_tolerance": 1e-12,
                   "contact_tolerance": 1e-9, "contacts": "single", "ccd": false, "resting": false},
        "bodies": [
            {"name": "floor", "static": true, "shape": {"box": [5, 0.5]}, "position": [0, -0.5]},
            {"name": "poly", "shape": {"polygon": [[-1, -1], [1, -1], [0, 1]]}, "position": [0, 3],
             "angle": 0.1, "velocity": [1, 0], "angular_velocity": 1, "density": 2, "inertia": 1,
             "rotation": true}]
    })";
    REQUIRE(rejection(base).empty());
    const nlohmann::json document = nlohmann::json::parse(base);
    const std::vector<nlohmann::json> replacements = {nullptr,
                                                      true,
                                                      false,
                                                      0,
                                                      -1,
                                                      1e308,
                                                      "text",
                                                      nlohmann::json::array(),
                                                      nlohmann::json::array({1, 2}),
                                                      nlohmann::json::object()};
    const nlohmann::json flat = document.flatten();
    std::vector<std::string> pointers;
    for (const auto& [pointer, value] : flat.items()) {
        // Every leaf and every container above it.
        for (std::string p = pointer; !p.empty(); p = p.substr(0, p.rfind('/'))) {
            pointers.push_back(p);
        }
    }
    for (const std::string& pointer : pointers) {
        for (const nlohmann::json& replacement : replacements) {
            nlohmann::json changed = document;
            changed[nlohmann::json::json_pointer(pointer)] = replacement;
            INFO(pointer << " = " << replacement.dump());
            CHECK_NOTHROW(rejection(changed.dump()));
        }
    }
}

// ---------------------------------------------------------------- tolerance and expectations

namespace {

// Static ground with its top at y = 0; "ball" (a disc of radius 0.5) 1 m above
// it; "tilted", a 2 x 1 box turned 0.5 rad, free to rotate, well above it;
// "crate", a non-rotating unit box 1 m above it.
const std::string standard_bodies = R"([
    {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
    {"name": "ball", "shape": {"circle": 0.5}, "position": [0, 1.5]},
    {"name": "tilted", "shape": {"box": [1, 0.5]}, "angle": 0.5, "position": [5, 3]},
    {"name": "crate", "shape": {"box": [0.5, 0.5]}, "rotation": false, "position": [-5, 1.5]}])";

// Free space: two discs 3 m apart closing along x, and two non-rotating boxes
// in line along x, closing.
const std::string free_bodies = R"([
    {"name": "a", "shape": {"circle": 0.5}, "velocity": [2, 0]},
    {"name": "b", "shape": {"circle": 0.5}, "position": [3, 0]},
    {"name": "p", "shape": {"box": [0.5, 0.5]}, "rotation": false, "position": [0, 5],
     "velocity": [1, 0]},
    {"name": "q", "shape": {"box": [0.5, 0.5]}, "rotation": false, "position": [3, 5]}])";

// A scene with the given expectations (a JSON array), bodies and further
// top-level keys (end them with a comma).
std::string expecting(const std::string& expectations, const std::string& bodies = standard_bodies,
                      const std::string& extra = "") {
    return R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1, )" + extra +
           R"( "expectations": )" + expectations + R"(, "bodies": )" + bodies + "}";
}

std::string free_space(const std::string& expectations, const std::string& bodies = free_bodies) {
    return expecting(expectations, bodies, R"("gravity": [0, 0],)");
}

} // namespace

TEST_CASE("tolerance: channels given are read, the others stay empty", "[scene]") {
    const Scene scene =
        parse_scene(scene_with(R"("tolerance": {"position": {"atol": 1e-9, "rtol": 1e-6},
                                    "event_time": {"ulp": 4}, "impulse": {"rtol": 0}},)"),
                    test_file);
    using impulse::harness::Channel;
    REQUIRE(scene.tolerances[Channel::position].has_value());
    CHECK(scene.tolerances[Channel::position]->atol == 1e-9);
    CHECK(scene.tolerances[Channel::position]->rtol == 1e-6);
    CHECK(scene.tolerances[Channel::position]->ulp == 0);
    REQUIRE(scene.tolerances[Channel::event_time].has_value());
    CHECK(scene.tolerances[Channel::event_time]->ulp == 4);
    CHECK(scene.tolerances[Channel::event_time]->atol == 0.0);
    CHECK(scene.tolerances[Channel::impulse].has_value());
    CHECK_FALSE(scene.tolerances[Channel::angle].has_value());
    CHECK_FALSE(scene.tolerances[Channel::velocity].has_value());
    CHECK_FALSE(scene.tolerances[Channel::angular_velocity].has_value());
    // No key, no tolerances and no expectations.
    const Scene plain = parse_scene(scene_with(""), test_file);
    for (const auto& channel : plain.tolerances.channels) {
        CHECK_FALSE(channel.has_value());
    }
    CHECK(plain.expectations.empty());
}

TEST_CASE("expectations: every kind is read with its path and values", "[scene]") {
    using Kind = impulse::harness::Expectation::Kind;
    const Scene scene = parse_scene(expecting(R"([
        {"kind": "drop", "body": "ball", "impacts": 3, "rtol": 1e-9, "description": "ladder"},
        {"kind": "corner-impact", "body": "tilted", "atol": 1e-6},
        {"kind": "energy-non-increasing", "atol": 0, "rtol": 1e-12},
        {"kind": "event", "index": 2, "a": "tilted", "t": 0.5, "normal": [0, 1], "vn_after": 1,
         "rtol": 1e-9},
        {"kind": "state", "body": "crate", "t": 0.25, "vy": -2.4525, "y": 1.2, "atol": 1e-12},
        {"kind": "drop", "body": "crate", "impacts": 1.0, "rtol": 1e-9}])"),
                                    test_file);
    REQUIRE(scene.expectations.size() == 6);
    const auto& drop = scene.expectations[0];
    CHECK(drop.kind == Kind::drop);
    CHECK(drop.path == "expectations[0]");
    CHECK(drop.description == "ladder");
    CHECK(drop.body == "ball");
    CHECK(drop.impacts == 3);
    CHECK(drop.rtol == 1e-9);
    CHECK(drop.atol == 0.0);
    const auto& corner = scene.expectations[1];
    CHECK(corner.kind == Kind::corner_impact);
    CHECK(corner.body == "tilted");
    CHECK(corner.atol == 1e-6);
    CHECK(corner.rtol == 0.0);
    CHECK(scene.expectations[2].kind == Kind::energy_non_increasing);
    const auto& event = scene.expectations[3];
    CHECK(event.kind == Kind::event);
    CHECK(event.index == 2);
    CHECK(event.body == "tilted");
    CHECK(event.other.empty());
    // Numbers first, in the format's order, then the pairs.
    using Values = std::vector<std::pair<std::string, double>>;
    CHECK(event.values ==
          Values{{"t", 0.5}, {"vn_after", 1.0}, {"normal.x", 0.0}, {"normal.y", 1.0}});
    const auto& state = scene.expectations[4];
    CHECK(state.kind == Kind::state);
    CHECK(state.path == "expectations[4]");
    CHECK(state.body == "crate");
    CHECK(state.t == 0.25);
    CHECK(state.values == Values{{"y", 1.2}, {"vy", -2.4525}});
    CHECK(scene.expectations[5].impacts == 1);

    const Scene free = parse_scene(free_space(R"([
        {"kind": "head-on", "a": "a", "b": "b", "rtol": 1e-9},
        {"kind": "head-on", "a": "q", "b": "p", "rtol": 1e-9},
        {"kind": "conserved", "quantities": ["energy", "momentum", "angular_momentum"],
         "rtol": 1e-12}])"),
                                   test_file);
    REQUIRE(free.expectations.size() == 3);
    CHECK(free.expectations[0].kind == Kind::head_on);
    CHECK(free.expectations[0].body == "a");
    CHECK(free.expectations[0].other == "b");
    CHECK(free.expectations[1].body == "q");
    CHECK(free.expectations[2].kind == Kind::conserved);
    CHECK(free.expectations[2].quantities ==
          std::vector<std::string>{"energy", "momentum", "angular_momentum"});
}

TEST_CASE("a rotating polygon may drop when it lands on one corner below its centre", "[scene]") {
    // A unit square at 45 degrees: the impulse at its lowest corner passes
    // through the centre, so it bounces straight.
    CHECK(
        rejection(expecting(R"([{"kind": "drop", "body": "diamond", "impacts": 2, "rtol": 1e-9}])",
                            R"([{"name": "ground", "static": true, "shape": {"box": [50, 0.5]},
                                   "position": [0, -0.5]},
                                  {"name": "diamond", "shape": {"box": [0.5, 0.5]},
                                   "angle": 0.7853981633974483, "position": [0, 2]}])"))
            .empty());
}

TEST_CASE("rejected tolerance", "[scene]") {
    SECTION("not an object") {
        require_rejected(scene_with(R"("tolerance": [],)"), "tolerance",
                         "must be an object, got an array");
    }
    SECTION("unknown channel") {
        require_rejected(scene_with(R"("tolerance": {"positon": {"atol": 1}},)"),
                         "tolerance.positon", "unknown key (did you mean position?)");
    }
    SECTION("a channel that is a number") {
        require_rejected(scene_with(R"("tolerance": {"position": 1e-9},)"), "tolerance.position",
                         "must be an object, got 1e-09");
    }
    SECTION("a channel with no bound") {
        require_rejected(scene_with(R"("tolerance": {"position": {}},)"), "tolerance.position",
                         "must give at least one of atol, rtol or ulp");
    }
    SECTION("unknown key in a channel") {
        require_rejected(scene_with(R"("tolerance": {"angle": {"atl": 1}},)"),
                         "tolerance.angle.atl", "unknown key (did you mean atol?)");
    }
    SECTION("negative atol") {
        require_rejected(scene_with(R"("tolerance": {"velocity": {"atol": -1}},)"),
                         "tolerance.velocity.atol", "must be >= 0, got -1");
    }
    SECTION("rtol as a string") {
        require_rejected(scene_with(R"("tolerance": {"impulse": {"rtol": "1e-9"}},)"),
                         "tolerance.impulse.rtol", "must be a number");
    }
    SECTION("fractional ulp") {
        require_rejected(scene_with(R"("tolerance": {"event_time": {"ulp": 2.5}},)"),
                         "tolerance.event_time.ulp", "must be a whole number from 0 to");
    }
    SECTION("negative ulp") {
        require_rejected(scene_with(R"("tolerance": {"angular_velocity": {"ulp": -1}},)"),
                         "tolerance.angular_velocity.ulp", "got -1");
    }
}

TEST_CASE("rejected expectations: the list and the common keys", "[scene]") {
    SECTION("not an array") {
        require_rejected(expecting("{}"), "expectations", "must be an array, got an object");
    }
    SECTION("an entry that is not an object") {
        require_rejected(expecting("[1]"), "expectations[0]", "must be an object");
    }
    SECTION("kind missing") {
        require_rejected(expecting(R"([{"body": "ball", "rtol": 1e-9}])"), "expectations[0].kind",
                         "is required but missing");
    }
    SECTION("unknown kind") {
        require_rejected(expecting(R"([{"kind": "bounce", "rtol": 1e-9}])"), "expectations[0].kind",
                         "must be one of \"drop\", \"corner-impact\", \"head-on\", \"conserved\", "
                         "\"energy-non-increasing\", \"momentum-balance\", \"event\", "
                         "\"state\", got \"bounce\"");
    }
    SECTION("kind not a string") {
        require_rejected(expecting(R"([{"kind": 3, "rtol": 1e-9}])"), "expectations[0].kind",
                         "got 3");
    }
    SECTION("a typo in a kind's key") {
        require_rejected(
            expecting(R"([{"kind": "drop", "body": "ball", "impact": 2, "rtol": 1e-9}])"),
            "expectations[0].impact", "unknown key (did you mean impacts?)");
    }
    SECTION("a key of another kind") {
        require_rejected(
            expecting(R"([{"kind": "energy-non-increasing", "body": "ball", "rtol": 1e-9}])"),
            "expectations[0].body", "unknown key; expected one of kind, description, atol, rtol");
    }
    SECTION("no tolerance") {
        require_rejected(expecting(R"([{"kind": "energy-non-increasing"}])"), "expectations[0]",
                         "must give atol or rtol (or both); an expectation has no default "
                         "tolerance");
    }
    SECTION("negative atol") {
        require_rejected(expecting(R"([{"kind": "energy-non-increasing", "atol": -1e-9}])"),
                         "expectations[0].atol", "must be >= 0, got -1e-09");
    }
    SECTION("rtol null") {
        require_rejected(expecting(R"([{"kind": "energy-non-increasing", "rtol": null}])"),
                         "expectations[0].rtol", "must be a number, got null");
    }
    SECTION("description not a string") {
        require_rejected(
            expecting(R"([{"kind": "energy-non-increasing", "rtol": 0, "description": 1}])"),
            "expectations[0].description", "must be a string");
    }
    SECTION("the path names the entry") {
        require_rejected(expecting(R"([{"kind": "energy-non-increasing", "rtol": 0},
                                       {"kind": "energy-non-increasing", "rtol": -1}])"),
                         "expectations[1].rtol", "must be >= 0");
    }
}

TEST_CASE("rejected drop expectations", "[scene]") {
    auto drop = [](const std::string& body, const std::string& more = R"("impacts": 2)") {
        return R"([{"kind": "drop", "body": )" + body + ", " + more + R"(, "rtol": 1e-9}])";
    };
    SECTION("body missing") {
        require_rejected(expecting(R"([{"kind": "drop", "impacts": 2, "rtol": 1e-9}])"),
                         "expectations[0].body", "is required but missing");
    }
    SECTION("no such body") {
        require_rejected(expecting(drop(R"("bal")")), "expectations[0].body",
                         "no body is named \"bal\"; the bodies are ground, ball, tilted, crate");
    }
    SECTION("a static body") {
        require_rejected(expecting(drop(R"("ground")")), "expectations[0].body",
                         "'ground' is static; the drop formula needs a dynamic body");
    }
    SECTION("impacts missing") {
        require_rejected(expecting(drop(R"("ball")", R"("description": "")")),
                         "expectations[0].impacts", "is required but missing");
    }
    SECTION("no impacts") {
        require_rejected(expecting(drop(R"("ball")", R"("impacts": 0)")), "expectations[0].impacts",
                         "must be a whole number from 1 to 10000, got 0");
    }
    SECTION("a fractional number of impacts") {
        require_rejected(expecting(drop(R"("ball")", R"("impacts": 1.5)")),
                         "expectations[0].impacts", "got 1.5");
    }
    SECTION("released moving: the whole message") {
        const std::string text =
            expecting(drop(R"("box")"),
                      R"([{"name": "ground", "static": true, "shape": {"box": [50, 0.5]},
                           "position": [0, -0.5]},
                          {"name": "box", "shape": {"box": [0.5, 0.5]}, "rotation": false,
                           "position": [0, 2], "velocity": [1, 0]}])");
        CHECK(rejection(text) ==
              "scenes/test.json: expectations[0].body: the drop formula needs the body at rest at "
              "t = 0, but 'box' has velocity (1, 0)");
    }
    SECTION("released spinning") {
        require_rejected(
            expecting(drop(R"("ball")"),
                      R"([{"name": "ground", "static": true, "shape": {"box": [50, 0.5]},
                           "position": [0, -0.5]},
                          {"name": "ball", "shape": {"circle": 0.5}, "position": [0, 2],
                           "angular_velocity": 2}])"),
            "expectations[0].body",
            "needs the body at rest at t = 0, but 'ball' has angular velocity 2 rad/s");
    }
    SECTION("a rotating box landing flat") {
        require_rejected(expecting(drop(R"("tilted")")), "expectations[0].body",
                         "the drop formula has no rotation, but 'tilted' is a polygon free to "
                         "rotate that lands neither on one corner below its centre nor");
    }
    SECTION("gravity with a sideways part") {
        require_rejected(expecting(drop(R"("ball")"), standard_bodies, R"("gravity": [1, -9.81],)"),
                         "expectations[0]",
                         "the drop formula needs gravity (0, -g) with g > 0, but the scene's "
                         "gravity is (1, -9.81)");
    }
    SECTION("no gravity") {
        require_rejected(expecting(drop(R"("ball")"), standard_bodies, R"("gravity": [0, 0],)"),
                         "expectations[0]", "g > 0, but the scene's gravity is (0, 0)");
    }
    SECTION("already touching the ground") {
        require_rejected(
            expecting(drop(R"("ball")"),
                      R"([{"name": "ground", "static": true, "shape": {"box": [50, 0.5]},
                           "position": [0, -0.5]},
                          {"name": "ball", "shape": {"circle": 0.5}, "position": [0, 0.5]}])"),
            "expectations[0].body",
            "the drop formula needs a gap between 'ball' and the static ground at t = 0, but it "
            "touches it");
    }
    SECTION("no ground") {
        require_rejected(
            expecting(drop(R"("ball")"), R"([{"name": "ball", "shape": {"circle": 0.5}}])"),
            "expectations[0].body",
            "needs static ground for 'ball' to fall on, but every body is dynamic");
    }
}

TEST_CASE("rejected corner-impact expectations", "[scene]") {
    auto corner = [](const std::string& body) {
        return R"([{"kind": "corner-impact", "body": ")" + body + R"(", "rtol": 1e-9}])";
    };
    // A body over static ground, given its fields.
    auto over_ground = [](const std::string& fields) {
        return R"([{"name": "ground", "static": true, "shape": {"box": [50, 0.5]},
                    "position": [0, -0.5]}, {"name": "body", )" +
               fields + "}]";
    };
    SECTION("a disc") {
        require_rejected(expecting(corner("ball")), "expectations[0].body",
                         "the corner-impact formula needs a polygon, but 'ball' is a circle");
    }
    SECTION("a non-rotating body") {
        require_rejected(expecting(corner("crate")), "expectations[0].body",
                         "needs a body free to rotate, but 'crate' has \"rotation\": false");
    }
    SECTION("a static body") {
        require_rejected(expecting(corner("ground")), "expectations[0].body",
                         "'ground' is static; the corner-impact formula needs a dynamic body");
    }
    SECTION("spinning") {
        require_rejected(
            expecting(corner("body"), over_ground(R"("shape": {"box": [1, 0.5]}, "angle": 0.5,
                                                     "position": [0, 3], "angular_velocity": 1)")),
            "expectations[0].body", "needs angular velocity 0 at t = 0, but 'body' has 1 rad/s");
    }
    SECTION("landing flat") {
        require_rejected(
            expecting(corner("body"),
                      over_ground(R"("shape": {"box": [1, 0.5]}, "position": [0, 3])")),
            "expectations[0].body",
            "needs one lowest corner, but 'body' has two corners within 1e-09 m of the same "
            "height");
    }
    SECTION("gravity pointing up") {
        require_rejected(expecting(corner("tilted"), standard_bodies, R"("gravity": [0, 9.81],)"),
                         "expectations[0]",
                         "the corner-impact formula needs gravity (0, -g) with g >= 0, but the "
                         "scene's gravity is (0, 9.81)");
    }
    SECTION("no gravity and not moving down") {
        require_rejected(expecting(corner("tilted"), standard_bodies, R"("gravity": [0, 0],)"),
                         "expectations[0].body",
                         "without gravity needs the body moving down, but 'tilted' has vy = 0");
    }
    SECTION("no gravity and moving down is fine") {
        CHECK(rejection(expecting(corner("body"),
                                  over_ground(R"("shape": {"box": [1, 0.5]}, "angle": 0.5,
                                                 "position": [0, 3], "velocity": [0, -1])"),
                                  R"("gravity": [0, 0],)"))
                  .empty());
    }
    SECTION("its corner already on the ground") {
        // A triangle with its centroid at the origin and one corner 1 m below it.
        require_rejected(
            expecting(corner("body"),
                      over_ground(R"("shape": {"polygon": [[0, -1], [1, 0.5], [-1, 0.5]]},
                                                  "position": [0, 1])")),
            "expectations[0].body",
            "needs a gap between 'body' and the static ground at t = 0, but it "
            "touches it");
    }
}

TEST_CASE("rejected head-on expectations", "[scene]") {
    auto head_on = [](const std::string& a, const std::string& b) {
        return R"([{"kind": "head-on", "a": ")" + a + R"(", "b": ")" + b + R"(", "rtol": 1e-9}])";
    };
    SECTION("b missing") {
        require_rejected(free_space(R"([{"kind": "head-on", "a": "a", "rtol": 1e-9}])"),
                         "expectations[0].b", "is required but missing");
    }
    SECTION("no such body") {
        require_rejected(free_space(head_on("a", "c")), "expectations[0].b",
                         "no body is named \"c\"");
    }
    SECTION("twice the same body") {
        require_rejected(free_space(head_on("a", "a")), "expectations[0].b",
                         "the head-on formula needs two distinct bodies, but a and b are both 'a'");
    }
    SECTION("gravity") {
        require_rejected(expecting(head_on("ball", "crate")), "expectations[0]",
                         "the head-on formula needs zero gravity, but the scene's gravity is "
                         "(0, -9.81)");
    }
    SECTION("a static body") {
        require_rejected(
            expecting(head_on("ball", "ground"), standard_bodies, R"("gravity": [0, 0],)"),
            "expectations[0].b", "'ground' is static; the head-on formula needs a dynamic body");
    }
    SECTION("a box free to rotate") {
        require_rejected(free_space(head_on("a", "r"), R"([
                             {"name": "a", "shape": {"circle": 0.5}, "velocity": [2, 0]},
                             {"name": "r", "shape": {"box": [0.5, 0.5]}, "position": [3, 0]}])"),
                         "expectations[0].b",
                         "the head-on formula has no rotation, but 'r' is a polygon free to "
                         "rotate; give it \"rotation\": false");
    }
    SECTION("moving apart") {
        require_rejected(free_space(head_on("a", "b"), R"([
                             {"name": "a", "shape": {"circle": 0.5}, "velocity": [-2, 0]},
                             {"name": "b", "shape": {"circle": 0.5}, "position": [3, 0]}])"),
                         "expectations[0]",
                         "needs 'a' and 'b' approaching along the line of their centres, but "
                         "their closing speed is -2 m/s");
    }
    SECTION("named the other way round they still approach") {
        CHECK(rejection(free_space(head_on("b", "a"))).empty());
    }
    SECTION("relative velocity across the line of centres") {
        require_rejected(free_space(head_on("a", "b"), R"([
                             {"name": "a", "shape": {"circle": 0.5}, "velocity": [2, 1]},
                             {"name": "b", "shape": {"circle": 0.5}, "position": [3, 0]}])"),
                         "expectations[0]",
                         "but their relative velocity (2, 1) is not along (1, 0)");
    }
    SECTION("boxes off the line of their faces") {
        require_rejected(free_space(head_on("p", "q"), R"([
                             {"name": "p", "shape": {"box": [0.5, 0.5]}, "rotation": false,
                              "velocity": [3, 0.3]},
                             {"name": "q", "shape": {"box": [0.5, 0.5]}, "rotation": false,
                              "position": [3, 0.3]}])"),
                         "expectations[0]", "needs the contact normal along the line of centres");
    }
}

TEST_CASE("rejected conserved expectations", "[scene]") {
    auto conserved = [](const std::string& quantities) {
        return R"([{"kind": "conserved", "quantities": )" + quantities + R"(, "rtol": 1e-12}])";
    };
    SECTION("quantities missing") {
        require_rejected(free_space(R"([{"kind": "conserved", "rtol": 1e-12}])"),
                         "expectations[0].quantities", "is required but missing");
    }
    SECTION("quantities not an array") {
        require_rejected(free_space(conserved(R"("energy")")), "expectations[0].quantities",
                         "must be an array");
    }
    SECTION("no quantities") {
        require_rejected(free_space(conserved("[]")), "expectations[0].quantities",
                         "must name at least one of momentum, angular_momentum, energy");
    }
    SECTION("an unknown quantity") {
        require_rejected(free_space(conserved(R"(["momentum", "mass"])")),
                         "expectations[0].quantities[1]",
                         "must be one of momentum, angular_momentum, energy, got \"mass\"");
    }
    SECTION("a quantity twice") {
        require_rejected(free_space(conserved(R"(["momentum", "momentum"])")),
                         "expectations[0].quantities[1]", "repeats quantities[0]");
    }
    SECTION("momentum under gravity") {
        require_rejected(expecting(conserved(R"(["momentum"])"),
                                   R"([{"name": "ball", "shape": {"circle": 0.5}}])"),
                         "expectations[0].quantities[0]",
                         "momentum is conserved only in free space, but the scene's gravity is "
                         "(0, -9.81)");
    }
    SECTION("angular momentum with a static body") {
        require_rejected(expecting(conserved(R"(["angular_momentum"])"), standard_bodies,
                                   R"("gravity": [0, 0],)"),
                         "expectations[0].quantities[0]",
                         "angular momentum is conserved only in free space, but 'ground' is "
                         "static");
    }
    SECTION("energy with e < 1") {
        require_rejected(expecting(conserved(R"(["energy"])"), free_bodies,
                                   R"("gravity": [0, 0], "restitution": 0.5,)"),
                         "expectations[0].quantities[0]",
                         "energy is conserved only with restitution 1, but the scene's is 0.5");
    }
}

TEST_CASE("rejected event expectations", "[scene]") {
    SECTION("index missing") {
        require_rejected(expecting(R"([{"kind": "event", "t": 1, "rtol": 1e-9}])"),
                         "expectations[0].index", "is required but missing");
    }
    SECTION("negative index") {
        require_rejected(expecting(R"([{"kind": "event", "index": -1, "t": 1, "rtol": 1e-9}])"),
                         "expectations[0].index", "must be a whole number from 0 to");
    }
    SECTION("no such body") {
        require_rejected(expecting(R"([{"kind": "event", "index": 0, "a": "boll", "rtol": 1e-9}])"),
                         "expectations[0].a", "no body is named \"boll\"");
    }
    SECTION("body b not a string") {
        require_rejected(expecting(R"([{"kind": "event", "index": 0, "b": 1, "rtol": 1e-9}])"),
                         "expectations[0].b", "must be a string, got 1");
    }
    SECTION("nothing to check") {
        require_rejected(expecting(R"([{"kind": "event", "index": 0, "rtol": 1e-9}])"),
                         "expectations[0]",
                         "an event expectation must give at least one of a, b, t, impulse, "
                         "vn_before, vn_after, point or normal");
    }
    SECTION("point not a pair") {
        require_rejected(
            expecting(R"([{"kind": "event", "index": 0, "point": [1], "rtol": 1e-9}])"),
            "expectations[0].point", "must be an array of two numbers");
    }
    SECTION("a normal component that is not a number") {
        require_rejected(
            expecting(R"([{"kind": "event", "index": 0, "normal": [0, null], "rtol": 1e-9}])"),
            "expectations[0].normal[1]", "must be a number, got null");
    }
    SECTION("impulse as a string") {
        require_rejected(
            expecting(R"([{"kind": "event", "index": 0, "impulse": "2", "rtol": 1e-9}])"),
            "expectations[0].impulse", "must be a number");
    }
}

TEST_CASE("rejected state expectations", "[scene]") {
    SECTION("a static body has no state to check") {
        require_rejected(
            expecting(R"([{"kind": "state", "body": "ground", "t": 0, "y": 0, "rtol": 1e-9}])"),
            "expectations[0].body", "'ground' is static; a state expectation needs a dynamic body");
    }
    SECTION("t missing") {
        require_rejected(expecting(R"([{"kind": "state", "body": "ball", "y": 0, "rtol": 1e-9}])"),
                         "expectations[0].t", "is required but missing");
    }
    SECTION("t negative") {
        require_rejected(
            expecting(R"([{"kind": "state", "body": "ball", "t": -1, "y": 0, "rtol": 1e-9}])"),
            "expectations[0].t", "must be >= 0, got -1");
    }
    SECTION("t between frames") {
        require_rejected(
            expecting(R"([{"kind": "state", "body": "ball", "t": 0.015, "y": 0, "rtol": 1e-9}])"),
            "expectations[0].t",
            "must be the time of a frame, a multiple of dt = 0.01 s up to the end of the run, got "
            "0.015");
    }
    SECTION("t after the end") {
        require_rejected(
            expecting(R"([{"kind": "state", "body": "ball", "t": 2, "y": 0, "rtol": 1e-9}])"),
            "expectations[0].t", "must be the time of a frame");
    }
    SECTION("nothing to check") {
        require_rejected(expecting(R"([{"kind": "state", "body": "ball", "t": 0, "rtol": 1e-9}])"),
                         "expectations[0]",
                         "a state expectation must give at least one of x, y, angle, vx, vy or "
                         "omega");
    }
    SECTION("a value that is not a number") {
        require_rejected(
            expecting(R"([{"kind": "state", "body": "ball", "t": 0, "vx": "0", "rtol": 1e-9}])"),
            "expectations[0].vx", "must be a number");
    }
}

// As for the rest of the scene: whatever a value of the tolerance or of an
// expectation is replaced with, only InputError escapes.
TEST_CASE("only InputError escapes from tolerance and expectations", "[scene]") {
    const std::vector<std::string> bases = {
        expecting(R"([
            {"kind": "drop", "body": "ball", "impacts": 2, "rtol": 1e-9, "description": "d"},
            {"kind": "corner-impact", "body": "tilted", "atol": 1e-9},
            {"kind": "energy-non-increasing", "rtol": 1e-12},
            {"kind": "event", "index": 0, "a": "ball", "b": "ground", "t": 0.45, "impulse": 1,
             "vn_before": -1, "vn_after": 1, "point": [0, 0], "normal": [0, 1], "rtol": 1e-9},
            {"kind": "state", "body": "crate", "t": 0.5, "x": 0, "y": 1, "angle": 0, "vx": 0,
             "vy": 0, "omega": 0, "atol": 1e-9}])",
                  standard_bodies,
                  R"("tolerance": {"position": {"atol": 1e-9, "rtol": 0, "ulp": 2},
                                   "event_time": {"ulp": 4}},)"),
        free_space(R"([
            {"kind": "head-on", "a": "a", "b": "b", "rtol": 1e-9},
            {"kind": "conserved", "quantities": ["momentum", "angular_momentum", "energy"],
             "rtol": 1e-12}])")};
    const std::vector<nlohmann::json> replacements = {nullptr,
                                                      true,
                                                      0,
                                                      -1,
                                                      2.5,
                                                      1e308,
                                                      "text",
                                                      "ground",
                                                      nlohmann::json::array(),
                                                      nlohmann::json::array({1, 2}),
                                                      nlohmann::json::object()};
    for (const std::string& base : bases) {
        REQUIRE(rejection(base).empty());
        const nlohmann::json document = nlohmann::json::parse(base);
        const nlohmann::json flat = document.flatten();
        std::vector<std::string> pointers;
        for (const auto& [pointer, value] : flat.items()) {
            if (pointer.rfind("/expectations", 0) != 0 && pointer.rfind("/tolerance", 0) != 0) {
                continue;
            }
            for (std::string p = pointer; !p.empty(); p = p.substr(0, p.rfind('/'))) {
                pointers.push_back(p);
            }
        }
        for (const std::string& pointer : pointers) {
            for (const nlohmann::json& replacement : replacements) {
                nlohmann::json changed = document;
                changed[nlohmann::json::json_pointer(pointer)] = replacement;
                INFO(pointer << " = " << replacement.dump());
                CHECK_NOTHROW(rejection(changed.dump()));
            }
        }
    }
}

// ---------------------------------------------------------------- box2d

namespace {

// A scene with the standard bodies (or others) and the given "box2d" block.
std::string with_box2d(const std::string& block, const std::string& bodies = standard_bodies,
                       const std::string& extra = "") {
    return R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1, )" + extra +
           R"( "box2d": )" + block + R"(, "bodies": )" + bodies + "}";
}

// A block with one observable.
std::string observing(const std::string& observable) {
    return R"({"observables": [)" + observable + "]}";
}

} // namespace

TEST_CASE("box2d: without the block, Box2D's defaults and nothing to compare", "[scene]") {
    const Scene scene = parse_scene(scene_with(""), test_file);
    CHECK(scene.box2d.substeps == 1);
    CHECK(scene.box2d.velocity_iterations == 8);
    CHECK(scene.box2d.position_iterations == 3);
    CHECK(scene.box2d.observables.empty());
    const Scene empty = parse_scene(with_box2d("{}"), test_file);
    CHECK(empty.box2d.velocity_iterations == 8);
    CHECK(empty.box2d.observables.empty());
    // The block is part of the scene's content, so of its fingerprint.
    CHECK(parse_scene(with_box2d(R"({"substeps": 2})"), test_file).sha256 != empty.sha256);
}

TEST_CASE("box2d: settings and every observable kind are read with their paths", "[scene]") {
    using Kind = impulse::harness::Box2dObservable::Kind;
    const Scene scene = parse_scene(with_box2d(R"({
        "substeps": 4, "velocity_iterations": 20, "position_iterations": 10.0,
        "observables": [
          {"kind": "impact-times", "body": "tilted", "count": 2, "atol": 0.034},
          {"kind": "apex-heights", "body": "ball", "count": 3, "rtol": 0.1},
          {"kind": "apex-ratios", "body": "crate", "count": 1, "atol": 0.1, "rtol": 0.2},
          {"kind": "post-impact-velocity", "body": "tilted", "impact": 2, "atol": 0.5},
          {"kind": "restitution-residual", "atol": 0.05},
          {"kind": "restitution-residual", "body": "ball", "atol": 0.05},
          {"kind": "momentum", "atol": 1e-5},
          {"kind": "angular-momentum", "atol": 1e-5},
          {"kind": "energy", "rtol": 0.01}]})"),
                                    test_file);
    const impulse::harness::Box2dSettings& b = scene.box2d;
    CHECK(b.substeps == 4);
    CHECK(b.velocity_iterations == 20);
    CHECK(b.position_iterations == 10);
    REQUIRE(b.observables.size() == 9);
    const auto& times = b.observables[0];
    CHECK(times.kind == Kind::impact_times);
    CHECK(times.path == "box2d.observables[0]");
    CHECK(times.body == "tilted");
    CHECK(times.count == 2);
    CHECK(times.atol == 0.034);
    CHECK(times.rtol == 0.0);
    CHECK(b.observables[1].kind == Kind::apex_heights);
    CHECK(b.observables[1].body == "ball");
    CHECK(b.observables[1].count == 3);
    CHECK(b.observables[1].atol == 0.0);
    CHECK(b.observables[1].rtol == 0.1);
    CHECK(b.observables[2].kind == Kind::apex_ratios);
    CHECK(b.observables[2].body == "crate");
    CHECK(b.observables[2].atol == 0.1);
    CHECK(b.observables[2].rtol == 0.2);
    CHECK(b.observables[3].kind == Kind::post_impact_velocity);
    CHECK(b.observables[3].impact == 2);
    CHECK(b.observables[4].kind == Kind::restitution_residual);
    CHECK(b.observables[4].body.empty());
    CHECK(b.observables[5].body == "ball");
    CHECK(b.observables[6].kind == Kind::momentum);
    CHECK(b.observables[7].kind == Kind::angular_momentum);
    CHECK(b.observables[8].kind == Kind::energy);
    CHECK(b.observables[8].path == "box2d.observables[8]");
}

TEST_CASE("rejected box2d blocks: the block and its settings", "[scene]") {
    SECTION("not an object") {
        require_rejected(with_box2d("[]"), "box2d", "must be an object, got an array");
    }
    SECTION("unknown key") {
        require_rejected(with_box2d(R"({"substep": 2})"), "box2d.substep",
                         "unknown key (did you mean substeps?); expected one of substeps, "
                         "velocity_iterations, position_iterations, observables");
    }
    SECTION("substeps 0") {
        require_rejected(with_box2d(R"({"substeps": 0})"), "box2d.substeps",
                         "must be a whole number from 1 to 1000, got 0");
    }
    SECTION("fractional velocity iterations") {
        require_rejected(with_box2d(R"({"velocity_iterations": 2.5})"), "box2d.velocity_iterations",
                         "must be a whole number from 1 to 1000, got 2.5");
    }
    SECTION("position iterations as a string") {
        require_rejected(with_box2d(R"({"position_iterations": "3"})"), "box2d.position_iterations",
                         "must be a number, got \"3\"");
    }
    SECTION("too many substeps") {
        require_rejected(with_box2d(R"({"substeps": 1001})"), "box2d.substeps",
                         "must be a whole number from 1 to 1000, got 1001");
    }
    SECTION("observables not an array") {
        require_rejected(with_box2d(R"({"observables": {}})"), "box2d.observables",
                         "must be an array, got an object");
    }
    SECTION("an observable that is not an object") {
        require_rejected(with_box2d(R"({"observables": [1]})"), "box2d.observables[0]",
                         "must be an object, got 1");
    }
}

TEST_CASE("rejected box2d observables: kind, keys and tolerance", "[scene]") {
    SECTION("kind missing") {
        require_rejected(with_box2d(observing(R"({"body": "ball", "atol": 1})")),
                         "box2d.observables[0].kind", "is required but missing");
    }
    SECTION("unknown kind") {
        require_rejected(with_box2d(observing(R"({"kind": "apex", "atol": 1})")),
                         "box2d.observables[0].kind",
                         "must be one of \"impact-times\", \"apex-heights\", \"apex-ratios\", "
                         "\"post-impact-velocity\", \"restitution-residual\", \"momentum\", "
                         "\"angular-momentum\", \"energy\", got \"apex\"");
    }
    SECTION("a key of another kind") {
        require_rejected(
            with_box2d(observing(R"({"kind": "momentum", "body": "ball", "atol": 1})")),
            "box2d.observables[0].body", "unknown key; expected one of kind, atol, rtol");
    }
    SECTION("a typo in a key") {
        require_rejected(with_box2d(observing(R"({"kind": "apex-heights", "body": "ball", "cont": 2,
                                     "atol": 1})")),
                         "box2d.observables[0].cont", "unknown key (did you mean count?)");
    }
    SECTION("a description is not part of an observable") {
        require_rejected(
            with_box2d(observing(R"({"kind": "energy", "atol": 1, "description": "x"})")),
            "box2d.observables[0].description", "unknown key");
    }
    SECTION("no tolerance") {
        require_rejected(with_box2d(observing(R"({"kind": "energy"})")), "box2d.observables[0]",
                         "must give atol or rtol (or both); an observable has no default "
                         "tolerance");
    }
    SECTION("negative rtol") {
        require_rejected(with_box2d(observing(R"({"kind": "energy", "rtol": -0.5})")),
                         "box2d.observables[0].rtol", "must be >= 0, got -0.5");
    }
    SECTION("atol null") {
        require_rejected(with_box2d(observing(R"({"kind": "energy", "atol": null})")),
                         "box2d.observables[0].atol", "must be a number, got null");
    }
    SECTION("the path names the entry") {
        require_rejected(with_box2d(R"({"observables": [{"kind": "energy", "atol": 1},
                                                         {"kind": "momentum", "atol": -1}]})"),
                         "box2d.observables[1].atol", "must be >= 0, got -1");
    }
}

TEST_CASE("rejected box2d observables: bodies, counts and the drop's preconditions", "[scene]") {
    SECTION("body missing") {
        require_rejected(with_box2d(observing(R"({"kind": "impact-times", "count": 1,
                                                  "atol": 1})")),
                         "box2d.observables[0].body", "is required but missing");
    }
    SECTION("no such body") {
        require_rejected(with_box2d(observing(R"({"kind": "impact-times", "body": "bal",
                                                  "count": 1, "atol": 1})")),
                         "box2d.observables[0].body",
                         "no body is named \"bal\"; the bodies are ground, ball, tilted, crate");
    }
    SECTION("a static body") {
        require_rejected(with_box2d(observing(R"({"kind": "impact-times", "body": "ground",
                                                  "count": 1, "atol": 1})")),
                         "box2d.observables[0].body",
                         "'ground' is static; the impact-times observable needs a dynamic body");
    }
    SECTION("a static body for the residual") {
        require_rejected(with_box2d(observing(R"({"kind": "restitution-residual",
                                                  "body": "ground", "atol": 1})")),
                         "box2d.observables[0].body",
                         "'ground' is static; the restitution-residual observable needs a "
                         "dynamic body");
    }
    SECTION("count missing") {
        require_rejected(with_box2d(observing(R"({"kind": "apex-ratios", "body": "ball",
                                                  "atol": 1})")),
                         "box2d.observables[0].count", "is required but missing");
    }
    SECTION("count 0") {
        require_rejected(with_box2d(observing(R"({"kind": "impact-times", "body": "ball",
                                                  "count": 0, "atol": 1})")),
                         "box2d.observables[0].count",
                         "must be a whole number from 1 to 10000, got 0");
    }
    SECTION("impact missing") {
        require_rejected(with_box2d(observing(R"({"kind": "post-impact-velocity",
                                                  "body": "ball", "atol": 1})")),
                         "box2d.observables[0].impact", "is required but missing");
    }
    SECTION("a fractional impact") {
        require_rejected(with_box2d(observing(R"({"kind": "post-impact-velocity",
                                                  "body": "ball", "impact": 1.5, "atol": 1})")),
                         "box2d.observables[0].impact", "must be a whole number from 1 to 10000");
    }
    SECTION("apex heights without gravity") {
        require_rejected(with_box2d(observing(R"({"kind": "apex-heights", "body": "ball",
                                                  "count": 1, "atol": 1})"),
                                    standard_bodies, R"("gravity": [0, 0],)"),
                         "box2d.observables[0]",
                         "the drop formula behind apex-heights needs gravity (0, -g) with g > 0, "
                         "but the scene's gravity is (0, 0)");
    }
    SECTION("apex ratios of a moving body") {
        require_rejected(
            with_box2d(observing(R"({"kind": "apex-ratios", "body": "b", "count": 1,
                                     "atol": 1})"),
                       R"([{"name": "ground", "static": true, "shape": {"box": [50, 0.5]},
                            "position": [0, -0.5]},
                           {"name": "b", "shape": {"circle": 0.5}, "position": [0, 2],
                            "velocity": [1, 0]}])"),
            "box2d.observables[0].body",
            "the drop formula behind apex-ratios needs the body at rest at t = 0, but 'b' has "
            "velocity (1, 0)");
    }
    SECTION("apex heights of a polygon that would spin") {
        require_rejected(with_box2d(observing(R"({"kind": "apex-heights", "body": "tilted",
                                                  "count": 1, "atol": 1})")),
                         "box2d.observables[0].body",
                         "the drop formula behind apex-heights has no rotation, but 'tilted' is a "
                         "polygon free to rotate that lands neither on one corner below its "
                         "centre nor (with \"contacts\": \"simultaneous\") flat and centred; "
                         "give it \"rotation\": false");
    }
    SECTION("apex heights with nothing to land on") {
        require_rejected(with_box2d(observing(R"({"kind": "apex-heights", "body": "b",
                                                  "count": 1, "atol": 1})"),
                                    free_bodies),
                         "box2d.observables[0].body",
                         "the drop formula behind apex-heights needs static ground for 'b' to "
                         "fall on, but every body is dynamic");
    }
    SECTION("impact times need no drop") {
        CHECK(rejection(with_box2d(observing(R"({"kind": "impact-times", "body": "tilted",
                                                 "count": 3, "atol": 1})"),
                                   standard_bodies, R"("gravity": [0, 0],)"))
                  .empty());
    }
}

// As for the rest of the scene: whatever a value of the box2d block is
// replaced with, only InputError escapes.
TEST_CASE("only InputError escapes from the box2d block", "[scene]") {
    const std::string base = with_box2d(R"({
        "substeps": 2, "velocity_iterations": 8, "position_iterations": 3,
        "observables": [
          {"kind": "impact-times", "body": "tilted", "count": 2, "atol": 0.034},
          {"kind": "apex-heights", "body": "ball", "count": 3, "rtol": 0.1},
          {"kind": "apex-ratios", "body": "crate", "count": 1, "atol": 0.1, "rtol": 0.2},
          {"kind": "post-impact-velocity", "body": "tilted", "impact": 2, "atol": 0.5},
          {"kind": "restitution-residual", "body": "ball", "atol": 0.05},
          {"kind": "momentum", "atol": 1e-5}]})");
    REQUIRE(rejection(base).empty());
    const std::vector<nlohmann::json> replacements = {nullptr,
                                                      true,
                                                      0,
                                                      -1,
                                                      2.5,
                                                      1e308,
                                                      "text",
                                                      "ground",
                                                      "energy",
                                                      nlohmann::json::array(),
                                                      nlohmann::json::array({1, 2}),
                                                      nlohmann::json::object()};
    const nlohmann::json document = nlohmann::json::parse(base);
    const nlohmann::json flat = document.flatten();
    std::vector<std::string> pointers;
    for (const auto& [pointer, value] : flat.items()) {
        if (pointer.rfind("/box2d", 0) != 0) {
            continue;
        }
        for (std::string p = pointer; !p.empty(); p = p.substr(0, p.rfind('/'))) {
            pointers.push_back(p);
        }
    }
    for (const std::string& pointer : pointers) {
        for (const nlohmann::json& replacement : replacements) {
            nlohmann::json changed = document;
            changed[nlohmann::json::json_pointer(pointer)] = replacement;
            INFO(pointer << " = " << replacement.dump());
            CHECK_NOTHROW(rejection(changed.dump()));
        }
    }
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

// ---------------------------------------------------------------- the gas block

namespace {

// A scene of no gravity with the given gas block (its inside, without braces)
// and further top-level keys (end them with a comma).
std::string gas_scene(const std::string& gas, const std::string& extra = "") {
    return R"({"schema": "impulse/scene@1", "name": "gas", "gravity": [0, 0], "dt": 0.01,
               "duration": 1, )" +
           extra + R"( "gas": {)" + gas + "}}";
}

// Five discs of radius 0.1 on a 0.5 m lattice: k = 3 (3 * 3 >= 5 > 2 * 2).
const std::string five = R"("count": 5, "shape": {"circle": 0.1}, "mass": 1, "spacing": 0.5,
                             "max_speed": 5)";

// The rule of docs/formats.md written out again, independently of gas.cpp:
// splitmix64 from `seed`, u = (z >> 11) 2^-53, s = 2 u - 1.
struct Draws {
    std::uint64_t state;
    double next() {
        state += 0x9e3779b97f4a7c15u;
        std::uint64_t z = state;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
        z ^= z >> 31;
        return 2.0 * (static_cast<double>(z >> 11) * 0x1.0p-53) - 1.0;
    }
};

std::uint64_t bits(double value) {
    std::uint64_t out = 0;
    std::memcpy(&out, &value, sizeof out);
    return out;
}

} // namespace

TEST_CASE("splitmix64 gives the reference outputs, and unit() its 53 high bits", "[scene]") {
    // Vigna's splitmix64.c from state 0: the first outputs of the published generator.
    impulse::harness::SplitMix64 random(0);
    CHECK(random.next() == 0xe220a8397b1dcdafu);
    CHECK(random.next() == 0x6e789e6aa1b965f4u);
    CHECK(random.next() == 0x06c45d188009454fu);
    // The 53 high bits: 0xf7a2... >> 11, times 2^-53.
    impulse::harness::SplitMix64 again(0);
    CHECK(again.unit() == static_cast<double>(0xe220a8397b1dcdafu >> 11) * 0x1.0p-53);
    CHECK(again.unit() < 1.0);
}

TEST_CASE("the lattice side and the bounding diameter", "[scene]") {
    using impulse::harness::bounding_diameter;
    using impulse::harness::gas_lattice_side;
    CHECK(gas_lattice_side(1) == 1);
    CHECK(gas_lattice_side(4) == 2);
    CHECK(gas_lattice_side(5) == 3);
    CHECK(gas_lattice_side(9) == 3);
    CHECK(gas_lattice_side(10) == 4);
    CHECK(gas_lattice_side(10000) == 100);
    CHECK(gas_lattice_side(10001) == 101);
    CHECK(gas_lattice_side(100000) == 317); // 316^2 = 99856 < 100000 <= 317^2 = 100489
    CHECK(bounding_diameter(impulse::make_circle(0.1)) == 0.2);
    // Box [0.3, 0.4]: corners 0.5 from the centre.
    CHECK(bounding_diameter(impulse::make_box(0.3, 0.4)) == Approx(1.0).epsilon(1e-15));
}

TEST_CASE("a gas block makes four walls and its bodies on the lattice", "[scene]") {
    const Scene scene = parse_scene(gas_scene(five), test_file);
    REQUIRE(scene.bodies.size() == 9);
    CHECK(scene.listed_bodies == 0);
    REQUIRE(scene.gas.has_value());
    CHECK(scene.gas->count == 5);
    CHECK(scene.gas->seed == 1);
    CHECK(scene.gas->wall_thickness == 1.0);
    CHECK(scene.warnings.empty());

    // k = 3, L = 1.5, h = 0.75; walls 1 m thick, so t = 0.5 and their centres
    // are c = 1.25 from the origin; the side walls are h + 1 = 1.75 tall each way.
    struct Wall {
        const char* name;
        Vec2 position;
        double hx, hy;
    };
    const Wall walls[4] = {{"wall-bottom", {0.0, -1.25}, 0.75, 0.5},
                           {"wall-top", {0.0, 1.25}, 0.75, 0.5},
                           {"wall-left", {-1.25, 0.0}, 0.5, 1.75},
                           {"wall-right", {1.25, 0.0}, 0.5, 1.75}};
    for (std::size_t w = 0; w < 4; ++w) {
        const impulse::harness::SceneBody& body = scene.bodies[w];
        INFO(body.name);
        CHECK(body.name == walls[w].name);
        CHECK(body.is_static);
        CHECK(body.position == walls[w].position);
        CHECK(body.angle == 0.0);
        CHECK(body.mass == 0.0);
        REQUIRE(body.shape.type == ShapeType::polygon);
        // make_box's first vertex is the lower left corner, the third the upper right.
        CHECK(body.shape.polygon.vertices[0] == Vec2{-walls[w].hx, -walls[w].hy});
        CHECK(body.shape.polygon.vertices[2] == Vec2{walls[w].hx, walls[w].hy});
    }
    // Sites at -0.75 + 0.5 (i + 0.5): -0.5, 0, 0.5; row by row from the bottom left.
    const Vec2 sites[5] = {{-0.5, -0.5}, {0.0, -0.5}, {0.5, -0.5}, {-0.5, 0.0}, {0.0, 0.0}};
    for (std::size_t n = 0; n < 5; ++n) {
        const impulse::harness::SceneBody& body = scene.bodies[4 + n];
        INFO(body.name);
        CHECK(body.name == "gas-" + std::to_string(n));
        CHECK_FALSE(body.is_static);
        CHECK(body.rotation);
        CHECK(body.position == sites[n]);
        CHECK(body.shape.type == ShapeType::circle);
        CHECK(body.shape.radius == 0.1);
        CHECK(body.mass == 1.0);
        CHECK(body.inertia == Approx(0.005).epsilon(1e-15)); // m r^2 / 2
        CHECK(body.angle == 0.0);                            // random_angles false
        CHECK(body.angular_velocity == 0.0);                 // max_angular_speed 0
        CHECK(impulse::length_squared(body.velocity) <= 25.0);
    }
    // The velocities by the documented rule: per body, (a, b) until a^2 + b^2 <= 1.
    Draws draws{1};
    for (std::size_t n = 0; n < 5; ++n) {
        double a = 0.0;
        double b = 0.0;
        do {
            a = draws.next();
            b = draws.next();
        } while (!(a * a + b * b <= 1.0));
        CHECK(bits(scene.bodies[4 + n].velocity.x) == bits(5.0 * a));
        CHECK(bits(scene.bodies[4 + n].velocity.y) == bits(5.0 * b));
    }
}

TEST_CASE("a gas's angles and spins follow the velocity draws, body by body", "[scene]") {
    const Scene scene = parse_scene(
        gas_scene(R"("count": 3, "shape": {"box": [0.1, 0.2]}, "density": 2, "spacing": 1,
                     "max_speed": 2, "max_angular_speed": 3, "random_angles": true, "seed": 7,
                     "wall_thickness": 0.25)"),
        test_file);
    REQUIRE(scene.bodies.size() == 7);
    // k = 2, L = 2, h = 1, t = 0.125: bottom wall at y = -1.125.
    CHECK(scene.bodies[0].position == Vec2{0.0, -1.125});
    CHECK(scene.bodies[2].shape.polygon.vertices[2] == Vec2{0.125, 1.25});
    Draws draws{7};
    for (std::size_t n = 0; n < 3; ++n) {
        const impulse::harness::SceneBody& body = scene.bodies[4 + n];
        INFO(body.name);
        double a = 0.0;
        double b = 0.0;
        do {
            a = draws.next();
            b = draws.next();
        } while (!(a * a + b * b <= 1.0));
        CHECK(bits(body.velocity.x) == bits(2.0 * a));
        CHECK(bits(body.velocity.y) == bits(2.0 * b));
        CHECK(bits(body.angle) == bits(3.141592653589793 * draws.next()));
        CHECK(bits(body.angular_velocity) == bits(3.0 * draws.next()));
        CHECK(body.angle >= -3.141592653589793);
        CHECK(body.angle < 3.141592653589793);
        CHECK(std::abs(body.angular_velocity) <= 3.0);
        // Density 2 over 0.2 x 0.4 m: 0.16 kg; I = M (0.2^2 + 0.4^2) / 12.
        CHECK(body.mass == Approx(0.16).epsilon(1e-15));
        CHECK(body.inertia == Approx(0.16 * 0.2 / 12.0).epsilon(1e-14));
    }
    // Sites: (-0.5, -0.5), (0.5, -0.5), (-0.5, 0.5).
    CHECK(scene.bodies[6].position == Vec2{-0.5, 0.5});
}

TEST_CASE("a gas is reproducible: the same seed gives the same bits, another seed others",
          "[scene]") {
    const std::string block = R"("count": 50, "shape": {"box": [0.1, 0.1]}, "spacing": 0.5,
                                  "max_speed": 5, "max_angular_speed": 5, "random_angles": true)";
    const Scene a = parse_scene(gas_scene(block + R"(, "seed": 3)"), test_file);
    const Scene b = parse_scene(gas_scene(block + R"(, "seed": 3)"), "other.json");
    const Scene c = parse_scene(gas_scene(block + R"(, "seed": 4)"), test_file);
    REQUIRE(a.bodies.size() == 54);
    REQUIRE(c.bodies.size() == 54);
    int differ = 0;
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
        for (const auto& [x, y] :
             {std::pair{a.bodies[i].velocity.x, b.bodies[i].velocity.x},
              std::pair{a.bodies[i].velocity.y, b.bodies[i].velocity.y},
              std::pair{a.bodies[i].angle, b.bodies[i].angle},
              std::pair{a.bodies[i].angular_velocity, b.bodies[i].angular_velocity}}) {
            CHECK(bits(x) == bits(y));
        }
        CHECK(a.bodies[i].position == c.bodies[i].position);
        differ += a.bodies[i].velocity != c.bodies[i].velocity ? 1 : 0;
        CHECK(impulse::length_squared(a.bodies[i].velocity) <= 25.0);
    }
    CHECK(differ == 50); // every gas body, none of the walls
    CHECK(a.sha256 == b.sha256);
    CHECK(a.sha256 != c.sha256);
}

TEST_CASE("a gas block goes after the listed bodies, which may be left out or all static",
          "[scene]") {
    SECTION("listed bodies first, then the walls, then the gas") {
        const Scene scene =
            parse_scene(gas_scene(five, R"("bodies": [{"name": "post", "static": true,
                                          "shape": {"circle": 0.05}, "position": [0.25, 0.25]},
                                         {"name": "ball", "shape": {"circle": 0.1},
                                          "position": [10, 10]}],)"),
                        test_file);
        REQUIRE(scene.bodies.size() == 11);
        CHECK(scene.listed_bodies == 2);
        CHECK(scene.bodies[0].name == "post");
        CHECK(scene.bodies[1].name == "ball");
        CHECK(scene.bodies[2].name == "wall-bottom");
        CHECK(scene.bodies[5].name == "wall-right");
        CHECK(scene.bodies[6].name == "gas-0");
        CHECK(scene.bodies[10].name == "gas-4");
    }
    SECTION("an empty bodies array") {
        CHECK(rejection(gas_scene(five, R"("bodies": [],)")).empty());
    }
    SECTION("names that only look like the gas's") {
        CHECK(rejection(gas_scene(five, R"("bodies": [
            {"name": "gas-5", "shape": {"circle": 0.1}, "position": [10, 0]},
            {"name": "gas-01", "shape": {"circle": 0.1}, "position": [20, 0]},
            {"name": "wall", "shape": {"circle": 0.1}, "position": [30, 0]}],)"))
                  .empty());
    }
    SECTION("a polygon off its centroid is recentred, with a warning") {
        const Scene scene = parse_scene(
            gas_scene(R"("count": 1, "shape": {"polygon": [[0, 0], [0.2, 0], [0.2, 0.2], [0, 0.2]]},
                         "spacing": 1, "max_speed": 0)"),
            test_file);
        REQUIRE(scene.warnings.size() == 1);
        CHECK(scene.warnings[0].rfind(test_file + ": gas.shape.polygon: centroid is at (0.1, 0.1)",
                                      0) == 0);
        CHECK(scene.bodies[4].shape.polygon.vertices[0] == Vec2{-0.1, -0.1});
        CHECK(scene.bodies[4].position == Vec2{0.0, 0.0}); // one site, at the centre
    }
}

TEST_CASE("rejected gas blocks", "[scene]") {
    SECTION("not an object") {
        require_rejected(R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01,
                             "duration": 1, "gas": 5})",
                         "gas", "must be an object, got 5");
    }
    SECTION("an unknown key") {
        require_rejected(gas_scene(five + R"(, "colour": "red")"), "gas.colour", "unknown key");
    }
    SECTION("a typo of a key") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacng": 0.5,
                                      "max_speed": 5)"),
                         "gas.spacng", "unknown key (did you mean spacing?)");
    }
    SECTION("count missing") {
        require_rejected(gas_scene(R"("shape": {"circle": 0.1}, "spacing": 0.5, "max_speed": 5)"),
                         "gas.count", "is required but missing");
    }
    SECTION("count 0") {
        require_rejected(gas_scene(R"("count": 0, "shape": {"circle": 0.1}, "spacing": 0.5,
                                      "max_speed": 5)"),
                         "gas.count", "must be a whole number from 1 to 100000, got 0");
    }
    SECTION("count 1.5") {
        require_rejected(gas_scene(R"("count": 1.5, "shape": {"circle": 0.1}, "spacing": 0.5,
                                      "max_speed": 5)"),
                         "gas.count", "must be a whole number from 1 to 100000, got 1.5");
    }
    SECTION("count above 100000") {
        require_rejected(gas_scene(R"("count": 100001, "shape": {"circle": 0.1}, "spacing": 0.5,
                                      "max_speed": 5)"),
                         "gas.count", "got 100001");
    }
    SECTION("count a string") {
        require_rejected(gas_scene(R"("count": "5", "shape": {"circle": 0.1}, "spacing": 0.5,
                                      "max_speed": 5)"),
                         "gas.count", "must be a number");
    }
    SECTION("shape missing") {
        require_rejected(gas_scene(R"("count": 5, "spacing": 0.5, "max_speed": 5)"), "gas.shape",
                         "is required but missing");
    }
    SECTION("a bad shape") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": -0.1}, "spacing": 0.5,
                                      "max_speed": 5)"),
                         "gas.shape.circle", "must be > 0");
    }
    SECTION("mass and density together") {
        require_rejected(gas_scene(five + R"(, "density": 2)"), "gas.density",
                         "give mass or density, not both");
    }
    SECTION("mass negative") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "mass": -1,
                                      "spacing": 0.5, "max_speed": 5)"),
                         "gas.mass", "must be > 0, got -1");
    }
    SECTION("spacing missing") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "max_speed": 5)"),
                         "gas.spacing", "is required but missing");
    }
    SECTION("spacing zero") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacing": 0,
                                      "max_speed": 5)"),
                         "gas.spacing", "must be > 0, got 0");
    }
    SECTION("spacing equal to a disc's diameter") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacing": 0.2,
                                      "max_speed": 5)"),
                         "gas.spacing",
                         "must be more than the shape's bounding diameter 0.2 m (twice its "
                         "furthest point from the centroid), so that no two bodies overlap at any "
                         "angle, got 0.2");
    }
    SECTION("spacing enough for a box side by side but not turned") {
        // Box [0.1, 0.1]: corners sqrt(0.02) from the centre, diameter 0.2828...
        require_rejected(gas_scene(R"("count": 5, "shape": {"box": [0.1, 0.1]}, "spacing": 0.25,
                                      "max_speed": 5)"),
                         "gas.spacing", "bounding diameter 0.28284271247461906 m");
    }
    SECTION("spacing so large the room is not finite") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacing": 1e308,
                                      "max_speed": 5)"),
                         "gas.spacing", "gives a room inf m wide; it must be finite");
    }
    SECTION("walls so thick the room is not finite") {
        require_rejected(gas_scene(five + R"(, "wall_thickness": 1e308)"), "gas.wall_thickness",
                         "it must be finite");
    }
    SECTION("max_speed missing") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacing": 0.5)"),
                         "gas.max_speed", "is required but missing");
    }
    SECTION("max_speed negative") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacing": 0.5,
                                      "max_speed": -1)"),
                         "gas.max_speed", "must be >= 0, got -1");
    }
    SECTION("max_angular_speed negative") {
        require_rejected(gas_scene(five + R"(, "max_angular_speed": -0.5)"),
                         "gas.max_angular_speed", "must be >= 0, got -0.5");
    }
    SECTION("random_angles not a bool") {
        require_rejected(gas_scene(five + R"(, "random_angles": 1)"), "gas.random_angles",
                         "must be true or false, got 1");
    }
    SECTION("seed negative") {
        require_rejected(gas_scene(five + R"(, "seed": -1)"), "gas.seed",
                         "must be a whole number from 0 to 9007199254740992, got -1");
    }
    SECTION("seed fractional") {
        require_rejected(gas_scene(five + R"(, "seed": 0.5)"), "gas.seed", "got 0.5");
    }
    SECTION("seed above 2^53") {
        require_rejected(gas_scene(five + R"(, "seed": 18014398509481984)"), "gas.seed",
                         "must be a whole number from 0 to 9007199254740992");
    }
    SECTION("wall_thickness zero") {
        require_rejected(gas_scene(five + R"(, "wall_thickness": 0)"), "gas.wall_thickness",
                         "must be > 0, got 0");
    }
    SECTION("a listed body takes a wall's name") {
        require_rejected(gas_scene(five, R"("bodies": [{"name": "wall-left",
                                                      "shape": {"circle": 0.1},
                                                      "position": [10, 0]}],)"),
                         "gas",
                         "makes a body named \"wall-left\", which is already the name of "
                         "bodies[0]; body names must be unique");
    }
    SECTION("a listed body takes a gas body's name") {
        require_rejected(gas_scene(five, R"("bodies": [{"name": "ball", "shape": {"circle": 0.1},
                                                      "position": [10, 0]},
                                                     {"name": "gas-4", "shape": {"circle": 0.1},
                                                      "position": [20, 0]}],)"),
                         "gas", "\"gas-4\", which is already the name of bodies[1]");
    }
    SECTION("a listed body inside the room, overlapping a gas body") {
        // gas-4 (scene body 1 + 4 + 4 = 9) at the origin, the ball 0.1 above it:
        // gap 0.1 - 0.1 - 0.1.
        require_rejected(gas_scene(five, R"("bodies": [{"name": "ball", "shape": {"circle": 0.1},
                                                      "position": [0, 0.1]}],)"),
                         "gas", "'gas-4' overlaps bodies[0] 'ball' at t = 0 by 0.1 m");
    }
    SECTION("a listed body in a wall") {
        require_rejected(gas_scene(five, R"("bodies": [{"name": "ball", "shape": {"circle": 0.1},
                                                      "position": [0, 1.25]}],)"),
                         "gas", "'wall-top' overlaps bodies[0] 'ball' at t = 0 by");
    }
    SECTION("neither bodies nor gas") {
        require_rejected(R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1})",
                         "bodies",
                         "is required but missing; a scene lists its bodies, has a gas "
                         "block, or both");
    }
}

// Whatever a value of the gas block is replaced with, only InputError escapes.
TEST_CASE("only InputError escapes from the gas block", "[scene]") {
    const std::string base =
        gas_scene(R"("count": 7, "shape": {"polygon": [[-0.1, -0.1], [0.1, -0.1], [0, 0.1]]},
                     "density": 2, "spacing": 0.5, "max_speed": 5, "max_angular_speed": 1,
                     "random_angles": true, "seed": 12, "wall_thickness": 0.5)");
    REQUIRE(rejection(base).empty());
    const std::vector<nlohmann::json> replacements = {nullptr,
                                                      true,
                                                      false,
                                                      0,
                                                      -1,
                                                      2.5,
                                                      1e308,
                                                      "text",
                                                      nlohmann::json::array(),
                                                      nlohmann::json::array({1, 2}),
                                                      nlohmann::json::object()};
    const nlohmann::json document = nlohmann::json::parse(base);
    const nlohmann::json flat = document.flatten();
    std::vector<std::string> pointers;
    for (const auto& [pointer, value] : flat.items()) {
        if (pointer.rfind("/gas", 0) != 0) {
            continue;
        }
        for (std::string p = pointer; !p.empty(); p = p.substr(0, p.rfind('/'))) {
            pointers.push_back(p);
        }
    }
    for (const std::string& pointer : pointers) {
        for (const nlohmann::json& replacement : replacements) {
            nlohmann::json changed = document;
            changed[nlohmann::json::json_pointer(pointer)] = replacement;
            INFO(pointer << " = " << replacement.dump());
            CHECK_NOTHROW(rejection(changed.dump()));
        }
    }
}

// ---------------------------------------------------------------- overlaps, by a sweep

namespace {

std::string shortest(double value) {
    char buffer[32];
    const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

// A body of a generated overlap scene, as the file will say it.
struct Made {
    std::string name;
    bool is_static = false;
    bool circle = true;
    double a = 0.0, b = 0.0; // radius, or half extents
    Vec2 position;
    double angle = 0.0;
};

impulse::Shape shape_of(const Made& m) {
    return m.circle ? impulse::make_circle(m.a) : impulse::make_box(m.a, m.b);
}

// The rule before the sweep, kept here as the reference: every pair (j, i < j)
// in order, the first that overlaps is named at bodies[j]. Empty when none does.
std::string old_rule(const std::vector<Made>& bodies) {
    for (std::size_t j = 1; j < bodies.size(); ++j) {
        const impulse::Transform xb{bodies[j].position, impulse::rotation_of(bodies[j].angle)};
        for (std::size_t i = 0; i < j; ++i) {
            if (bodies[i].is_static && bodies[j].is_static) {
                continue;
            }
            const impulse::Transform xa{bodies[i].position, impulse::rotation_of(bodies[i].angle)};
            const double gap =
                impulse::separation(shape_of(bodies[i]), xa, shape_of(bodies[j]), xb);
            if (gap < 0.0) {
                return test_file + ": bodies[" + std::to_string(j) + "]: '" + bodies[j].name +
                       "' overlaps bodies[" + std::to_string(i) + "] '" + bodies[i].name +
                       "' at t = 0 by " + shortest(-gap) + " m";
            }
        }
    }
    return "";
}

std::string scene_of(const std::vector<Made>& bodies) {
    nlohmann::json list = nlohmann::json::array();
    for (const Made& m : bodies) {
        nlohmann::json body = {
            {"name", m.name}, {"position", {m.position.x, m.position.y}}, {"angle", m.angle}};
        body["shape"] =
            m.circle ? nlohmann::json{{"circle", m.a}} : nlohmann::json{{"box", {m.a, m.b}}};
        if (m.is_static) {
            body["static"] = true;
        }
        list.push_back(body);
    }
    return scene_with_bodies(list.dump());
}

} // namespace

TEST_CASE("the overlap sweep names the same first pair as the pairwise rule", "[scene]") {
    SECTION("the first pair by (j, i) is not the first the sweep meets") {
        // c and d, far left, overlap by 1.5 and are swept first; a and b, on the
        // right, overlap by 1 and come first in the file: (1, 0) before (3, 2).
        const std::string text = scene_with_bodies(R"([
            {"name": "a", "shape": {"circle": 1}, "position": [10, 0]},
            {"name": "b", "shape": {"circle": 1}, "position": [11, 0]},
            {"name": "c", "shape": {"circle": 1}, "position": [-10, 0]},
            {"name": "d", "shape": {"circle": 1}, "position": [-9.5, 0]}])");
        CHECK(rejection(text) ==
              test_file + ": bodies[1]: 'b' overlaps bodies[0] 'a' at t = 0 by 1 m");
    }
    SECTION("one body over two: the smaller i, though the sweep meets the other first") {
        // The bar overlaps q (left, met first) and p (right, listed first). The
        // disc p's centre is 0.5 inside the bar's right face: -0.5 - 1.
        const std::string text = scene_with_bodies(R"([
            {"name": "p", "shape": {"circle": 1}, "position": [2, 0]},
            {"name": "q", "shape": {"circle": 1}, "position": [-2, 0]},
            {"name": "bar", "shape": {"box": [2.5, 0.5]}}])");
        CHECK(rejection(text) ==
              test_file + ": bodies[2]: 'bar' overlaps bodies[0] 'p' at t = 0 by 1.5 m");
    }
    SECTION("a later pair with a smaller j wins over an earlier-swept larger j") {
        // (2, 1) is the first by j; (3, 0) is further left.
        const std::string text = scene_with_bodies(R"([
            {"name": "w", "shape": {"box": [0.5, 0.5]}, "position": [-20, 0]},
            {"name": "x", "shape": {"box": [0.5, 0.5]}, "position": [5, 0]},
            {"name": "y", "shape": {"box": [0.5, 0.5]}, "position": [5.75, 0.25]},
            {"name": "z", "shape": {"box": [0.5, 0.5]}, "position": [-19.5, 0]}])");
        const std::string message = rejection(text);
        CHECK(message.rfind(test_file + ": bodies[2]: 'y' overlaps bodies[1] 'x' at t = 0 by", 0) ==
              0);
    }
    SECTION("static pairs are skipped, static-dynamic pairs are not") {
        const std::string text = scene_with_bodies(R"([
            {"name": "floor", "static": true, "shape": {"box": [5, 0.5]}},
            {"name": "wall", "static": true, "shape": {"box": [0.5, 5]}},
            {"name": "ball", "shape": {"circle": 1}, "position": [3, 1]}])");
        CHECK(rejection(text) ==
              test_file + ": bodies[2]: 'ball' overlaps bodies[0] 'floor' at t = 0 by 0.5 m");
    }
    SECTION("random crowds of discs and turned boxes, against the pairwise rule") {
        std::mt19937_64 rng(20240601);
        const auto uniform = [&](double lo, double hi) {
            return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
        };
        int rejected = 0;
        for (int scene = 0; scene < 200; ++scene) {
            std::vector<Made> bodies;
            const int n = 2 + static_cast<int>(rng() % 30);
            for (int k = 0; k < n; ++k) {
                Made m;
                m.name = "b" + std::to_string(k);
                m.is_static = rng() % 4 == 0;
                m.circle = rng() % 2 == 0;
                m.a = uniform(0.05, 0.5);
                m.b = uniform(0.05, 0.5);
                m.position = {uniform(-6.0, 6.0), uniform(-6.0, 6.0)};
                m.angle = m.circle ? 0.0 : uniform(-3.0, 3.0);
                bodies.push_back(m);
            }
            if (std::all_of(bodies.begin(), bodies.end(),
                            [](const Made& m) { return m.is_static; })) {
                bodies[0].is_static = false;
            }
            const std::string text = scene_of(bodies);
            const std::string expected = old_rule(bodies);
            INFO("scene " << scene << ": " << text);
            CHECK(rejection(text) == expected);
            rejected += expected.empty() ? 0 : 1;
        }
        // Crowded enough that most scenes overlap somewhere, loose enough that some do not.
        CHECK(rejected > 50);
        CHECK(rejected < 200);
    }
}

// ---------------------------------------------------------------- the scale scenes

TEST_CASE("the gas scenes load with local stepping and their expectations", "[scene]") {
    const std::string dir = std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes/";
    using Kind = impulse::harness::Expectation::Kind;
    for (const std::string kind : {"circles", "boxes"}) {
        for (const int count : {10, 100, 1000, 10000}) {
            const std::string name = "gas-" + kind + "-" + std::to_string(count);
            INFO(name);
            const Scene scene = load_scene(dir + "scale/" + name + ".json");
            CHECK(scene.name == name);
            CHECK(scene.bodies.size() == static_cast<std::size_t>(count) + 4);
            CHECK(scene.bodies.back().name == "gas-" + std::to_string(count - 1));
            CHECK(scene.solver.stepping == impulse::Stepping::local);
            CHECK(scene.solver.integrator == Integrator::symplectic_euler);
            CHECK(scene.solver.toi == impulse::TimeOfImpactMethod::secant);
            CHECK(scene.gravity == Vec2{0.0, 0.0});
            CHECK(scene.restitution == 1.0);
            CHECK(scene.duration == 2.0);
            CHECK(scene.dt == 1.0 / 60.0);
            CHECK(scene.gas->random_angles == (kind == "boxes"));
            REQUIRE(scene.expectations.size() == 2);
            CHECK(scene.expectations[0].kind == Kind::conserved);
            CHECK(scene.expectations[0].rtol == 1e-9);
            CHECK(scene.expectations[1].kind == Kind::momentum_balance);
            CHECK(scene.expectations[1].rtol == 1e-9);
        }
        const Scene canonical = load_scene(dir + "gas-" + kind + ".json");
        CHECK(canonical.bodies.size() == 14);
        CHECK(canonical.duration == 3.0);
        CHECK(canonical.solver.stepping == impulse::Stepping::local);
        CHECK(canonical.expectations.size() == 2);
    }
}

TEST_CASE("momentum-balance is read, and refused under gravity", "[scene]") {
    const Scene scene =
        parse_scene(gas_scene(five, R"("expectations": [{"kind": "momentum-balance", "rtol": 1e-9,
                                             "description": "walls"}],)"),
                    test_file);
    REQUIRE(scene.expectations.size() == 1);
    CHECK(scene.expectations[0].kind == impulse::harness::Expectation::Kind::momentum_balance);
    CHECK(scene.expectations[0].description == "walls");
    require_rejected(expecting(R"([{"kind": "momentum-balance", "rtol": 1e-9}])"),
                     "expectations[0]",
                     "momentum-balance needs zero gravity, but the scene's gravity is (0, -9.81); "
                     "gravity would add m g t to the momentum");
    require_rejected(gas_scene(five, R"("expectations": [{"kind": "momentum-balance",
                                                          "rtol": 1e-9, "body": "gas-0"}],)"),
                     "expectations[0].body", "unknown key");
}

TEST_CASE("a drop of a box landing flat needs simultaneous contacts and a centred landing",
          "[scene]") {
    // Two level lowest corners below the centre take equal impulses only when
    // both are solved together; one at a time, the first makes the box spin.
    const auto flat_drop = [](const std::string& solver, const std::string& x) {
        return R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1, )" +
               solver + R"( "bodies": [
                   {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
                   {"name": "box", "shape": {"box": [1, 0.5]}, "position": [)" +
               x + R"(, 1.5]}],
               "expectations": [{"kind": "drop", "body": "box", "impacts": 2, "atol": 1e-9}]})";
    };
    const Scene accepted =
        parse_scene(flat_drop(R"("solver": {"contacts": "simultaneous"},)", "0"), test_file);
    CHECK(accepted.expectations.size() == 1);
    require_rejected(flat_drop("", "0"), "expectations[0].body",
                     "lands neither on one corner below its centre nor");
    // A flat box is centred on its own bottom edge wherever it is: still accepted.
    CHECK_NOTHROW(
        parse_scene(flat_drop(R"("solver": {"contacts": "simultaneous"},)", "3.25"), test_file));
}
