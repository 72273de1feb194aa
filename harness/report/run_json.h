// `impulse run SCENE --json FILE` (cli/run.cpp): the run's result as JSON,
// impulse/run@1 (docs/formats.md): what ran, how far it got, and each
// declared expectation with the sentence the terminal prints for it.
#pragma once

#include "expectations.h"
#include "scene.h"
#include "trajectory.h"

#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

inline constexpr const char* run_schema = "impulse/run@1";

struct RunResult {
    const Scene* scene = nullptr;
    const Trajectory* trajectory = nullptr;
    std::string engine_name;                    // the engine spec's: "impulse", "box2d", ...
    std::optional<std::string> trajectory_file; // --out FILE; empty for standard output
    // Empty when they were not checked (a run that stopped early).
    std::optional<std::vector<ExpectationResult>> expectations;
};

// "expectations[1]: drop of 'box': impact 3 time: expected 0.45, got 0.46
// (...)": what run prints after the scene's file for a failed expectation.
std::string expectation_message(const ExpectationResult& result);

std::string run_json(const RunResult& result);

} // namespace impulse::harness
