// Memory that never runs away (docs/memory.md), through the real tool under
// an address-space cap (RLIMIT_AS, as `ulimit -v`): what would exceed a
// documented budget is refused up front with exit 2 and one sentence naming
// the budget and how to change it; what fits completes under the cap. Never
// a crash (exit 134), never an output half-written.
#include "memory_budget.h"
#include "support/files.h"
#include "support/tool.h"

#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

constexpr std::size_t mib = 1024 * 1024;

// The tool with `args`, the environment plus `env`, its address space capped.
Outcome capped_tool(const std::vector<std::string>& args, const std::vector<std::string>& env,
                    std::size_t cap_bytes) {
    // Under AddressSanitizer no cap: it reserves terabytes of address space.
    // A cap of 0 means none.
    ChildLimits limits;
    if (cap_bytes > 0 && !under_address_sanitizer) {
        limits.address_space_bytes = cap_bytes;
    }
    return run_tool_limited(args, limits, env);
}

// Exit 2 and one sentence naming the file and what to change.
void require_refused(const Outcome& outcome, const std::string& file, const std::string& words,
                     const std::string& variable) {
    INFO("stderr: " << outcome.err);
    REQUIRE(outcome.exited);
    CHECK(outcome.exit_code == 2);
    CHECK_THAT(outcome.err, Catch::StartsWith(file + ": "));
    CHECK_THAT(outcome.err, Catch::Contains(words));
    CHECK_THAT(outcome.err, Catch::Contains(variable));
    CHECK(outcome.err.find('\n') == outcome.err.size() - 1); // one line
}

// A trajectory of `frames` frames of 7 zeros (t and one body), in the
// writer's layout. The digest is FNV-1a 64 over the zero bytes of every
// double (docs/formats.md): a zero byte leaves the xor unchanged, so it is the
// offset basis times the prime once per byte.
std::string zero_frames(std::size_t frames) {
    std::uint64_t digest = 0xcbf29ce484222325ULL;
    for (std::size_t byte = 0; byte < frames * 7 * 8; ++byte) {
        digest *= 0x100000001b3ULL;
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(digest));
    std::string text = "{\n  \"schema\": \"impulse/trajectory@1\",\n  \"scene\": \"zeros\",\n"
                       "  \"scene_sha256\": \"" +
                       std::string(64, '0') +
                       "\",\n  \"engine\": \"impulse 0.1.0\",\n"
                       "  \"solver\": {\"integrator\": \"euler\"},\n  \"digest\": \"" +
                       hex +
                       "\",\n  \"columns\": [\"t\", \"b.x\", \"b.y\", \"b.angle\", \"b.vx\", "
                       "\"b.vy\", \"b.omega\"],\n  \"frames\": [\n";
    const std::string line = "    [0, 0, 0, 0, 0, 0, 0]";
    text.reserve(text.size() + frames * (line.size() + 2) + 32);
    for (std::size_t i = 0; i < frames; ++i) {
        text += line + (i + 1 < frames ? ",\n" : "\n");
    }
    return text + "  ],\n  \"events\": []\n}\n";
}

// A gas scene (docs/formats.md, the gas block) of `count` discs.
std::string gas_scene(const std::string& name, int count, const std::string& dt,
                      const std::string& duration, const std::string& stepping) {
    return "{\"schema\": \"impulse/scene@1\", \"name\": \"" + name +
           "\", \"gravity\": [0, 0], \"dt\": " + dt + ", \"duration\": " + duration +
           ", \"solver\": {\"stepping\": \"" + stepping +
           "\"}, \"gas\": {\"count\": " + std::to_string(count) +
           ", \"shape\": {\"circle\": 0.1}, \"mass\": 1, \"spacing\": 0.5, \"max_speed\": 5}}\n";
}

const std::string limit_variable = "IMPULSE_MAX_TRAJECTORY_MIB";

} // namespace

TEST_CASE("diff refuses up front a trajectory of zero frames that would not fit in memory",
          "[unit][memory]") {
    const TempDir dir;
    // About 12 MiB of text, under a 16 MiB limit; held in memory its
    // 3.5 million numbers (8 bytes each) and 500,000 frames (64 bytes each)
    // would take 58 MiB, more than the limit.
    const std::size_t frames = 500'000;
    const fs::path file = dir.dir / "zeros.json";
    spit(file, zero_frames(frames));
    REQUIRE(fs::file_size(file) < 16 * mib);
    const Outcome outcome =
        capped_tool({"diff", file.string(), file.string()}, {limit_variable + "=16"}, 256 * mib);
    require_refused(outcome, file.string(), "is too large to read", limit_variable);
    // Every number of the file counted: seven per frame.
    CHECK_THAT(outcome.err, Catch::Contains("(" + std::to_string(frames * 7) + " numbers)"));
    CHECK_THAT(outcome.err, Catch::Contains("more than the limit of 16 MiB"));
}

TEST_CASE("diff of a trajectory within the limit completes under a cap a tree of it would exceed",
          "[unit][memory]") {
    const TempDir dir;
    // 8 MiB of zero frames: streamed, each copy takes 8 bytes a number and a
    // frame's bookkeeping (300,000 x (7 x 8 + 40) bytes, 27 MiB), so the tool
    // needs about 70 MB of address space; the document tree of one file took
    // about 20 times its text, more than 160 MB. The cap lies between.
    const std::size_t frames = 300'000;
    const fs::path a = dir.dir / "a.json";
    const fs::path b = dir.dir / "b.json";
    spit(a, zero_frames(frames));
    spit(b, zero_frames(frames));
    const Outcome outcome =
        capped_tool({"diff", a.string(), b.string()}, {limit_variable + "=64"}, 112 * mib);
    INFO("stderr: " << outcome.err);
    REQUIRE(outcome.exited);
    CHECK(outcome.exit_code == 0);
    CHECK(outcome.out == "identical\n");
}

TEST_CASE("a 10-body gas over 10,000,000 steps is refused before it is simulated",
          "[unit][memory]") {
    const TempDir dir;
    const fs::path scene = dir.dir / "long-gas.json";
    spit(scene, gas_scene("long-gas", 10, "1e-5", "100", "local"));
    const fs::path out = dir.dir / "out.json";
    const Outcome outcome =
        capped_tool({"run", scene.string(), "--out", out.string()}, {}, 256 * mib);
    // duration / dt = 10^7 steps, so 10^7 + 1 frames of 1 + 6 x 10 numbers.
    require_refused(outcome, scene.string(), "the run would record 10000001 frames of 61 numbers",
                    limit_variable);
    CHECK_THAT(outcome.err, Catch::Contains("more than the limit of 256 MiB"));
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("bless refuses before simulating a golden that check would refuse, and writes every "
          "golden check reads",
          "[unit][memory]") {
    const TempDir dir;
    const fs::path scenes = dir.dir / "harness" / "scenes";
    fs::create_directories(scenes);
    const std::string root = dir.dir.string();
    // A drop at dt = 1e-6 for 10 s: 10^7 + 1 frames of 7 numbers, over a GiB
    // of text (the issue's 367 MB golden had fewer digits).
    const std::string ground = "{\"name\": \"ground\", \"static\": true, \"shape\": {\"box\": [50, "
                               "0.5]}, \"position\": [0, -0.5]}";
    const auto drop = [&](const std::string& name, const std::string& dt,
                          const std::string& duration) {
        spit(
            scenes / (name + ".json"),
            "{\"schema\": \"impulse/scene@1\", \"name\": \"" + name + "\", \"dt\": " + dt +
                ", \"duration\": " + duration + ", \"bodies\": [" + ground +
                ", {\"name\": \"ball\", \"shape\": {\"circle\": 0.5}, \"position\": [0, 100]}]}\n");
    };
    drop("fine", "1e-6", "10");
    const Outcome refused = capped_tool({"bless", "fine", "--root", root}, {}, 256 * mib);
    require_refused(refused, (scenes / "fine.json").string(),
                    "the run would record 10000001 frames of 7 numbers", limit_variable);
    CHECK_FALSE(fs::exists(dir.dir / "goldens" / "fine.json"));

    // Around a 1 MiB limit: a frame of 7 numbers is at most 8 + 7 x 26 = 190
    // bytes, so 5000 frames (4999 steps of 1 ms) fit and 6000 do not.
    const std::vector<std::string> env = {limit_variable + "=1"};
    for (const auto& [name, duration] : {std::pair{"fits", "4.999"}, {"over", "5.999"}}) {
        drop(name, "0.001", duration);
        const Outcome blessed = capped_tool({"bless", name, "--root", root}, env, 256 * mib);
        const Outcome checked = capped_tool({"check", name, "--root", root}, env, 256 * mib);
        INFO(name << " bless: " << blessed.out << blessed.err << " check: " << checked.out);
        REQUIRE(blessed.exited);
        REQUIRE(checked.exited);
        const bool written = fs::exists(dir.dir / "goldens" / (std::string(name) + ".json"));
        CHECK(written == (std::string(name) == "fits"));
        CHECK(blessed.exit_code == (written ? 0 : 2));
        CHECK(checked.exit_code == (written ? 0 : 2)); // 2: refused, no golden
    }
}

TEST_CASE("collision events that push the trajectory over the limit stop the run with a sentence",
          "[unit][memory]") {
    const TempDir dir;
    // A disc of radius 0.1 between two walls 0.001 m wider than it, at 10 m/s:
    // a collision every 0.001 / 10 = 1e-4 s, 10,000 in 1 s, each event up to
    // 330 bytes of text: over 3 MiB, where the 101 frames take 19 KiB.
    const fs::path scene = dir.dir / "rattle.json";
    spit(scene, "{\"schema\": \"impulse/scene@1\", \"name\": \"rattle\", \"gravity\": [0, 0], "
                "\"dt\": 0.01, \"duration\": 1, \"bodies\": ["
                "{\"name\": \"left\", \"static\": true, \"shape\": {\"box\": [0.5, 1]}, "
                "\"position\": [-0.6005, 0]},"
                "{\"name\": \"right\", \"static\": true, \"shape\": {\"box\": [0.5, 1]}, "
                "\"position\": [0.6005, 0]},"
                "{\"name\": \"disc\", \"shape\": {\"circle\": 0.1}, \"velocity\": [10, 0]}]}\n");
    const fs::path out = dir.dir / "out.json";
    const Outcome outcome = capped_tool({"run", scene.string(), "--out", out.string()},
                                        {limit_variable + "=1"}, 256 * mib);
    require_refused(outcome, scene.string(), "collision events so far", limit_variable);
    CHECK_THAT(outcome.err, Catch::Contains("the run stopped at t = "));
    // What was simulated up to the stop is written, marked partial (docs/formats.md).
    REQUIRE(fs::exists(out));
    CHECK_THAT(slurp(out), Catch::Contains("\"partial\": {\"reason\": "));
}

TEST_CASE("world stepping of a 100,000-body gas is refused before its pair list is built",
          "[unit][memory]") {
    const TempDir dir;
    const fs::path scene = dir.dir / "big-gas.json";
    spit(scene, gas_scene("big-gas", 100'000, "0.01", "0.01", "world"));
    const Outcome outcome = capped_tool({"run", scene.string()}, {}, 1024 * mib);
    // Pairs: 100,000 x 99,999 / 2 among the discs, plus 100,000 x 4 with the walls.
    const std::uint64_t pairs = 100'000ULL * 99'999ULL / 2 + 100'000ULL * 4;
    require_refused(outcome, scene.string(), std::to_string(pairs) + " pairs",
                    "IMPULSE_MAX_WORLD_PAIRS");
    CHECK_THAT(outcome.err, Catch::Contains("solver.stepping: "));
    CHECK_THAT(outcome.err, Catch::Contains("\"stepping\": \"local\""));
}

TEST_CASE("a gas of 2000 bodies in world stepping fits its budget and runs under a cap",
          "[unit][memory]") {
    const TempDir dir;
    const fs::path scene = dir.dir / "gas-2000.json";
    spit(scene, gas_scene("gas-2000", 2000, "0.01", "0.01", "world"));
    const fs::path out = dir.dir / "out.json";
    // 2,007,000 pairs of 8 bytes (16 MB) and about 3 KB a body.
    const Outcome outcome =
        capped_tool({"run", scene.string(), "--out", out.string()}, {}, 128 * mib);
    INFO("stderr: " << outcome.err);
    REQUIRE(outcome.exited);
    CHECK(outcome.exit_code == 0);
    CHECK(fs::exists(out));
}

TEST_CASE("a limit that is not a whole number of MiB is exit 2 naming the variable",
          "[unit][memory]") {
    const TempDir dir;
    const fs::path file = dir.dir / "zeros.json";
    spit(file, zero_frames(3));
    for (const char* value : {"abc", "0", "-1", "1.5", "99999999999"}) {
        const Outcome outcome = capped_tool({"diff", file.string(), file.string()},
                                            {limit_variable + "=" + std::string(value)}, 0);
        require_refused(outcome, limit_variable, "must be a whole number of MiB", limit_variable);
    }
}

TEST_CASE("the reader's count of a text: numbers, arrays and objects outside strings, and strings",
          "[unit][memory]") {
    using impulse::harness::size_of_text;
    const auto size = size_of_text(
        R"({"a": [1, -2.5e-3, 0], "b": "[1, 2, {x}]", "c": [{"d": 1e5}, [], true, null]})");
    CHECK(size.numbers == 4);
    CHECK(size.arrays == 3);
    CHECK(size.objects == 2);
    CHECK(size.strings == 5); // four keys and "[1, 2, {x}]"
}
