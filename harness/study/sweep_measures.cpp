#include "sweep_measures.h"

#include "exact_answers.h"
#include "expectations.h"

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

} // namespace impulse::harness
