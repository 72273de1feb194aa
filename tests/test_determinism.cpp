// Determinism rule 1 (docs/design.md), the part one binary can check: the same scene
// gives the same bits run after run and on several threads at once. (Across
// compilers, -O levels, -march and aarch64: scripts/determinism-matrix.)
#include "run.h"
#include "scene.h"
#include "trajectory.h"

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace impulse::harness;

namespace {

const std::string scenes_dir = std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes/";

// Every canonical scene file, sorted by path.
std::vector<std::string> canonical_scene_paths() {
    std::vector<std::string> paths;
    for (const auto& entry : std::filesystem::directory_iterator(scenes_dir)) {
        if (entry.is_regular_file() && entry.path().extension() == ".json") {
            paths.push_back(entry.path().string());
        }
    }
    std::sort(paths.begin(), paths.end());
    return paths;
}

struct Run {
    std::string text; // the trajectory file's bytes
    std::uint64_t digest = 0;
};

Run run_once(const Scene& scene) {
    const Trajectory trajectory = run_scene(scene);
    return {write_trajectory(trajectory), digest_of(trajectory)};
}

// "" when the texts are equal, else where they first part: the line number and
// both lines (a whole trajectory is too long for a failure message).
std::string first_difference(const std::string& expected, const std::string& actual) {
    if (expected == actual) {
        return "";
    }
    std::size_t line = 1;
    std::size_t start = 0;
    const std::size_t n = std::min(expected.size(), actual.size());
    for (std::size_t i = 0; i < n && expected[i] == actual[i]; ++i) {
        if (expected[i] == '\n') {
            ++line;
            start = i + 1;
        }
    }
    const auto line_at = [start](const std::string& text) {
        return text.substr(start, text.find('\n', start) - start);
    };
    return "line " + std::to_string(line) + ": expected '" + line_at(expected) + "', got '" +
           line_at(actual) + "'";
}

// What one thread did: for each run, which scene and what came out.
struct ThreadResult {
    std::vector<std::size_t> scene_index;
    std::vector<Run> runs;
    std::string error; // what() of an exception that ended the thread early
};

} // namespace

TEST_CASE("the same scene run twice in a row gives identical bytes", "[determinism]") {
    const std::vector<std::string> paths = canonical_scene_paths();
    REQUIRE_FALSE(paths.empty());
    for (const std::string& path : paths) {
        INFO(path);
        const Scene scene = load_scene(path);
        const Run first = run_once(scene);
        const Run second = run_once(scene);
        CHECK(first.digest == second.digest);
        CHECK(first_difference(first.text, second.text).empty());
        // A scene loaded again from its file runs the same, too.
        CHECK(first_difference(first.text, run_once(load_scene(path)).text).empty());
    }
}

TEST_CASE("scenes run on several threads at once give the same bits as run one by one",
          "[determinism]") {
    const std::vector<std::string> paths = canonical_scene_paths();
    REQUIRE_FALSE(paths.empty());

    // The reference: every scene once, sequentially, on this thread.
    std::vector<Run> sequential;
    for (const std::string& path : paths) {
        sequential.push_back(run_once(load_scene(path)));
    }

    constexpr int thread_count = 6;
    constexpr int rounds = 3; // each thread runs every scene this many times
    std::vector<ThreadResult> results(thread_count);
    std::atomic<int> ready{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < thread_count; ++t) {
        threads.emplace_back([&, t] {
            ThreadResult& result = results[static_cast<std::size_t>(t)];
            try {
                // Each thread loads its own scenes and runs them in its own order.
                std::vector<Scene> scenes;
                for (const std::string& path : paths) {
                    scenes.push_back(load_scene(path));
                }
                std::vector<std::size_t> order;
                for (int r = 0; r < rounds; ++r) {
                    for (std::size_t i = 0; i < scenes.size(); ++i) {
                        order.push_back(i);
                    }
                }
                std::mt19937_64 rng(0x5eed0000u + static_cast<unsigned>(t));
                std::shuffle(order.begin(), order.end(), rng);
                // Start together, so that the runs overlap.
                ready.fetch_add(1);
                while (ready.load() < thread_count) {
                    std::this_thread::yield();
                }
                for (const std::size_t i : order) {
                    result.runs.push_back(run_once(scenes[i]));
                    result.scene_index.push_back(i);
                }
            } catch (const std::exception& e) {
                result.error = e.what();
                ready.fetch_add(thread_count); // never leave the others waiting
            }
        });
    }
    for (std::thread& thread : threads) {
        thread.join();
    }

    // Catch2's assertions are not thread-safe: everything is checked here.
    for (std::size_t t = 0; t < results.size(); ++t) {
        const ThreadResult& result = results[t];
        INFO("thread " << t);
        REQUIRE(result.error.empty());
        REQUIRE(result.runs.size() == rounds * paths.size());
        for (std::size_t k = 0; k < result.runs.size(); ++k) {
            const std::size_t i = result.scene_index[k];
            INFO(paths[i] << ", run " << k << " of this thread");
            CHECK(result.runs[k].digest == sequential[i].digest);
            CHECK(first_difference(sequential[i].text, result.runs[k].text).empty());
        }
    }
}
