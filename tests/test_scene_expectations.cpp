// Scene loading, the tolerance and the expectations (docs/design.md, "Scene
// format"): every kind read with its values, and one case per rejected input,
// each checked for the file name, the exact JSON path and the reason
// (support/scene_text.h).
#include "input_error.h"
#include "scene.h"
#include "support/scene_text.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

using impulse::harness::InputError;
using impulse::harness::parse_scene;
using impulse::harness::Scene;
using namespace impulse::test;

// ---------------------------------------------------------------- tolerance and expectations

namespace {

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
                         "\"state\", \"max-overlap\", \"at-rest\", got \"bounce\"");
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
            "expectations[0].body",
            "unknown key; the keys allowed here are kind, description, atol, rtol");
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
        require_only_input_errors(document, {"/expectations", "/tolerance"}, replacements);
    }
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
