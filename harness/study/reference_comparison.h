// The second reference's logic (impulse box2d): one scene run in the impulse
// engine and in Box2D with friction off, the observables its "box2d" block
// names compared (observables.h). The verb (cli/box2d.cpp) parses and prints.
#pragma once

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
    std::optional<double> dt;
    std::optional<int> substeps, velocity_iterations, position_iterations;
    bool scene_integrator = false;
};

// One scene compared: everything both outputs show.
struct ReferenceComparison {
    std::string name;
    std::string file;
    double dt = 0.0;
    std::string integrator;       // the impulse run's
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
// either engine refuses (a tunnel, a shape Box2D cannot take). Built only
// with Box2D (IMPULSE_WITH_BOX2D).
ReferenceComparison compare_with_box2d(const std::string& path, const ReferenceOptions& options);

} // namespace impulse::harness
