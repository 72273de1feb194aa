// The conformance suite (docs/conformance.md): which shipped scenes test
// collision response itself rather than one of this engine's solver choices,
// and an engine's score on their expectations, with reference engines beside
// it for scale.
#pragma once

#include "engine.h"
#include "expectations.h"
#include "scene.h"

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

// The solver keys that choose a collision model rather than how accurately
// one model is followed: a scene that names one declares answers that hold
// under that model.
inline constexpr const char* model_solver_keys[] = {"contacts", "vertex_normal", "resting",
                                                    "stepping"};

// The rule (docs/conformance.md, "Which scenes"): empty when the scene is a
// conformance scene, else one sentence saying why not. `solver_keys` are the
// keys its file's solver block names (a default named is still a choice:
// drop-flat names "contacts": "single" because its answer is that model's).
std::optional<std::string> conformance_exclusion(const Scene& scene,
                                                 const std::vector<std::string>& solver_keys);

struct ShippedScene {
    Scene scene;
    std::vector<std::string> solver_keys;
    std::optional<std::string> exclusion; // conformance_exclusion's verdict
};

// Every NAME.json in `dir`, sorted by name, loaded and judged by the rule.
// Throws InputError naming the file for one that does not load: a shipped
// scene that does not load is a broken installation, not a skip.
std::vector<ShippedScene> shipped_scenes(const std::string& dir);

// One engine's result on one scene.
struct EngineScore {
    enum class Outcome {
        ran,         // results hold the expectations' checks
        unsupported, // the engine refused the scene's settings (exit 3): a skip
        error        // the engine failed (crash, time-out, garbage): message says how
    };
    std::string engine; // EngineSpec::name
    Outcome outcome = Outcome::ran;
    std::string message; // unsupported: the engine's sentence; error: the harness's
    std::vector<ExpectationResult> results;
    double seconds = 0.0; // wall time of the run

    std::size_t within() const; // results that passed
    bool passed() const { return outcome == Outcome::ran && within() == results.size(); }
};

struct SceneScore {
    std::string name;
    std::string file;
    std::vector<EngineScore> engines; // in the order the engines were given
};

// Runs `scene` in each engine and evaluates its expectations on each
// trajectory. Never throws for an engine's failure: it becomes that engine's
// error outcome, so one scene's crash does not stop the others.
SceneScore score_scene(const Scene& scene, const std::vector<EngineSpec>& engines);

struct ScoringOptions {
    int jobs = 1; // scenes scored at once; results identical for any value
    // Called from the worker threads, for a progress bar only.
    std::function<void(const std::string& scene_name)> on_start;
    std::function<void()> on_done;
};

// score_scene for every scene, in the order given.
std::vector<SceneScore> score_scenes(const std::vector<Scene>& scenes,
                                     const std::vector<EngineSpec>& engines,
                                     const ScoringOptions& options);

// The engine under test's tally (engines[index] of every scene): scenes it
// passed, failed, refused or failed to run, and its checks within their
// allowance.
struct ConformanceCounts {
    std::size_t scenes = 0, passed = 0, failed = 0, unsupported = 0, errors = 0;
    std::size_t checks = 0, within = 0;
};
ConformanceCounts count_engine(const std::vector<SceneScore>& scores, std::size_t index = 0);
// The verdict: every check of every scene the engine ran is within its
// allowance, no scene failed to run, and at least one scene ran (an engine
// that refuses them all has shown nothing).
bool conforms(const ConformanceCounts& counts);

// What identifies a check across engines and runs: its `what` without what
// the run itself decides (where a conserved quantity strayed furthest, which
// component): "conserved momentum (x), furthest from t = 0 at t = 1.2 s" ->
// "conserved momentum". Rows of a scorecard and JUnit test names use it.
std::string check_key(const ExpectationResult& result);

} // namespace impulse::harness
