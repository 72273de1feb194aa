// impulse::protocol (harness/protocol/): the trajectory writer a C++ engine
// uses and its main(). What it writes must be what the harness reads: the
// strict golden reader (read_trajectory) accepts it, digest and all.
#include "input_error.h"
#include "protocol.h"
#include "scene.h"
#include "support/files.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

using namespace impulse::harness;
using impulse::protocol::BodyState;
using impulse::protocol::TrajectoryWriter;
using impulse::test::TempDir;

namespace {

// Two dynamic discs, a static box between them (listed first), dt 0.25 s
// over 1 s: 4 steps, 5 frames.
const std::string two_discs = R"({"schema": "impulse/scene@1", "name": "pair",
  "dt": 0.25, "duration": 1, "gravity": [0, 0],
  "bodies": [
    {"name": "wall", "static": true, "shape": {"box": [0.5, 0.5]}},
    {"name": "left", "shape": {"circle": 0.5}, "position": [-3, 0], "velocity": [1, 0]},
    {"name": "right", "shape": {"circle": 0.5}, "position": [3, 0], "angular_velocity": 2}]})";

// Free flight, computed here from the scene's initial state.
void write_free_flight(const Scene& scene, TrajectoryWriter& writer) {
    for (std::size_t k = 0; k < writer.frames_expected(); ++k) {
        const double t = static_cast<double>(k) * scene.dt;
        std::vector<BodyState> states;
        for (const SceneBody& b : scene.bodies) {
            if (!b.is_static) {
                states.push_back({b.position.x + t * b.velocity.x, b.position.y,
                                  t * b.angular_velocity, b.velocity.x, b.velocity.y,
                                  b.angular_velocity});
            }
        }
        writer.frame(states);
    }
}

// Runs engine_main in-process with argv {"engine", args...}, returning its
// exit code and what it wrote to standard error.
std::pair<int, std::string> run_main(const std::vector<std::string>& args,
                                     const impulse::protocol::Simulation& simulate) {
    std::vector<const char*> argv = {"engine"};
    for (const std::string& a : args) {
        argv.push_back(a.c_str());
    }
    std::ostringstream err;
    std::streambuf* old_err = std::cerr.rdbuf(err.rdbuf());
    const int code = impulse::protocol::engine_main(static_cast<int>(argv.size()), argv.data(),
                                                    "test-engine 1", simulate);
    std::cerr.rdbuf(old_err);
    return {code, err.str()};
}

} // namespace

TEST_CASE("The trajectory writer's text is a trajectory of the scene the golden reader accepts",
          "[protocol]") {
    const Scene scene = parse_scene(two_discs, "pair.json");
    TrajectoryWriter writer(scene, "test-engine 1.0");
    REQUIRE(writer.frames_expected() == 5);
    writer.setting("integrator", "exact");
    writer.setting("toi_tolerance", 1e-9);
    write_free_flight(scene, writer);
    TrajectoryEvent event;
    event.t = 0.5;
    event.a = "left";
    event.b = "wall";
    event.point[0] = -0.5;
    event.normal[0] = -1.0;
    event.impulse = 2.0;
    event.vn_before = -1.0;
    event.vn_after = 1.0;
    writer.event(event);

    const std::string text = writer.text();
    const Trajectory back = read_trajectory(text, "engine output");
    CHECK(back.scene == "pair");
    CHECK(back.engine == "test-engine 1.0");
    CHECK(back.columns == std::vector<std::string>{"t", "left.x", "left.y", "left.angle", "left.vx",
                                                   "left.vy", "left.omega", "right.x", "right.y",
                                                   "right.angle", "right.vx", "right.vy",
                                                   "right.omega"});
    REQUIRE(back.frames.size() == 5);
    for (std::size_t k = 0; k < 5; ++k) {
        CHECK(back.frames[k][0] == static_cast<double>(k) * 0.25); // t = k dt, not a sum
    }
    CHECK(back.frames[4][1] == -3.0 + 1.0); // left.x after 1 s at 1 m/s
    CHECK(back.frames[4][9] == 2.0);        // right.angle after 1 s at 2 rad/s
    REQUIRE(back.events.size() == 1);
    CHECK(back.events[0].a == "left");
    CHECK(back.events[0].impulse == 2.0);
    CHECK(back.solver == std::vector<std::pair<std::string, std::string>>{
                             {"integrator", "\"exact\""}, {"toi_tolerance", "1e-09"}});
    // Canonical: the harness's own writer gives the same bytes.
    CHECK(write_trajectory(back) == text);
    CHECK(text.find("\"cost\"") == std::string::npos);
}

TEST_CASE("The writer adds the protocol's cost block when the engine reports one", "[protocol]") {
    const Scene scene = parse_scene(two_discs, "pair.json");
    TrajectoryWriter writer(scene, "test-engine 1.0");
    write_free_flight(scene, writer);
    writer.cost(0.125, 4);
    const nlohmann::json parsed = nlohmann::json::parse(writer.text());
    CHECK(parsed["cost"] == nlohmann::json{{"seconds", 0.125}, {"steps", 4}});
    CHECK(parsed["frames"].size() == 5);

    writer.cost(0.5);
    CHECK(nlohmann::json::parse(writer.text())["cost"] == nlohmann::json{{"seconds", 0.5}});
    CHECK_THROWS_AS(writer.cost(-1.0), std::logic_error);
}

TEST_CASE("The writer refuses frames that could never be read back", "[protocol]") {
    const Scene scene = parse_scene(two_discs, "pair.json");
    TrajectoryWriter writer(scene, "test-engine 1.0");
    CHECK_THROWS_AS(writer.frame({BodyState{}}), std::logic_error); // two dynamic bodies
    CHECK_THROWS_WITH(writer.text(), Catch::Contains("5 frames") && Catch::Contains("0 were"));
    write_free_flight(scene, writer);
    CHECK_THROWS_WITH(writer.frame({BodyState{}, BodyState{}}), Catch::Contains("one more"));
}

TEST_CASE("The writer names the frame and column of a NaN or an infinity, and the collision of "
          "one",
          "[protocol]") {
    const Scene scene = parse_scene(two_discs, "pair.json");
    TrajectoryWriter writer(scene, "test-engine");
    writer.frame({BodyState{}, BodyState{}});
    BodyState blown{};
    blown.vy = std::numeric_limits<double>::quiet_NaN();
    // Frame 1 is at t = 0.25 s; right.vy is its eleventh column.
    CHECK_THROWS_WITH(writer.frame({BodyState{}, blown}),
                      Catch::StartsWith("frame 1 (t = 0.25 s): right.vy is NaN"));
    blown.vy = 0.0;
    blown.omega = -std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH(writer.frame({blown, BodyState{}}), Catch::Contains("left.omega is -inf"));
    TrajectoryEvent hit;
    hit.t = 0.5;
    hit.a = "left";
    hit.b = "wall";
    hit.impulse = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH(writer.event(hit),
                      Catch::Contains("'left' and 'wall' at t = 0.5 s") && Catch::Contains("inf"));
}

TEST_CASE("engine_main: exit 3 and the sentence for a refusal, 2 for a bad scene or command line, "
          "1 for a failure",
          "[protocol]") {
    const TempDir dir;
    impulse::test::spit(dir.dir / "pair.json", two_discs);
    const std::string scene = (dir.dir / "pair.json").string();

    const auto refusal = run_main({scene}, [](const Scene&, TrajectoryWriter&) {
        throw impulse::protocol::Unsupported("test-engine does not model discs");
    });
    CHECK(refusal.first == 3);
    CHECK(refusal.second == "test-engine does not model discs\n");

    const auto failure = run_main({scene}, [](const Scene&, TrajectoryWriter&) {
        throw std::runtime_error("the solver diverged");
    });
    CHECK(failure.first == 1);
    CHECK(failure.second == "test-engine 1: the solver diverged\n");

    // Frames missing: the writer's sentence, never a cut trajectory.
    const auto unfinished = run_main({scene}, [](const Scene&, TrajectoryWriter&) {});
    CHECK(unfinished.first == 1);
    CHECK_THAT(unfinished.second, Catch::Contains("5 frames"));

    impulse::test::spit(dir.dir / "bad.json", R"({"schema": "impulse/scene@1"})");
    const auto bad =
        run_main({(dir.dir / "bad.json").string()}, [](const Scene&, TrajectoryWriter&) {});
    CHECK(bad.first == 2);
    CHECK_THAT(bad.second, Catch::Contains("bad.json"));

    const auto usage = run_main({}, [](const Scene&, TrajectoryWriter&) {});
    CHECK(usage.first == 2);
    CHECK_THAT(usage.second, Catch::StartsWith("usage: engine SCENE.json"));
}
