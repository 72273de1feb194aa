// `impulse diff A B --json` (cli/diff.cpp): the comparison as JSON,
// impulse/diff@1 (docs/formats.md), with the verdict and the one first
// divergence the terminal prints (first_divergence.h), so a script reads
// the same facts a person does.
#pragma once

#include "compare.h"

#include <string>

namespace impulse::harness {

inline constexpr const char* diff_schema = "impulse/diff@1";

struct DiffInput {
    std::string golden_file; // A, the reference
    std::string new_file;    // B
    bool tolerance_mode = false;
    bool same_scene = true; // equal scene_sha256
};

// "identical", "within tolerance" or "differs": the terminal's verdict.
const char* diff_verdict(const Comparison& comparison);

std::string diff_json(const DiffInput& input, const Comparison& comparison);

} // namespace impulse::harness
