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

// A body's acceleration when more than gravity acts on it: resting contact
// forces (solver.resting) add a linear and an angular part, both constant
// over the interval.
struct Acceleration {
    Vec2 linear;
    double angular = 0.0;
};

// advance() under gravity plus other constant forces, with an angular
// acceleration too; each integrator treats
// the angle as it treats the position. With angular = 0 it is advance().
BodyState advance_under(Integrator integrator, const BodyState& state,
                        const Acceleration& acceleration, bool rotates, double h);

} // namespace impulse
