// Scene loading, the tolerance and the expectations (docs/design.md, "Scene
// format"): every kind read with its values, and the rejected lists and
// common keys, each checked for the file name, the exact JSON path and the
// reason (support/scene_text.h). Each kind's own rejections are in
// test_rejected_expectations.cpp.
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
