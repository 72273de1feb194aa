// `impulse run`: a scene in, a trajectory out.
#pragma once

#include "scene.h"
#include "trajectory.h"

#include <optional>
#include <string>

namespace impulse::harness {

// Command-line overrides that change the physics; each one used is recorded
// in the trajectory's solver block under "overrides".
struct Overrides {
    std::optional<double> dt;
    std::optional<Integrator> integrator;
    std::optional<double> toi_tolerance;
};

Scene with_overrides(Scene scene, const Overrides& overrides);

// The solver block's "overrides" value for the overrides given, e.g.
// ["dt", "integrator"], in that fixed order; empty when none is given. Every
// engine's trajectory records them so, whichever engine ran the scene.
std::string overrides_list(const Overrides& overrides);

// Simulates the scene with the impulse engine; throws InputError when the
// scene asks for something the engine cannot do.
Trajectory run_scene(const Scene& scene, const Overrides& overrides = {});

} // namespace impulse::harness
