// ccd under time-stepping (solver.ccd; docs/engine.md, "Tunnelling"). A
// time step holds the contact points its start sees, each one linear in the
// bodies' velocities; a body that turns far within a step (a thin rod at
// thousands of rad/s) can cross a thin one that no such point held. With ccd
// the step's motion is swept as the event model's is, and a crossing is
// refused, naming the pair, instead of passing unseen.
#pragma once

#include "time_stepping_scratch.h"
#include "world.h"

#include <optional>

namespace impulse {

// The first candidate pair of the step that the step's motion carries deeper
// into each other than half the smaller of their inradii (a crossing: a held
// contact never sinks that far), or nothing. The motion: a body an impulse
// moved goes uniformly from x_k to its end pose (x_k + h v_{k+1}, the angle
// likewise, as the step sets it), every other body flies freely under
// gravity by the scene's integrator. Call it with the bodies at the step's
// end poses, before the overlap guard moves them.
std::optional<StepError> swept_crossing(World& world, const TimeSteppingScratch& s, double t0,
                                        double h);

} // namespace impulse
