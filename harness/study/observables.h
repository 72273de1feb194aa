// The observables `impulse box2d` compares (docs/physics.md): quantities that
// survive Box2D's differences from the exact model, computed the same way
// from any simulator's trajectory of a scene.
#pragma once

#include "scene.h"
#include "trajectory.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

struct ObservableRow {
    std::string path;            // "box2d.observables[0]"
    std::string name;            // "apex 2 of 'box' (m)"
    std::optional<double> exact; // where the scene's formulas give one
    std::optional<double> impulse;
    std::optional<double> box2d; // nullopt when the run has no such value
    double tolerance = 0.0;      // atol + rtol * |impulse|
    bool within = false;         // |box2d - impulse| <= tolerance
    std::string note;            // why a value is missing, one sentence
};

// One observable's values in any number of runs of a scene (impulse compare:
// the engine under study, then each reference).
struct ObservableReadings {
    std::string path;
    std::string name;
    std::optional<double> exact;
    std::vector<std::optional<double>> values; // one per run, nullopt when it has none
    double atol = 0.0, rtol = 0.0;             // the observable's, from the scene's box2d block
    std::string note;                          // why values are missing, a sentence each

    // atol + rtol * |values[0]|: how far a run may be from the first.
    double tolerance() const;
    // |values[run] - values[0]| <= tolerance().
    bool within(std::size_t run) const;
};

// A run and the name its notes call it by ("The Box2D run has 2 impacts ...").
struct ObservedRun {
    const Trajectory* trajectory;
    std::string name;
};

// One or more rows per observable of scene.box2d.observables, each with a
// value per run. A post-impact velocity is read at the same frame time in
// every run that has one (the latest of their first frames after the impact),
// its exact answer at that time.
std::vector<ObservableReadings> read_observables(const Scene& scene,
                                                 const std::vector<ObservedRun>& runs);

// read_observables of the two runs "impulse" and "Box2D", as impulse box2d
// shows them.
std::vector<ObservableRow> compare_observables(const Scene& scene, const Trajectory& impulse,
                                               const Trajectory& box2d);

} // namespace impulse::harness
