// Dense contact by time-stepping (solver.resting_method; docs/engine.md,
// "Dense contact"; docs/physics.md, "Dense contact: time-stepping"): per step,
// candidate contact points within reach of the step's motion, islands, Newton's
// law at the impacts of the step's start, a velocity-level complementarity
// problem that holds every contact, and an overlap guard, after Moreau and Jean.
#pragma once

#include "world.h"

namespace impulse {

// Advances the world from time t0 by dt with time-stepping contact, appending
// every impact to events. On failure the world is left at the step's start.
std::optional<StepError> step_time_stepping(World& world, double t0, double dt,
                                            std::vector<CollisionEvent>& events);

} // namespace impulse
