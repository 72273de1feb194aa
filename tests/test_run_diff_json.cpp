// run --json FILE (impulse/run@1) and diff --json (impulse/diff@1) through
// the real binary: the documents parse strictly, say what the terminal says,
// and bad input writes nothing.
#include "strict_json.h"
#include "support/drop_scenes.h"
#include "support/files.h"
#include "support/tool.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

using namespace impulse::harness;
using namespace impulse::test;
namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

Json parsed(const std::string& text, const std::string& what) {
    INFO(what << ": " << text);
    return parse_strict_json<Json>(text, what);
}

bool one_line(const std::string& text) {
    return !text.empty() && text.find('\n') == text.size() - 1;
}

} // namespace

TEST_CASE("run --json FILE: the run's result beside its trajectory", "[run-diff-json]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "ball.json";
    spit(scene, ball_scene("ball"));
    const fs::path out = tmp.dir / "ball.trajectory.json";
    const fs::path result = tmp.dir / "ball.run.json";
    const Outcome o = run_tool(
        {"run", scene.string(), "--out", out.string(), "--json", result.string(), "--quiet"});
    REQUIRE(o.exit_code == 1); // expectations[1] fails by construction, as without --json
    CHECK(o.out.empty());

    const Json j = parsed(slurp(result), result.string());
    const Trajectory t = read_trajectory_file(out.string(), "a trajectory");
    CHECK(j["schema"] == "impulse/run@1");
    CHECK(j["scene"] == "ball");
    CHECK(j["scene_file"] == scene.string());
    CHECK(j["engine"] == "impulse");
    CHECK(j["trajectory"] == out.string());
    // 0.5 s in steps of 0.01 s, a frame at t = 0 and after each; one landing.
    CHECK(j["steps"] == 50);
    CHECK(j["frames"] == 51);
    CHECK(j["frames"] == t.frames.size());
    CHECK(j["events"] == 1);
    CHECK(j["events"] == t.events.size());
    CHECK(j["partial"].is_null());
    CHECK(j["passed"] == false);
    const Json& e = j["expectations"];
    REQUIRE(e.size() == 2);
    CHECK(e[0]["path"] == "expectations[0]");
    CHECK(e[0]["passed"] == true);
    CHECK(e[0]["expected"] == 1.5);
    CHECK(e[0]["actual"] == 1.5);
    CHECK(e[0]["message"].is_null());
    CHECK(e[1]["passed"] == false);
    CHECK(e[1]["expected"] == 1.0);
    CHECK(e[1]["actual"] == 0.0);
    // The sentence the terminal prints after the scene's file.
    CHECK(o.err == scene.string() + ": " + e[1]["message"].get<std::string>() + "\n");

    SECTION("--json - is standard output when the trajectory has a file") {
        const Outcome s = run_tool({"run", scene.string(), "--out", out.string(), "--json", "-"});
        REQUIRE(s.exit_code == 1);
        CHECK(parsed(s.out, "standard output") == j);
    }
}

TEST_CASE("run --json of a run that stops: partial with its reason and time", "[run-diff-json]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "zeno.json";
    spit(scene, zeno_scene());
    const fs::path out = tmp.dir / "zeno.trajectory.json";
    const Outcome o = run_tool({"run", scene.string(), "--out", out.string(), "--json", "-"});
    REQUIRE(o.exit_code == 2);
    const Json j = parsed(o.out, "standard output");
    const Trajectory t = read_trajectory_file(out.string(), "a trajectory");
    REQUIRE(t.partial);
    REQUIRE(j["partial"].is_object());
    CHECK(j["partial"]["reason"] == t.partial->reason);
    CHECK(j["partial"]["t"].get<double>() == t.partial->t);
    CHECK(j["partial"]["t"].get<double>() <= zeno_end());
    CHECK(j["frames"] == t.frames.size());
    CHECK(j["expectations"].is_null());
    CHECK(j["passed"] == false);
    // The terminal's sentence is the reason.
    CHECK(o.err == scene.string() + ": " + t.partial->reason + "\n");
}

TEST_CASE("run --json: bad input is one sentence, exit 2, nothing written", "[run-diff-json]") {
    const TempDir tmp;
    // A project with a goldens folder (a harness/scenes beside it).
    const fs::path scene = tmp.dir / "harness" / "scenes" / "ball.json";
    fs::create_directories(scene.parent_path());
    fs::create_directories(tmp.dir / "goldens");
    spit(scene, ball_scene("ball"));
    const fs::path out = tmp.dir / "ball.trajectory.json";
    const std::string root = tmp.dir.string();

    SECTION("--json into goldens/") {
        const fs::path into = tmp.dir / "goldens" / "ball.json";
        const Outcome o = run_tool(
            {"run", "ball", "--root", root, "--out", out.string(), "--json", into.string()});
        CHECK(o.exit_code == 2);
        CHECK(one_line(o.err));
        CHECK(o.err.find("--json") != std::string::npos);
        CHECK(o.err.find("goldens") != std::string::npos);
        CHECK_FALSE(fs::exists(into));
        CHECK_FALSE(fs::exists(out));
    }
    SECTION("--json a folder") {
        const Outcome o = run_tool(
            {"run", "ball", "--root", root, "--out", out.string(), "--json", tmp.dir.string()});
        CHECK(o.exit_code == 2);
        CHECK(one_line(o.err));
        CHECK(o.err.find("is a directory") != std::string::npos);
        CHECK_FALSE(fs::exists(out));
    }
    SECTION("--json - with the trajectory on standard output too") {
        const Outcome o = run_tool({"run", "ball", "--root", root, "--json", "-"});
        CHECK(o.exit_code == 2);
        CHECK(one_line(o.err));
        CHECK(o.err.find("--out FILE") != std::string::npos);
        CHECK(o.out.empty());
    }
    SECTION("--json and --out the same file") {
        // The same file spelled another way.
        const std::string again = (tmp.dir / "." / out.filename()).string();
        const Outcome o =
            run_tool({"run", "ball", "--root", root, "--out", out.string(), "--json", again});
        CHECK(o.exit_code == 2);
        CHECK(one_line(o.err));
        CHECK_FALSE(fs::exists(out));
    }
    SECTION("a scene name the project does not have") {
        const fs::path json = tmp.dir / "result.json";
        const Outcome o = run_tool({"run", "no-such-scene", "--root", root, "--out", out.string(),
                                    "--json", json.string()});
        CHECK(o.exit_code == 2);
        CHECK(one_line(o.err));
        CHECK(o.err.find("named 'no-such-scene'") != std::string::npos);
        CHECK_FALSE(fs::exists(json));
        CHECK_FALSE(fs::exists(out));
    }
}

TEST_CASE("diff --json: the verdict and the terminal's first divergence", "[run-diff-json]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "ball.json";
    spit(scene, ball_scene("ball"));
    const fs::path a = tmp.dir / "a.json";
    REQUIRE(run_tool({"run", scene.string(), "--out", a.string()}).exit_code == 1);
    // b: a with the ball 1 mm higher at frame 10, and nothing else changed.
    Trajectory changed = read_trajectory_file(a.string(), "a trajectory");
    std::size_t y = 0;
    for (std::size_t i = 0; i < changed.columns.size(); ++i) {
        y = changed.columns[i] == "ball.y" ? i : y;
    }
    REQUIRE(y != 0);
    const double golden = changed.frames[10][y];
    changed.frames[10][y] = golden + 1e-3;
    const double moved = changed.frames[10][y];
    const fs::path b = tmp.dir / "b.json";
    spit(b, write_trajectory(changed));

    SECTION("differs: exit 1 as the text, the same first divergence") {
        const Outcome text = run_tool({"diff", a.string(), b.string()});
        const Outcome json = run_tool({"diff", a.string(), b.string(), "--json"});
        REQUIRE(text.exit_code == 1);
        REQUIRE(json.exit_code == 1);
        const Json j = parsed(json.out, "standard output");
        CHECK(j["schema"] == "impulse/diff@1");
        CHECK(j["verdict"] == "differs");
        CHECK(j["passed"] == false);
        CHECK(j["mode"] == "exact");
        CHECK(j["same_scene"] == true);
        const Json& first = j["first_divergence"];
        CHECK(first["column"] == "ball.y");
        CHECK(first["channel"] == "position");
        CHECK(first["frame"] == 10);
        CHECK(first["t"].get<double>() == changed.frames[10][0]);
        CHECK(first["golden"].get<double>() == golden);
        CHECK(first["new"].get<double>() == moved);
        CHECK(first["abs"].get<double>() == std::abs(moved - golden));
        // The terminal's line, word for word.
        const std::string line = j["first_divergence_line"];
        CHECK(text.out.find("\n" + line + "\n") != std::string::npos);
        REQUIRE(j["columns"].size() == 1);
        CHECK(j["channels"]["position"]["differing"] == 1);
        CHECK(j["channels"]["velocity"]["differing"] == 0);
    }
    SECTION("identical: exit 0, no divergence") {
        const Outcome json = run_tool({"diff", a.string(), a.string(), "--json"});
        REQUIRE(json.exit_code == 0);
        const Json j = parsed(json.out, "standard output");
        CHECK(j["verdict"] == "identical");
        CHECK(j["first_divergence"].is_null());
        CHECK(j["columns"].empty());
    }
    SECTION("within tolerance: exit 0, the divergence still reported") {
        const Outcome json =
            run_tool({"diff", a.string(), b.string(), "--json", "--tolerance", "--atol", "0.01"});
        REQUIRE(json.exit_code == 0);
        const Json j = parsed(json.out, "standard output");
        CHECK(j["verdict"] == "within tolerance");
        CHECK(j["mode"] == "tolerance");
        // How close it came, as the text's per-channel maxima.
        CHECK(j["channels"]["position"]["max_abs"].get<double>() == std::abs(moved - golden));
        CHECK(j["first_divergence_line"].is_null());
    }
    SECTION("a file that is not a trajectory: one sentence, exit 2, no JSON") {
        const Outcome json = run_tool({"diff", a.string(), scene.string(), "--json"});
        CHECK(json.exit_code == 2);
        CHECK(one_line(json.err));
        CHECK(json.err.find(scene.string()) != std::string::npos);
        CHECK(json.out.empty());
    }
}
