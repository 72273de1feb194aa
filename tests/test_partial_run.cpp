// A run that stops early still writes what it simulated (docs/formats.md,
// "partial"): marked partial with the reason and the last frame's time,
// exit 2 as before, drawable by render, and never a golden.
#include "support/files.h"
#include "support/tool.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>

using namespace impulse::harness;
using namespace impulse::test;
namespace fs = std::filesystem;

namespace {

constexpr double g = 9.81;
constexpr double dt = 0.01;
constexpr double drop = 4.5; // the disc's gap above the ground, m
constexpr double e = 0.5;

// A disc dropped 4.5 m at e = 0.5 without "resting": it bounces ever lower
// and comes to rest at t_inf = t1 (1 + 2e / (1 - e)) = 3 t1 = 2.87 s, where
// t1 = sqrt(2 h / g), inside the 4 s run. Collisions alone cannot go on.
std::string zeno_scene() {
    return R"({"schema":"impulse/scene@1","name":"zeno","dt":0.01,"duration":4,)"
           R"("restitution":0.5,"solver":{"integrator":"verlet"},)"
           R"("bodies":[{"name":"ground","static":true,"shape":{"box":[5,0.5]},"position":[0,-0.5]},)"
           R"({"name":"ball","shape":{"circle":0.5},"mass":1,"position":[0,5]}]})";
}

// The time a sentence states after "at t = ", in seconds.
double stated_time(const std::string& text) {
    const std::string marker = "at t = ";
    const std::size_t at = text.find(marker);
    REQUIRE(at != std::string::npos);
    return std::stod(text.substr(at + marker.size()));
}

} // namespace

TEST_CASE("A run that stops writes a partial trajectory up to the stop", "[partial-run]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "zeno.json";
    spit(scene, zeno_scene());
    const fs::path out = tmp.dir / "out.json";
    const Outcome o = run_tool({"run", scene.string(), "--out", out.string()});
    INFO(o.out << o.err);
    REQUIRE(o.exited);
    CHECK(o.exit_code == 2);                     // a stopped run is still bad input for the scene
    CHECK(o.err.find('\n') == o.err.size() - 1); // one sentence
    REQUIRE(o.err.rfind(scene.string() + ": ", 0) == 0);

    REQUIRE(fs::exists(out));
    const Trajectory t = read_trajectory_file(out.string(), "a trajectory");
    REQUIRE(t.partial);
    // The reason is the sentence the run printed, without the file.
    CHECK(scene.string() + ": " + t.partial->reason + "\n" == o.err);
    // The last frame is the last full step before the stop.
    const double last = t.frames.back().front();
    CHECK(t.partial->t == last);
    const double stop = stated_time(o.err);
    CHECK(last <= stop);
    CHECK(stop < last + dt + 1e-12);
    const double t1 = std::sqrt(2.0 * drop / g);
    const double t_inf = t1 * (1.0 + 2.0 * e / (1.0 - e));
    CHECK(last > t1);         // it bounced before it stopped
    CHECK(last < t_inf + dt); // and stopped by the end of the cascade
    CHECK(last < 4.0);        // before the scene's duration
    CHECK(t.events.size() >= 2);
    CHECK(slurp(out).find("\"partial\": {\"reason\": ") != std::string::npos);

    SECTION("render draws it") {
        const fs::path svg = tmp.dir / "zeno.svg";
        const Outcome r =
            run_tool({"render", out.string(), "--out", svg.string(), "--root", tmp.dir.string()});
        INFO(r.out << r.err);
        CHECK(r.exit_code == 0);
        CHECK(slurp(svg).rfind("<svg", 0) != std::string::npos);
    }
    SECTION("the gate never takes it as a golden") {
        const Outcome d = run_tool({"diff", out.string(), out.string()});
        CHECK(d.exit_code == 1);
        CHECK(d.out.find("the golden is partial: it stopped at t = ") != std::string::npos);
        CHECK(d.out.find("a partial trajectory is never a golden") != std::string::npos);
    }
}

TEST_CASE("A complete run has no partial key", "[partial-run]") {
    const TempDir tmp;
    const fs::path out = tmp.dir / "drop.json";
    const Outcome o = run_tool(
        {"run", (fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes" / "drop-box.json").string(),
         "--out", out.string()});
    CHECK(o.exit_code == 0);
    CHECK(slurp(out).find("\"partial\"") == std::string::npos);
    CHECK_FALSE(read_trajectory_file(out.string(), "a trajectory").partial);
}

TEST_CASE("A bad partial marker is refused naming its path", "[partial-run]") {
    const TempDir tmp;
    const fs::path out = tmp.dir / "drop.json";
    REQUIRE(
        run_tool({"run",
                  (fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes" / "drop-box.json").string(),
                  "--out", out.string()})
            .exit_code == 0);
    std::string text = slurp(out);
    const std::size_t end = text.rfind("\n}");
    REQUIRE(end != std::string::npos);
    text.insert(end, ",\n  \"partial\": {\"reason\": \"\", \"t\": 1}");
    spit(out, text);
    const Outcome d = run_tool({"diff", out.string(), out.string()});
    CHECK(d.exit_code == 2);
    CHECK(d.err.find("partial.reason") != std::string::npos);
}
