// The reference comparison over a list of scenes, as `impulse compare` runs it
// and `impulse check --compare` runs it after the gate: one function both
// verbs call, so the two can never compare differently.
#pragma once

#include "engine_comparison.h"
#include "reference_comparison.h"
#include "reference_engines.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

struct ComparisonRequest {
    // The engine under study, dt and the integrator; its `references` are
    // filled from `references` below.
    CompareOptions options;
    std::vector<ReferenceEngine> references; // the columns, in this order
    std::vector<ReferenceEngine> skipped;    // not on this machine and not asked for
    std::vector<std::string> notes;          // a reference left out, and why
    // Box2D v3's sub-steps per step, given to its program as --substeps N.
    std::optional<int> box2d_3_substeps;
    // For a progress bar, never for results.
    std::function<void(const std::string& scene_path)> on_start;
    std::function<void()> on_done;
};

// Every scene of `paths` run in the engine under study and each reference,
// in order; throws what compare_engines throws (a bad scene, an engine that
// failed), before anything is printed or written.
ComparisonReport run_comparison(const std::vector<std::string>& paths,
                                const ComparisonRequest& request);

} // namespace impulse::harness
