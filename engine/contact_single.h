// The seed's contact model (docs/physics.md, "The simulation loop of the seed"):
// one point of one pair at a time.
#pragma once

#include "world.h"

#include <vector>

namespace impulse {

// Resolves the deepest approaching point of the pair (ties go to the first)
// with Eq. 9 at the bodies' current states and appends the event; a point
// whose impulse leaves its approach exactly as it was (rounding size) gives
// way to the next (docs/engine.md, "Which pair and which point"). False when
// no point approaches: touching without approaching, which the seed model
// cannot resolve.
bool resolve_single_contact(World& world, const Pair& pair, double time,
                            std::vector<CollisionEvent>& events);

} // namespace impulse
