// Checking a run against the answers its scene declares.
#pragma once

#include "scene.h"
#include "trajectory.h"

#include <string>
#include <vector>

namespace impulse::harness {

struct ExpectationResult {
    std::string path; // "expectations[1]"
    std::string what; // "drop of 'box': impact 3 time", one line
    bool passed = true;
    double expected = 0.0;
    double actual = 0.0;
    std::string detail; // one sentence when it failed (or cannot be evaluated)
};

// One result per checked value (a drop expectation checks several). Works on
// any simulator's trajectory of this scene.
std::vector<ExpectationResult> evaluate_expectations(const Scene& scene,
                                                     const Trajectory& trajectory);

} // namespace impulse::harness
