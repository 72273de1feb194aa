// `impulse check --json`: the gate's results as one JSON document,
// impulse/check@1 (docs/formats.md, "The check results"), for scripts and
// CI. Its numbers are the terminal's (the first divergence of
// first_divergence.h, the differences of scaled_difference.h), written
// exactly (exact_json.h).
#pragma once

#include "engine_comparison.h"
#include "scene_check.h"

#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

inline constexpr const char* check_schema = "impulse/check@1";

// What the document says besides the scenes' checks.
struct CheckRun {
    bool tolerance_mode = false;
    bool ci = false;
    // The engine of a check whose SceneCheck carries none (a project with
    // one engine).
    std::string engine;
    std::optional<std::string> shard;     // "K/N" when --shard was given
    std::vector<std::string> shard_notes; // when the shard leaves out scenes given
    int exit_code = 0;
    // --compare: the reference comparison run after the gate.
    std::optional<ComparisonReport> comparison;
    // --compare could not finish (a reference failed on a scene): its sentence.
    std::string comparison_error;
};

std::string check_json(const std::vector<SceneCheck>& checks, const CheckRun& run);

// "ok", "diff", "stale", "failed" (an expectation, other settings, an
// unreferenced golden), "error" or "skipped".
const char* check_status_key(const SceneCheck& check);

} // namespace impulse::harness
