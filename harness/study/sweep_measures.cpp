#include "sweep_measures.h"

#include "exact_answers.h"
#include "expectations.h"
#include "sweep.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

bool is_pile_scene(const Scene& scene) {
    bool dense = false;
    for (const Expectation& x : scene.expectations) {
        switch (x.kind) {
        case Expectation::Kind::drop:
        case Expectation::Kind::corner_impact:
        case Expectation::Kind::head_on:
            return false;
        case Expectation::Kind::max_overlap:
        case Expectation::Kind::at_rest:
        case Expectation::Kind::energy_non_increasing:
            dense = true;
            break;
        default:
            break;
        }
    }
    return dense;
}

double deepest_overlap_over_run(const Scene& scene, const Trajectory& trajectory) {
    // The max-overlap expectation's own measurement, with nothing allowed to
    // fail but a pose that is not finite.
    Scene probe = scene;
    probe.expectations.clear();
    Expectation x;
    x.kind = Expectation::Kind::max_overlap;
    x.atol = std::numeric_limits<double>::max();
    probe.expectations.push_back(x);
    const std::vector<ExpectationResult> results = evaluate_expectations(probe, trajectory);
    if (results.empty() || !results.front().passed) {
        return std::numeric_limits<double>::infinity();
    }
    return std::max(0.0, results.front().actual); // never -0 (touching is depth 0)
}

double energy_gain_over_run(const Scene& scene, const Trajectory& trajectory) {
    std::string missing;
    const std::optional<std::vector<Mass>> masses = masses_of(scene, trajectory, missing);
    if (!masses || trajectory.frames.empty()) {
        return std::numeric_limits<double>::infinity();
    }
    const Totals initial = totals_in(trajectory.frames.front(), *masses, scene.gravity);
    double lowest = initial.energy;
    double gain = 0.0;
    for (const std::vector<double>& frame : trajectory.frames) {
        const double energy = totals_in(frame, *masses, scene.gravity).energy;
        if (!std::isfinite(energy)) {
            return std::numeric_limits<double>::infinity();
        }
        lowest = std::min(lowest, energy);
        gain = std::max(gain, energy - lowest);
    }
    return gain / std::max(initial.energy_scale, std::numeric_limits<double>::min());
}

namespace {

bool is_exact_kind(Expectation::Kind kind) {
    return kind == Expectation::Kind::drop || kind == Expectation::Kind::corner_impact ||
           kind == Expectation::Kind::head_on;
}

double relative_error(double actual, double expected) {
    const double off = std::abs(actual - expected);
    if (!std::isfinite(off)) {
        return std::numeric_limits<double>::infinity();
    }
    return off / std::max(std::abs(expected), sweep_error_floor);
}

} // namespace

// The largest relative error over the exact-answer expectations.
double error_against_exact(const Scene& exact_only, const Trajectory& trajectory) {
    double worst = 0.0;
    for (const ExpectationResult& r : evaluate_expectations(exact_only, trajectory)) {
        // A check without numbers (a missing impact) has nothing to measure:
        // the run failed to produce the answer at all.
        if (!r.passed && r.expected == 0.0 && r.actual == 0.0) {
            return std::numeric_limits<double>::infinity();
        }
        worst = std::max(worst, relative_error(r.actual, r.expected));
    }
    return worst;
}

// The largest relative difference of the final frame's positions, angles and
// velocities (every column but t).
double error_against_reference(const Trajectory& reference, const Trajectory& trajectory) {
    if (trajectory.frames.empty() || reference.frames.empty()) {
        return std::numeric_limits<double>::infinity();
    }
    const std::vector<double>& a = trajectory.frames.back();
    const std::vector<double>& r = reference.frames.back();
    double worst = 0.0;
    for (std::size_t i = 1; i < a.size() && i < r.size(); ++i) {
        worst = std::max(worst, relative_error(a[i], r[i]));
    }
    return worst;
}

// The scene with only its exact-answer expectations: what the error is
// measured against when it declares any.
Scene with_exact_expectations_only(const Scene& scene) {
    Scene exact_only = scene;
    exact_only.expectations.clear();
    for (const Expectation& x : scene.expectations) {
        if (is_exact_kind(x.kind)) {
            exact_only.expectations.push_back(x);
        }
    }
    return exact_only;
}

} // namespace impulse::harness
