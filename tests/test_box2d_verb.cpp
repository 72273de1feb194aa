// The `impulse box2d` verb (harness/cli): its options, its JSON and its table
// on a canonical scene, its exit codes. The observables it compares are
// tested on hand-made trajectories in test_observables.cpp.
#include "cli.h"
#include "observables.h"
#include "scene.h"
#include "support/trajectories.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using namespace impulse::test;

namespace {

struct Verb {
    int exit_code = -1;
    std::string out;
    std::string err;
};

Verb box2d_verb(const std::vector<std::string>& args) {
    std::ostringstream out, err;
    Verb v;
    v.exit_code = impulse::harness::cli::box2d_verb(args, out, err);
    v.out = out.str();
    v.err = err.str();
    return v;
}

} // namespace

TEST_CASE("box2d verb: bad options are usage errors", "[observables]") {
    using impulse::harness::cli::UsageError;
    CHECK_THROWS_AS(box2d_verb({"--substeps", "0"}), UsageError);
    CHECK_THROWS_AS(box2d_verb({"--velocity-iterations", "eight"}), UsageError);
    CHECK_THROWS_AS(box2d_verb({"--dt", "-1"}), UsageError);
    CHECK_THROWS_AS(box2d_verb({"--tolerance"}), UsageError);
    const Verb help = box2d_verb({"--help"});
    CHECK(help.exit_code == 0);
    CHECK(help.out.find("--scene-integrator") != std::string::npos);
}

#ifdef IMPULSE_WITH_BOX2D

TEST_CASE("box2d verb: the JSON has every scene's rows, nulls where a value is missing",
          "[observables]") {
    const Verb v = box2d_verb({"drop-box", "head-on", "--root", IMPULSE_SOURCE_DIR, "--json"});
    INFO(v.err);
    CHECK(v.exit_code == 0);
    const nlohmann::json doc = nlohmann::json::parse(v.out);
    CHECK(doc["schema"] == "impulse/box2d-comparison@1");
    CHECK(doc["impulse_integrator"] == "symplectic-euler");
    REQUIRE(doc["scenes"].size() == 2);
    const nlohmann::json& drop = doc["scenes"][0];
    CHECK(drop["name"] == "drop-box");
    CHECK(drop["passed"] == true);
    CHECK(drop["impulse"]["integrator"] == "symplectic-euler");
    CHECK(drop["box2d"]["velocity_iterations"] == 8);
    CHECK(drop["box2d"]["position_iterations"] == 3);
    CHECK(drop["box2d"]["substeps"] == 1);
    // The drop's bounces die out sooner under symplectic Euler: the impulse
    // engine stops in a Zeno cascade before 3 s and the runs are compared up to there.
    CHECK(drop["stopped"].is_string());
    REQUIRE_FALSE(drop["rows"].empty());
    for (const nlohmann::json& row : drop["rows"]) {
        for (const char* key : {"path", "name", "exact", "impulse", "box2d", "impulse_error",
                                "box2d_error", "difference", "tolerance", "within", "note"}) {
            CHECK(row.contains(key));
        }
        CHECK(row["within"] == true);
        CHECK(row["impulse"].is_number());
        CHECK(row["box2d"].is_number());
    }
    const nlohmann::json& first = drop["rows"][0];
    CHECK(first["name"] == "impact 1 time of 'box' (s)");
    // The exact answer of the drop: t1 = sqrt(2 h0 / g) with h0 = 1, g = 9.81.
    CHECK(first["exact"].get<double>() == Approx(std::sqrt(2.0 / 9.81)).epsilon(1e-12));
    CHECK(first["difference"].get<double>() ==
          Approx(first["box2d"].get<double>() - first["impulse"].get<double>()));
    // head-on's impact time has no exact answer: null.
    const nlohmann::json& head_on = doc["scenes"][1];
    CHECK(head_on["rows"][0]["exact"].is_null());
    CHECK(head_on["rows"][0]["impulse_error"].is_null());
}

TEST_CASE("box2d verb: the table, the summary and the legend", "[observables]") {
    const Verb v = box2d_verb({"tilted-box", "--root", IMPULSE_SOURCE_DIR});
    CHECK(v.exit_code == 0);
    CHECK(v.out.find("symplectic-euler, Box2D's own integrator") != std::string::npos);
    CHECK(v.out.find("observable") != std::string::npos);
    CHECK(v.out.find("Box2D - impulse") != std::string::npos);
    CHECK(v.out.find("vy after impact 1 of 'tilted30' (m/s)") != std::string::npos);
    CHECK(v.out.find("ok      tilted-box") != std::string::npos);
    CHECK(v.out.find("1 scene: 1 passed, 0 failed") != std::string::npos);
    CHECK(v.out.find("b2_polygonRadius") != std::string::npos);
}

TEST_CASE("box2d verb: a row outside its tolerance fails the scene with exit 1", "[observables]") {
    // tilted-box's observables with every tolerance 0: Box2D's impact comes a
    // step or two after the exact one, so its time alone is off.
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "impulse-obs-test";
    std::filesystem::create_directories(dir);
    const std::filesystem::path scene = dir / "strict.json";
    std::ofstream(scene)
        << R"({"schema": "impulse/scene@1", "name": "strict", "dt": 0.016666666666666666,
        "duration": 0.6, "restitution": 0.5,
        "bodies": [
          {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
          {"name": "box", "shape": {"box": [0.5, 0.5]}, "rotation": false, "position": [0, 1.5]}],
        "box2d": {"observables": [{"kind": "impact-times", "body": "box", "count": 1, "atol": 0}]}})";
    const Verb v = box2d_verb({scene.string()});
    CHECK(v.exit_code == 1);
    CHECK(v.out.find("FAILED  strict") != std::string::npos);
    CHECK(v.out.find("1 of 1 rows outside tolerance") != std::string::npos);
    CHECK(v.out.find(" NO") != std::string::npos);

    // Without observables: nothing to compare, and it passes.
    const std::filesystem::path plain = dir / "plain.json";
    std::ofstream(plain) << R"({"schema": "impulse/scene@1", "name": "plain", "dt": 0.1,
        "duration": 1, "bodies": [{"name": "a", "shape": {"circle": 0.5}}]})";
    const Verb p = box2d_verb({plain.string()});
    CHECK(p.exit_code == 0);
    CHECK(p.out.find("no observables declared") != std::string::npos);
    std::filesystem::remove_all(dir);
}

#else

TEST_CASE("box2d verb: a build without Box2D says so and exits 2", "[observables]") {
    const Verb v = box2d_verb({});
    CHECK(v.exit_code == 2);
    CHECK(v.err.find("no Box2D") != std::string::npos);
}

#endif
