// The references' logic (impulse box2d, impulse compare): one scene run in the
// engine under study (the impulse engine unless told otherwise: any engine
// behind run_engine, engine.h) and in reference engines (reference_engines.h),
// the observables its "box2d" block names compared (observables.h), computed
// from the trajectories. The verbs (cli/box2d.cpp, cli/compare.cpp) parse and
// print.
#pragma once

#include "engine.h"
#include "observables.h"
#include "scene.h"
#include "trajectory.h"

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness {

// The command line's choices for both runs; unset means the scene's own.
struct ReferenceOptions {
    EngineSpec engine = impulse_engine(); // the engine compared with Box2D
    std::optional<double> dt;
    std::optional<int> substeps, velocity_iterations, position_iterations;
    // The engine under study runs with the scene's own integrator instead of
    // symplectic-euler (Box2D's); another engine is asked for it through the
    // scene's solver.integrator, which it may ignore or refuse.
    bool scene_integrator = false;
};

// One scene compared: everything both outputs show.
struct ReferenceComparison {
    std::string name;
    std::string file;
    std::string engine = "impulse"; // the engine under study's name
    // Not empty when that engine refused the scene's settings (exit 3):
    // "unsupported by ENGINE: ...", a skip with no rows (neither pass nor fail).
    std::string skipped;
    double dt = 0.0;
    std::string integrator;       // the engine under study's run's
    std::string scene_integrator; // the scene's own
    Box2dSettings box2d;          // as run, observables included
    std::string impulse_engine;
    std::string box2d_engine;
    std::vector<std::string> warnings;
    std::string stopped; // why and where the comparison ends early, when it does
    std::vector<ObservableRow> rows;
    // Both runs, as compared, for --out (so impulse diff and render work on them).
    std::optional<Trajectory> impulse_run;
    std::optional<Trajectory> box2d_run;

    std::size_t outside() const {
        return static_cast<std::size_t>(std::count_if(
            rows.begin(), rows.end(), [](const ObservableRow& r) { return !r.within; }));
    }
    bool passed() const { return outside() == 0; }
};

// compare_with_box2d for any set of references (impulse compare).
struct CompareOptions {
    EngineSpec engine = impulse_engine(); // the engine under study
    std::vector<EngineSpec> references;   // its columns, in this order
    std::optional<double> dt;             // every run's step; unset: the scene's
    // As ReferenceOptions: the engine under study runs with symplectic-euler
    // unless this is set; the references always run with their own integrators.
    bool scene_integrator = false;
};

// One engine's run of one scene: its column.
struct EngineColumn {
    std::string name;        // the spec's: "impulse", "box2d-2.4", "box2d-3"
    std::string engine;      // the trajectory's engine: "box2d 2.4.1"
    std::string unsupported; // not empty: the engine refused the scene (exit 3), its sentence
    std::vector<std::pair<std::string, std::string>> settings; // its solver block, every setting
    std::vector<std::string> command;                          // external: what ran, scene appended
    std::optional<Trajectory> run; // as compared (cut where the engine under study stopped)
};

struct EngineComparison {
    std::string name;
    std::string file;
    double dt = 0.0;
    std::string scene_integrator;
    std::vector<std::string> warnings;
    std::string stopped; // why and where the comparison ends early, when it does
    // [0] the engine under study, then the references in the order asked.
    // When [0] refused the scene it is the only one and there are no rows.
    std::vector<EngineColumn> engines;
    // values[i] is engines[i]'s, nullopt for an engine that refused the scene.
    std::vector<ObservableReadings> rows;

    // The scene names no observables: no engine was run.
    bool nothing_declared() const { return engines.empty(); }
    // The engine under study refused the scene: nothing else was run.
    bool skipped() const { return !engines.empty() && !engines.front().unsupported.empty(); }
};

// Loads the scene and runs it in every engine. A reference that refuses the
// scene (exit 3, or a shape a built-in reference cannot take) is an
// "unsupported" column, not a failure; the engine under study refusing it
// skips the scene. Throws InputError for a broken scene, a scene that would
// tunnel unseen in the impulse engine, and an engine that fails (run_engine).
EngineComparison compare_engines(const std::string& path, const CompareOptions& options);

// Loads the scene and compares the two runs. Throws InputError for a scene
// either engine refuses (a tunnel, a shape Box2D cannot take) and, from
// run_engine, for an engine that fails; an engine that refuses the scene's
// settings (exit 3) is a skipped comparison. Built only with Box2D
// (IMPULSE_WITH_BOX2D).
ReferenceComparison compare_with_box2d(const std::string& path, const ReferenceOptions& options);

} // namespace impulse::harness
