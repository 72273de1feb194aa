// Checking a run against the answers its scene declares.
#pragma once

#include "scene.h"
#include "trajectory.h"

#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

struct ExpectationResult {
    std::string path; // "expectations[1]"
    std::string what; // "drop of 'box': impact 3 time", one line
    bool passed = true;
    double expected = 0.0;
    double actual = 0.0;
    // false when expected or actual was not finite: they hold 0 then, and a
    // message shows the detail alone rather than "expected 0, got 0" beside
    // the inf it is about.
    bool numeric = true;
    // The allowance |actual - expected| was judged against (atol + rtol x
    // scale; one-sided for energy-non-increasing), for a scorecard that shows
    // it; empty for a name compared as a string and for a check that failed
    // without a number (a missing event or frame).
    std::optional<double> allowed;
    std::string detail; // one sentence when it failed (or cannot be evaluated)
};

// One result per checked value (a drop expectation checks several). Works on
// any simulator's trajectory of this scene.
std::vector<ExpectationResult> evaluate_expectations(const Scene& scene,
                                                     const Trajectory& trajectory);

} // namespace impulse::harness
