// `impulse compare` (cli/compare.cpp) as a table for people, as JSON
// (impulse/engine-comparison@1) for scripts and as JUnit XML for CI: one
// column per engine (the engine under study, then each reference) beside the
// exact answer, each engine's error against it, every setting of every run.
#pragma once

#include "reference_comparison.h"
#include "reference_engines.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

inline constexpr const char* engine_comparison_schema = "impulse/engine-comparison@1";

// The one reference the scenes' box2d blocks hold tolerances for (they were
// measured on Box2D 2.4.1): its column decides pass or fail; the others are
// shown for scale and never fail a comparison.
inline constexpr const char* judged_reference = "box2d-2.4";

struct ComparisonReport {
    std::string engine;                      // the engine under study
    bool engine_is_impulse = true;           // else an engine that may have no integrators
    bool scene_integrator = false;           // --scene-integrator
    std::vector<ReferenceEngine> references; // the columns after the engine under study
    std::vector<ReferenceEngine> skipped;    // not on this machine and not asked for
    std::vector<std::string> notes;          // e.g. "box2d-2.4 left out: ..."
    std::vector<EngineComparison> scenes;
};

// The column of the judged reference in a scene, when it ran there.
std::optional<std::size_t> judged_column(const EngineComparison& c);
// Rows of the judged reference outside the scene's tolerance of the engine
// under study (0 when it did not run).
std::size_t rows_outside(const EngineComparison& c);
// Every scene within tolerance (skipped scenes, unjudged ones and those
// with no observables do not fail).
bool comparison_passed(const ComparisonReport& report);

// A scene's row in the summary, the JSON and JUnit. A scene that declares no
// observables had nothing compared: neither a pass nor a failure, and told
// apart from both so a table of "ok" rows means something was checked.
enum class SceneStatus { passed, failed, skipped, no_observables };
SceneStatus scene_status(const EngineComparison& c);
// "passed", "failed", "skipped", "no observables" (the JSON's "status").
const char* status_name(SceneStatus status);
// "2 scenes: 0 passed, 0 failed, 2 with no observables": skipped and no
// observables only when there are some (impulse compare and impulse box2d).
std::string scene_totals(std::size_t scenes, std::size_t passed, std::size_t failed,
                         std::size_t skipped, std::size_t no_observables);
// The sentence a scene with no observables is reported with.
inline constexpr const char* no_observables_sentence =
    "no observables declared: the scene has no box2d.observables, so nothing was compared";

// Per scene: each engine's settings line, then the table (exact, then each
// engine's value and its error against the exact answer); at the end one
// summary line per engine and the verdict. `summary_only`: only the lines
// after the tables (scripts/gate).
std::string comparison_text(const ComparisonReport& report, bool summary_only);
std::string comparison_json(const ComparisonReport& report);
// One testcase per scene and engine: the judged reference's fails when a row
// is outside its tolerance; a refusal or a reference not on this machine is
// <skipped>; the others pass, with their worst error in <system-out>.
std::string comparison_junit(const ComparisonReport& report);
// The same cases as one <testsuite name="impulse.compare"> element (indented
// for <testsuites>) and its counts, for a document that holds other suites
// too (`impulse check --compare`).
struct ComparisonSuite {
    std::string xml;
    std::size_t tests = 0, failures = 0, skipped = 0;
};
ComparisonSuite comparison_junit_suite(const ComparisonReport& report);
// ` tests="N" failures="N" errors="0" skipped="N"`.
std::string counts_attributes(const ComparisonSuite& suite);

// An engine's worst relative error against the exact answer over the rows
// that have a non-zero exact answer, and where.
struct WorstError {
    double relative = 0.0; // |value - exact| / |exact|
    std::string scene;
    std::string row;
};
std::optional<WorstError> worst_error(const std::vector<EngineComparison>& scenes,
                                      const std::string& engine);

} // namespace impulse::harness
