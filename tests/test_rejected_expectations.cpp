// Scene loading, each expectation kind's rejected inputs (docs/formats.md,
// "Expectations"): one case per input, each checked for the file name, the
// exact JSON path and the reason (support/scene_text.h).
#include "exact_answers.h"
#include "input_error.h"
#include "scene.h"
#include "support/scene_text.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

using namespace impulse::test;

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
    SECTION("within the contact tolerance of the ground") {
        // 0.5e-9 m above it, and the default tolerance is 1e-9 m: the pair
        // counts as touching from the start and never collides.
        require_rejected(
            expecting(drop(R"("ball")"),
                      R"([{"name": "ground", "static": true, "shape": {"box": [50, 0.5]},
                           "position": [0, -0.5]},
                          {"name": "ball", "shape": {"circle": 0.5},
                           "position": [0, 0.5000000005]}])"),
            "expectations[0].body",
            "the drop formula needs a gap between 'ball' and the static ground at t = 0 wider "
            "than solver.contact_tolerance (1e-09 m), within which the two count as touching "
            "and never collide, but it is 5");
    }
    SECTION("the ground is what the body falls onto, not a roof or a wall nearer to it") {
        // Ground top at y = 0, ball of radius 0.5 at y = 2.5: h0 = 2 m. A roof
        // 0.9 m above it and a wall 0.1 m beside it are nearer, but a body
        // falling straight down never meets them (an outside review found the
        // formula taking either as the ground: first impact at 0.43 s or
        // 0.14 s instead of sqrt(2 h0 / g) = 0.639 s).
        const std::string bodies =
            R"([{"name": "ground", "static": true, "shape": {"box": [50, 0.5]},
                 "position": [0, -0.5]},
                {"name": "roof", "static": true, "shape": {"box": [5, 0.5]},
                 "position": [0, 4.4]},
                {"name": "wall", "static": true, "shape": {"box": [0.5, 5]},
                 "position": [1.1, 5]},
                {"name": "ball", "shape": {"circle": 0.5}, "position": [0, 2.5]}])";
        const impulse::harness::Scene scene =
            impulse::harness::parse_scene(expecting(drop(R"("ball")"), bodies), test_file);
        const auto landing = impulse::harness::landing_below(scene, scene.bodies[3]);
        REQUIRE(landing);
        CHECK(landing->gap == 2.0);
        CHECK(scene.bodies[static_cast<std::size_t>(landing->ground)].name == "ground");
    }
    SECTION("ground below that is sloped") {
        require_rejected(
            expecting(drop(R"("ball")"),
                      R"([{"name": "ground", "static": true, "shape": {"box": [50, 0.5]},
                           "position": [0, -0.5], "angle": 0.1},
                          {"name": "ball", "shape": {"circle": 0.5}, "position": [0, 3]}])"),
            "expectations[0].body",
            "the drop formula needs 'ball' to land on a level surface, but moved straight down "
            "it meets 'ground' where the contact normal is (");
    }
    SECTION("a ball over the corner of a ledge") {
        // The ledge's top right corner is at x = -0.3, under the ball's left
        // half: the ball lands on the corner and leaves along the line of centres.
        require_rejected(expecting(drop(R"("ball")"),
                                   R"([{"name": "ledge", "static": true, "shape": {"box": [1, 0.5]},
                           "position": [-1.3, -0.5]},
                          {"name": "ball", "shape": {"circle": 0.5}, "position": [0, 3]}])"),
                         "expectations[0].body",
                         "to land on a level surface, but moved straight down it "
                         "meets 'ledge' where the contact normal is (");
    }
    SECTION("a box landing flat on a ledge narrower than it") {
        require_rejected(
            expecting(drop(R"("box")"),
                      R"([{"name": "ledge", "static": true, "shape": {"box": [0.2, 0.5]},
                           "position": [0.4, -0.5]},
                          {"name": "box", "shape": {"box": [0.5, 0.5]}, "position": [0, 3]}])",
                      R"("solver": {"contacts": "simultaneous"},)"),
            "expectations[0].body",
            "the drop formula needs the ground's impulse on 'box' at its centre, x = 0, but moved "
            "straight down it meets 'ledge' at x = 0.3");
    }
    SECTION("nothing static below") {
        require_rejected(
            expecting(drop(R"("ball")"),
                      R"([{"name": "ground", "static": true, "shape": {"box": [1, 0.5]},
                           "position": [5, -0.5]},
                          {"name": "ball", "shape": {"circle": 0.5}, "position": [0, 3]}])"),
            "expectations[0].body",
            "needs static ground for 'ball' to fall on, but moved straight down it meets no "
            "static body");
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
        // The way out names a kind, not a quantity (an outside review
        // followed "use energy-non-increasing" into the quantities list).
        require_rejected(expecting(conserved(R"(["energy"])"), free_bodies,
                                   R"("gravity": [0, 0], "restitution": 0.5,)"),
                         "expectations[0].quantities[0]",
                         "declare {\"kind\": \"energy-non-increasing\"} in its place");
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
