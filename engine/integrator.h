// How a body moves between collisions: the only force is uniform gravity, so
// the angular velocity is constant and the acceleration is g.
#pragma once

#include "body.h"
#include "solver_settings.h"

namespace impulse {

// Advances a dynamic body's state by h seconds. rotates = false skips the
// angular update; a zero gravity skips the force pass (model only what is needed).
BodyState advance(Integrator integrator, const BodyState& state, Vec2 gravity, bool rotates,
                  double h);

} // namespace impulse
