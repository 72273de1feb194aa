// Scene loading, the "box2d" block (docs/design.md, "Scene format"): its settings
// and observables read with their paths, and one case per rejected input, each
// checked for the file name, the exact JSON path and the reason
// (support/scene_text.h).
#include "input_error.h"
#include "scene.h"
#include "sha256.h"
#include "support/scene_text.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

using impulse::harness::InputError;
using impulse::harness::parse_scene;
using impulse::harness::Scene;
using namespace impulse::test;

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
        require_rejected(
            with_box2d(R"({"substep": 2})"), "box2d.substep",
            "unknown key (did you mean substeps?); the keys allowed here are substeps, "
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
            "box2d.observables[0].body", "unknown key; the keys allowed here are kind, atol, rtol");
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
    require_only_input_errors(document, {"/box2d"}, replacements);
}
