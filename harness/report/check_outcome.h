// A scene's check in words, shared by the gate's reports (JUnit, summary.md,
// index.html) so that each says the same thing the same way.
#pragma once

#include "scene_check.h"

#include <cstddef>
#include <string>
#include <vector>

namespace impulse::harness {

struct CheckCounts {
    std::size_t passed = 0, failed = 0, errors = 0, skipped = 0;
    double seconds = 0.0;
};

CheckCounts count_checks(const std::vector<SceneCheck>& checks);

// Seconds with three decimals: "0.012"; an unmeasured or negative time is 0.
std::string seconds_text(double s);
// "3 scenes: 2 passed, 1 failed, 0 errors" (", 1 skipped" when one was).
std::string verdict_counts(const CheckCounts& c);
const char* status_word(SceneCheck::Status status);
// "ENGINE/NAME" when the project has several engines; the scene's name,
// else its file, else "(unnamed)".
std::string display_name(const SceneCheck& check);
// Why a scene failed, in two or three words (JUnit's failure type).
std::string failure_kind(const SceneCheck& check);
// Whose an error is, in two words (JUnit's error type): "input error",
// "engine error" or "internal error".
std::string error_kind(const SceneCheck& check);
// The one-line description of a scene's outcome for tables: the first
// divergence of a failed comparison, else the message, else a verdict.
std::string outcome_line(const SceneCheck& check);

} // namespace impulse::harness
