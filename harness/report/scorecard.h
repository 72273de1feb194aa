// The conformance scorecard (`impulse conform`, docs/conformance.md) as a
// table for people, as JSON (impulse/conformance@1) for scripts, and as JUnit
// XML for CI. Each is built from the scores alone, so the same scores always
// give the same bytes.
#pragma once

#include "conformance.h"

#include <cstddef>
#include <string>
#include <vector>

namespace impulse::harness {

inline constexpr const char* conformance_schema = "impulse/conformance@1";

struct Scorecard {
    std::string engine;                  // the engine under test (scenes[i].engines[0])
    std::vector<std::string> references; // engines[1...], for scale
    std::string scenes_dir;              // where the shipped scenes were found
    std::vector<std::string> notes;      // lines for the head of the table ("no Box2D ...")
    std::vector<SceneScore> scenes;
};

// Per scene: its engines' tallies, every check with the exact value, the
// engine's value, the absolute and relative error, the allowance and whether
// it is within (the references' absolute errors beside it), the failed
// checks' sentences; then one line per scene and the totals. At most 100
// columns wide, but for long names and sentences.
std::string scorecard_text(const Scorecard& card);

// A reference's tally over every scene, scenes[i].engines[index]: "box2d-2.4:
// 130 of 150 checks within the allowance on 12 scenes it ran (10 passed, 2
// failed, 0 unsupported, 0 errors)". The text's last lines and JUnit's properties.
std::string reference_tally(const Scorecard& card, std::size_t index);

// The same, impulse/conformance@1 (docs/conformance.md, "JSON").
std::string scorecard_json(const Scorecard& card);

// JUnit XML for the engine under test: one testcase per check of each scene
// it ran (<failure> outside the allowance), one per scene it refused
// (<skipped>) or failed to run (<error>).
std::string scorecard_junit(const Scorecard& card);

} // namespace impulse::harness
