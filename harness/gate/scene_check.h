// The gate's result for one scene: what check_scene found, kept apart from
// its presentation (report/) so the gate never includes the code that prints it.
#pragma once

#include "compare.h"
#include "expectations.h"
#include "scene.h"
#include "trajectory.h"

#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

// The outcome of checking one scene.
struct SceneCheck {
    // skipped: the engine refused the scene's settings (unsupported); neither
    // a pass nor a failure.
    enum class Status { passed, failed, error, skipped };
    std::string name; // scene name (or file when it did not load)
    // The engine's name when the project has several (rows and JUnit names
    // carry it), else empty.
    std::string engine;
    std::string scene_file;
    std::string golden_file;
    Status status = Status::passed;
    bool stale = false;  // the golden's scene_sha256 differs from the scene's
    std::string message; // one sentence for failed / error
    // Whose an error is: the input's (a scene, a golden, an option), the
    // engine's (engine_failure.h), or the harness's own (an exception
    // nothing expected, memory). JUnit's type of the <error>.
    enum class ErrorSource { input, engine, internal };
    ErrorSource error_source = ErrorSource::input;
    std::string details;               // multi-line text: divergences, failed expectations
    std::vector<std::string> warnings; // printed to stderr; never change the status
    // The scene's own, each naming its file (a polygon recentred): printed
    // to stderr as run prints them; never change the status.
    std::vector<std::string> scene_warnings;
    std::optional<Comparison> comparison;
    std::vector<ExpectationResult> expectations;
    std::optional<Scene> scene;
    std::optional<Trajectory> gold;
    std::optional<Trajectory> value;
    double seconds = 0.0; // wall time of this scene's check
    // The project's regen command (impulse.json's "regen"): what accepts
    // a change, for summary.md.
    std::string regen;
};

} // namespace impulse::harness
