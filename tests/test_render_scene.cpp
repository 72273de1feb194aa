// impulse render through the real binary: a scene by name, a trajectory's
// scene found (--scene, --root, or the project the trajectory lies in) only
// when its scene_sha256 matches, the stop of a partial run marked, and the
// times on key frames and contact marks.
#include "support/drop_scenes.h"
#include "support/files.h"
#include "support/tool.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

using namespace impulse::harness;
using namespace impulse::test;
namespace fs = std::filesystem;

namespace {

const std::string source_root = IMPULSE_SOURCE_DIR;
// The static body's outline, as a reader of the SVG finds it.
const std::string floor_mark = "class=\"static\" data-body=\"floor\"";

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
        ++n;
    }
    return n;
}

bool one_line(const std::string& text) {
    return !text.empty() && text.find('\n') == text.size() - 1;
}

// An implicit project (ROOT/harness/scenes) holding the ball scene, and its
// run recorded into a folder outside the project.
struct Recorded {
    TempDir tmp;
    fs::path project = tmp.dir / "project";
    fs::path scene = project / "harness" / "scenes" / "lookup-ball.json";
    fs::path outside = tmp.dir / "elsewhere";
    fs::path trajectory = outside / "run.json";

    Recorded() {
        fs::create_directories(scene.parent_path());
        fs::create_directories(outside);
        spit(scene, ball_scene("lookup-ball"));
        const Outcome o = run_tool(
            {"run", "lookup-ball", "--root", project.string(), "--out", trajectory.string()});
        INFO(o.err);
        REQUIRE(o.exit_code == 1); // expectations[1] fails by construction
        REQUIRE(fs::is_regular_file(trajectory));
    }
};

} // namespace

TEST_CASE("render takes a project scene's name, as run and check do", "[render-scene]") {
    const TempDir tmp;
    const fs::path svg = tmp.dir / "drop-box.svg";
    const Outcome o =
        run_tool({"render", "drop-box", "--root", source_root, "--out", svg.string(), "--quiet"});
    INFO(o.err);
    REQUIRE(o.exit_code == 0);
    const std::string text = slurp(svg);
    CHECK(text.find("class=\"static\" data-body=\"ground\"") != std::string::npos);
    CHECK(text.find("data-body=\"box\"") != std::string::npos);

    // A name no scene has: one sentence naming the name and the scenes, nothing written.
    const fs::path none = tmp.dir / "none.svg";
    const Outcome bad =
        run_tool({"render", "no-such-scene", "--root", source_root, "--out", none.string()});
    CHECK(bad.exit_code == 2);
    CHECK(one_line(bad.err));
    CHECK(bad.err.find("is named 'no-such-scene'") != std::string::npos);
    CHECK_FALSE(fs::exists(none));
}

TEST_CASE("render finds a trajectory's static bodies outside the repository", "[render-scene]") {
    const Recorded r;
    const fs::path svg = r.tmp.dir / "picture.svg";

    SECTION("--scene FILE") {
        const Outcome o = run_tool(
            {"render", r.trajectory.string(), "--scene", r.scene.string(), "--out", svg.string()});
        INFO(o.err);
        REQUIRE(o.exit_code == 0);
        CHECK(o.err.empty());
        CHECK(slurp(svg).find(floor_mark) != std::string::npos);
    }
    SECTION("--scene NAME with --root") {
        const Outcome o = run_tool({"render", r.trajectory.string(), "--scene", "lookup-ball",
                                    "--root", r.project.string(), "--out", svg.string()});
        INFO(o.err);
        REQUIRE(o.exit_code == 0);
        CHECK(slurp(svg).find(floor_mark) != std::string::npos);
    }
    SECTION("--root alone: the scene of the trajectory's name") {
        const Outcome o = run_tool(
            {"render", r.trajectory.string(), "--root", r.project.string(), "--out", svg.string()});
        INFO(o.err);
        REQUIRE(o.exit_code == 0);
        CHECK(o.err.empty());
        CHECK(slurp(svg).find(floor_mark) != std::string::npos);
    }
    SECTION("no option: the project the trajectory lies in") {
        // The current folder's project (this repository) has no such scene.
        const fs::path inside = r.project / "runs" / "run.json";
        fs::create_directories(inside.parent_path());
        fs::copy_file(r.trajectory, inside);
        const Outcome o = run_tool({"render", inside.string(), "--out", svg.string()});
        INFO(o.err);
        REQUIRE(o.exit_code == 0);
        CHECK(o.err.empty());
        CHECK(slurp(svg).find(floor_mark) != std::string::npos);
    }
    SECTION("no option and no project around it: paths only, saying why") {
        const Outcome o = run_tool({"render", r.trajectory.string(), "--out", svg.string()});
        REQUIRE(o.exit_code == 0);
        CHECK(one_line(o.err));
        CHECK(o.err.rfind("note: ", 0) == 0);
        CHECK(o.err.find("does not exist") != std::string::npos);
        CHECK(o.err.find("--scene") != std::string::npos);
        const std::string text = slurp(svg);
        CHECK(text.find(floor_mark) == std::string::npos);
        CHECK(text.find("data-body=\"ball\"") != std::string::npos);
    }
}

TEST_CASE("render refuses a scene whose sha256 is not the trajectory's", "[render-scene]") {
    const Recorded r;
    // The scene changes after the run: another restitution.
    spit(r.scene, ball_scene("lookup-ball", 0.9));
    const fs::path svg = r.tmp.dir / "picture.svg";

    SECTION("given with --scene: refused, exit 2, nothing written") {
        const Outcome o = run_tool(
            {"render", r.trajectory.string(), "--scene", r.scene.string(), "--out", svg.string()});
        CHECK(o.exit_code == 2);
        CHECK(one_line(o.err));
        CHECK(o.err.find("--scene") != std::string::npos);
        CHECK(o.err.find(r.scene.string() + " has changed") != std::string::npos);
        CHECK(o.err.find("scene_sha256") != std::string::npos);
        CHECK_FALSE(fs::exists(svg));
    }
    SECTION("found by name: not used, the reason noted, paths drawn") {
        const Outcome o = run_tool(
            {"render", r.trajectory.string(), "--root", r.project.string(), "--out", svg.string()});
        REQUIRE(o.exit_code == 0);
        CHECK(o.err.find("has changed") != std::string::npos);
        CHECK(slurp(svg).find(floor_mark) == std::string::npos);
    }
}

TEST_CASE("render marks where a partial trajectory stopped", "[render-scene]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "zeno.json";
    const fs::path run = tmp.dir / "zeno.trajectory.json";
    const fs::path svg = tmp.dir / "zeno.svg";
    spit(scene, zeno_scene());
    REQUIRE(run_tool({"run", scene.string(), "--out", run.string()}).exit_code == 2);
    const Trajectory t = read_trajectory_file(run.string(), "a trajectory");
    REQUIRE(t.partial);
    // Just before the bounces would end (within the last few steps).
    CHECK(t.partial->t <= zeno_end());
    CHECK(t.partial->t > zeno_end() - 0.05);

    const Outcome o =
        run_tool({"render", run.string(), "--scene", scene.string(), "--out", svg.string()});
    INFO(o.err);
    REQUIRE(o.exit_code == 0);
    const std::string text = slurp(svg);
    // One mark, at the last frame, around the one dynamic body.
    CHECK(count(text, "<g class=\"stop\"") == 1);
    const std::string frame = "data-frame=\"" + std::to_string(t.frames.size() - 1) + "\"";
    CHECK(text.find("<g class=\"stop\" data-t=\"") != std::string::npos);
    CHECK(text.find(frame + "><title>") != std::string::npos);
    CHECK(count(text, "<circle data-body=\"ball\"") == 1);
    const std::size_t at = text.find("<g class=\"stop\" data-t=\"") + 24;
    CHECK(std::stod(text.substr(at)) == Approx(t.partial->t).epsilon(1e-6));
    // The time and the reason in the title, the mark in the legend.
    CHECK(text.find("Stopped early at t = ") != std::string::npos);
    CHECK(text.find("Zeno cascade") != std::string::npos);
    CHECK(text.find(">where the run stopped</text>") != std::string::npos);
}

TEST_CASE("render labels key frames and contact marks with their times", "[render-scene]") {
    const Recorded r;
    const fs::path svg = r.tmp.dir / "picture.svg";
    REQUIRE(run_tool({"render", r.trajectory.string(), "--scene", r.scene.string(), "--out",
                      svg.string()})
                .exit_code == 0);
    const std::string text = slurp(svg);
    const Trajectory t = read_trajectory_file(r.trajectory.string(), "a trajectory");
    REQUIRE(t.events.size() == 1); // the landing at sqrt(2 / g)
    // The first and last of the 8 key frames are labelled (labels that would
    // overlap an earlier one are left out), and the one contact.
    const std::size_t labels = count(text, "class=\"time\"");
    CHECK(labels >= 3);
    CHECK(labels <= 8 + 1);
    CHECK(text.find(">t = 0 s</text>") != std::string::npos);
    CHECK(text.find(">t = 0.5 s</text>") != std::string::npos);
    // Within a step of the landing at sqrt(2 / g); the mark's tooltip says when.
    CHECK(std::abs(t.events[0].t - std::sqrt(2.0 / drop_g)) < 0.01);
    const std::string tip = "<circle class=\"contact\"";
    const std::size_t mark = text.find(tip);
    REQUIRE(mark != std::string::npos);
    const std::size_t title = text.find("<title>t = ", mark);
    REQUIRE(title != std::string::npos);
    CHECK(text.find("</circle>", mark) > title);
    CHECK(std::stod(text.substr(title + 11)) == Approx(t.events[0].t).epsilon(1e-5));
}
