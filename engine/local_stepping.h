// Local stepping (solver.stepping = local; docs/engine.md, "Local stepping"):
// the seed's step with each body on its own clock. A collision rewinds and
// re-integrates only the two bodies in it, and only the pairs the broad phase
// finds near them are tested again, so a step costs about N plus a constant
// per collision instead of N per collision.
#pragma once

#include "world.h"

namespace impulse {

// The seed's rules, pair by pair: a pair collides in a step when it
// interpenetrates at the end of its bodies' motions; its collision time is
// the pair's own time-of-impact search from the later of its bodies' clocks;
// collisions are resolved earliest first (ties by pair), each with the seed's
// single contact. With one moving body this is the seed's step bit for bit.
std::optional<StepError> step_local(World& world, double t0, double dt,
                                    std::vector<CollisionEvent>& events);

} // namespace impulse
