// The observables `impulse box2d` compares (docs/physics.md): quantities that
// survive Box2D's differences from the exact model, computed the same way
// from any simulator's trajectory of a scene.
#pragma once

#include "scene.h"
#include "trajectory.h"

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

// One or more rows per observable of scene.box2d.observables.
std::vector<ObservableRow> compare_observables(const Scene& scene, const Trajectory& impulse,
                                               const Trajectory& box2d);

} // namespace impulse::harness
