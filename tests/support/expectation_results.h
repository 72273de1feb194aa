// Expectations evaluated on a trajectory and what their results say, for the
// expectation tests (test_expectations*.cpp, test_momentum_balance.cpp).
#pragma once

#include "expectations.h"
#include "scene.h"
#include "scene_text.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

namespace impulse::test {

using impulse::harness::ExpectationResult;
using impulse::harness::Trajectory;

// How many results failed.
inline int failures(const std::vector<ExpectationResult>& results) {
    int n = 0;
    for (const ExpectationResult& r : results) {
        n += r.passed ? 0 : 1;
    }
    return n;
}

// Every result, one per line, for INFO.
inline std::string listing(const std::vector<ExpectationResult>& results) {
    std::string out;
    for (const ExpectationResult& r : results) {
        out += (r.passed ? "  pass " : "  FAIL ") + r.path + " " + r.what + " (" + r.detail + ")\n";
    }
    return out;
}

// The one result whose `what` contains `text`.
inline const ExpectationResult& result_about(const std::vector<ExpectationResult>& results,
                                             const std::string& text) {
    const ExpectationResult* found = nullptr;
    for (const ExpectationResult& r : results) {
        if (r.what.find(text) != std::string::npos) {
            REQUIRE(found == nullptr);
            found = &r;
        }
    }
    INFO("no result about '" << text << "' in\n" << listing(results));
    REQUIRE(found != nullptr);
    return *found;
}

// Only the result about `text` fails.
inline void require_only_failure(const std::vector<ExpectationResult>& results,
                                 const std::string& text) {
    INFO(listing(results));
    CHECK(failures(results) == 1);
    CHECK_FALSE(result_about(results, text).passed);
    CHECK_FALSE(result_about(results, text).detail.empty());
}

// The scene text with its expectations replaced by `expectations` (a JSON array).
inline std::string with_expectations(const std::string& scene, const std::string& expectations) {
    return scene.substr(0, scene.rfind('}')) + R"(, "expectations": )" + expectations + "}";
}

// The results of `expectations` in `scene` (loaded as test_file) on a trajectory.
inline std::vector<ExpectationResult>
evaluate(const std::string& scene, const std::string& expectations, const Trajectory& trajectory) {
    return impulse::harness::evaluate_expectations(
        impulse::harness::parse_scene(with_expectations(scene, expectations), test_file),
        trajectory);
}

} // namespace impulse::test
