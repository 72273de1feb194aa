// Scene loading, the bodies and their shapes (docs/design.md, "Scene format"): the
// derived mass properties, polygon recentring, overlaps at t = 0, and one case
// per rejected body, each checked for the file name, the exact JSON path and
// the reason (support/scene_text.h).
#include "body.h"
#include "input_error.h"
#include "manifold.h"
#include "rotation.h"
#include "scene.h"
#include "support/scene_text.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

using impulse::Vec2;
using impulse::harness::InputError;
using impulse::harness::parse_scene;
using impulse::harness::Scene;
using namespace impulse::test;

// ---------------------------------------------------------------- accepted bodies

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

TEST_CASE("a sliver is recentred when its centroid is off by a fraction of its width", "[scene]") {
    // A triangle 2 m long and h = 2.1e-9 m tall, given with its base on the
    // origin: the centroid is h / 3 = 7e-10 m up, far below 1e-9 of its size
    // but a third of its width, and left there the origin lies on its base
    // (inradius about the origin 0: refused as having no thickness).
    const double h = 2.1e-9;
    const Scene off = parse_scene(
        scene_with_body(R"("shape": {"polygon": [[-1, 0], [1, 0], [0, 2.1e-9]]})"), test_file);
    REQUIRE(off.warnings.size() == 1);
    CHECK(std::abs(off.bodies[0].position.y - h / 3.0) <= 1e-24);
    // About the centroid a triangle's sides are a third of their altitudes
    // away; the base's altitude, h, is the least.
    CHECK(std::abs(impulse::inradius(off.bodies[0].shape) - h / 3.0) <= 1e-6 * h);
    // The same triangle given centred (up to the centroid's rounding, about
    // 1e-16 m) is left alone.
    const Scene centred = parse_scene(
        scene_with_body(R"("shape": {"polygon": [[-1, -7e-10], [1, -7e-10], [0, 1.4e-9]]})"),
        test_file);
    CHECK(centred.warnings.empty());
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

// Ten boxes of half side 0.15 stacked at y = 0.15 + 0.3 k on a floor: in
// decimal they touch, in binary some neighbours overlap by a rounding (the
// precondition is checked with the narrow phase's own separation). Resting
// contact counts a pair inside its band d as touching, so such a stack loads
// with "resting": true; without it the refusal says what would carry it.
TEST_CASE("bodies stacked at decimal heights touch under resting contact", "[scene]") {
    nlohmann::json scene = nlohmann::json::parse(R"({
        "schema": "impulse/scene@1", "name": "t", "description": "d", "gravity": [0, -9.81],
        "restitution": 0.5, "dt": 0.01, "duration": 1, "solver": {"resting": true},
        "bodies": [{"name": "floor", "static": true, "shape": {"box": [5, 0.5]},
                    "position": [0, -0.5]}]})");
    double deepest = 0.0;
    for (int k = 0; k < 10; ++k) {
        const double y = 0.15 + 0.3 * k;
        scene["bodies"].push_back({{"name", "b" + std::to_string(k)},
                                   {"shape", {{"box", {0.15, 0.15}}}},
                                   {"position", {0.0, y}}});
        if (k > 0) {
            const impulse::Shape box = impulse::make_box(0.15, 0.15);
            impulse::BodyState lower;
            impulse::BodyState upper;
            lower.position = {0.0, 0.15 + 0.3 * (k - 1)};
            upper.position = {0.0, y};
            deepest = std::min(deepest, impulse::separation(box, impulse::transform_of(lower), box,
                                                            impulse::transform_of(upper)));
        }
    }
    REQUIRE(deepest < 0.0);    // some pair overlaps by rounding alone
    REQUIRE(deepest > -1e-15); // and by nothing more
    CHECK(rejection(scene.dump()).empty());
    scene["solver"]["resting"] = false;
    const std::string refusal = rejection(scene.dump());
    CHECK(refusal.find("at t = 0 by") != std::string::npos);
    CHECK(refusal.find("no more than the rounding of the positions: with \"resting\": true such "
                       "a pair counts as touching") != std::string::npos);
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
    require_only_input_errors(document, {""}, replacements);
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
                       "' at t = 0 by " + shortest(-gap) +
                       " m; move them apart by at least that, so that they start separate or "
                       "touching";
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
              test_file +
                  ": bodies[1]: 'b' overlaps bodies[0] 'a' at t = 0 by 1 m"
                  "; move them apart by at least that, so that they start separate or touching");
    }
    SECTION("one body over two: the smaller i, though the sweep meets the other first") {
        // The bar overlaps q (left, met first) and p (right, listed first). The
        // disc p's centre is 0.5 inside the bar's right face: -0.5 - 1.
        const std::string text = scene_with_bodies(R"([
            {"name": "p", "shape": {"circle": 1}, "position": [2, 0]},
            {"name": "q", "shape": {"circle": 1}, "position": [-2, 0]},
            {"name": "bar", "shape": {"box": [2.5, 0.5]}}])");
        CHECK(rejection(text) ==
              test_file +
                  ": bodies[2]: 'bar' overlaps bodies[0] 'p' at t = 0 by 1.5 m"
                  "; move them apart by at least that, so that they start separate or touching");
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
              test_file +
                  ": bodies[2]: 'ball' overlaps bodies[0] 'floor' at t = 0 by 0.5 m"
                  "; move them apart by at least that, so that they start separate or touching");
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
