// The second reference's logic (impulse box2d): one scene run in the engine
// under study (the impulse engine unless told otherwise: any engine behind
// run_engine, engine.h) and in Box2D with friction off, the observables its
// "box2d" block names compared (observables.h), computed from the two
// trajectories. The verb (cli/box2d.cpp) parses and prints.
#pragma once

#include "engine.h"
#include "observables.h"
#include "scene.h"
#include "trajectory.h"

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
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

// Loads the scene and compares the two runs. Throws InputError for a scene
// either engine refuses (a tunnel, a shape Box2D cannot take) and, from
// run_engine, for an engine that fails; an engine that refuses the scene's
// settings (exit 3) is a skipped comparison. Built only with Box2D
// (IMPULSE_WITH_BOX2D).
ReferenceComparison compare_with_box2d(const std::string& path, const ReferenceOptions& options);

} // namespace impulse::harness
