// The references a verb puts beside the engine under study (compare, conform):
// the one place that turns --with into reference engines
// (reference_engines.h), so both verbs choose them by the same rule.
#pragma once

#include "reference_engines.h"

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness::cli {

inline constexpr const char* with_option = "--with";

struct ReferenceChoice {
    std::vector<ReferenceEngine> used;    // to run, in the order asked (or the registry's)
    std::vector<ReferenceEngine> skipped; // not on this machine and not asked for
    std::vector<std::string> notes;       // a reference left out, and why
};

// Without --with: every reference on this machine, the others skipped (listed
// with the command that installs them); box2d-2.4 left out with a note when
// `box2d_off` says why ("impulse.json says \"box2d\": false"). With --with
// LIST: exactly those (comma-separated; "none" for none). A name that is not
// a reference is a UsageError; a requested reference not on this machine
// writes "impulse VERB: reference ... is not available (...); install it
// with: scripts/setup" to err and returns nullopt (exit 2).
std::optional<ReferenceChoice> chosen_references(const std::optional<std::string>& with,
                                                 const std::string& box2d_off,
                                                 const std::string& verb, std::ostream& err);

} // namespace impulse::harness::cli
