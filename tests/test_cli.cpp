// The `impulse` tool as a user runs it: exit codes, messages, output files.
#include "atomic_file.h"
#include "support/files.h"
#include "support/tool.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

// Runs the built tool with arguments (already shell-quoted where needed).
Outcome impulse_tool(const std::string& arguments) {
    const TempDir capture;
    const fs::path out = capture.dir / "stdout", err = capture.dir / "stderr";
    const std::string command = std::string(IMPULSE_BINARY) + " " + arguments + " > " +
                                out.string() + " 2> " + err.string();
    return outcome_of(std::system(command.c_str()), out, err);
}

std::string scene_path(const std::string& name) {
    return std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes/" + name + ".json";
}

fs::path temp_file(const std::string& name, const std::string& content) {
    const fs::path path = fs::temp_directory_path() / name;
    std::ofstream(path) << content;
    return path;
}

} // namespace

TEST_CASE("The tool answers --version and --help with exit 0", "[cli]") {
    const Outcome version = impulse_tool("--version");
    CHECK(version.exit_code == 0);
    CHECK(version.out.rfind("impulse ", 0) == 0);
    const Outcome help = impulse_tool("--help");
    CHECK(help.exit_code == 0);
    CHECK(help.out.find("run SCENE") != std::string::npos);
    const Outcome run_help = impulse_tool("run --help");
    CHECK(run_help.exit_code == 0);
    CHECK(run_help.out.find("--toi-tolerance") != std::string::npos);
}

TEST_CASE("A bad scene gives exit 2, one sentence with file and JSON path, no output", "[cli]") {
    const fs::path bad =
        temp_file("impulse-cli-bad-mass.json",
                  R"({"schema": "impulse/scene@1", "name": "bad", "dt": 0.01, "duration": 1,
            "bodies": [{"name": "ground", "static": true, "shape": {"box": [5, 0.5]}},
                       {"name": "box", "shape": {"box": [0.5, 0.5]}, "mass": -1,
                        "position": [0, 3]}]})");
    const fs::path out = fs::temp_directory_path() / "impulse-cli-bad-mass.out.json";
    fs::remove(out);
    const Outcome o = impulse_tool("run " + bad.string() + " --out " + out.string());
    CHECK(o.exit_code == 2);
    CHECK(o.err == bad.string() + ": bodies[1].mass: must be > 0, got -1\n");
    CHECK(o.out.empty());
    CHECK_FALSE(fs::exists(out));
    fs::remove(bad);
}

TEST_CASE("Bad options and missing files give exit 2 and name the problem", "[cli]") {
    const std::string drop = scene_path("drop-box");
    CHECK(impulse_tool("run " + drop + " --dt -1").exit_code == 2);
    CHECK(impulse_tool("run " + drop + " --dt abc").err.find("--dt") != std::string::npos);
    CHECK(impulse_tool("run " + drop + " --integrator leapfrog").exit_code == 2);
    CHECK(impulse_tool("run " + drop + " --frobnicate").exit_code == 2);
    CHECK(impulse_tool("run").exit_code == 2);
    CHECK(impulse_tool("teleport").exit_code == 2);
    const Outcome missing = impulse_tool("run /nonexistent/scene.json");
    CHECK(missing.exit_code == 2);
    CHECK(missing.err.find("/nonexistent/scene.json: cannot be read") == 0);
    const Outcome unwritable = impulse_tool("run " + drop + " --out /nonexistent/dir/x.json");
    CHECK(unwritable.exit_code == 2);
    CHECK(unwritable.err.find("/nonexistent/dir/x.json") == 0);
}

TEST_CASE("run writes a trajectory that reads back bit for bit", "[cli]") {
    for (const char* name : {"drop-box", "spin", "glancing"}) {
        const fs::path out =
            fs::temp_directory_path() / (std::string("impulse-cli-") + name + ".json");
        const Outcome o = impulse_tool("run " + scene_path(name) + " --out " + out.string());
        INFO(name << ": " << o.err);
        REQUIRE(o.exit_code == 0);
        const std::string text = slurp(out);
        const impulse::harness::Trajectory t = impulse::harness::read_trajectory(text, out);
        CHECK(t.scene == name);
        CHECK(impulse::harness::write_trajectory(t) == text);
        // Same scene, same bits: a second run writes identical bytes.
        CHECK(impulse_tool("run " + scene_path(name)).out == text);
        fs::remove(out);
    }
}

TEST_CASE("Overrides change the physics and are recorded", "[cli]") {
    const Outcome o = impulse_tool("run " + scene_path("drop-box") + " --dt 0.01 --integrator rk4");
    REQUIRE(o.exit_code == 0);
    const impulse::harness::Trajectory t = impulse::harness::read_trajectory(o.out, "stdout");
    bool recorded = false;
    for (const auto& [key, value] : t.solver) {
        if (key == "overrides") {
            recorded = value.find("dt") != std::string::npos &&
                       value.find("integrator") != std::string::npos;
        }
        if (key == "integrator") {
            CHECK(value == "\"rk4\"");
        }
        if (key == "dt") {
            CHECK(value == "0.01");
        }
    }
    CHECK(recorded);
    CHECK(t.frames.size() == 301); // 3 s at 0.01 s, plus the frame at t = 0
}

TEST_CASE("An option given twice takes its last value, as make and the compilers do", "[cli]") {
    const Outcome o = impulse_tool("run " + scene_path("drop-box") + " --dt 0.5 --dt=0.01");
    REQUIRE(o.exit_code == 0);
    const impulse::harness::Trajectory t = impulse::harness::read_trajectory(o.out, "stdout");
    CHECK(t.frames.size() == 301); // 3 s at 0.01 s, not at 0.5 s
}
