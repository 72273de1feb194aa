// The poses of all bodies at one instant, and the questions the step asks of
// them: where is everything after h seconds, and does any pair interpenetrate?
#pragma once

#include "world.h"

#include <vector>

namespace impulse {

using Configuration = std::vector<BodyState>;

Configuration configuration_of(const World& world);
void commit(World& world, const Configuration& configuration);

// Body i's state h seconds after `from`: gravity, plus the resting contact
// forces of this interval when there are any. Every integration of the step
// goes through here, so a trial at a time is the same bits wherever it is made.
BodyState advance_body(World& world, std::size_t i, const BodyState& from, double h);

// Moves every dynamic body h seconds forward from `from` into `to`.
void advance_all(World& world, const Configuration& from, double h, Configuration& to);

// The seed's test: pair p interpenetrates when its separation is below this,
// 0, except that a resting pair is held by its contact forces and counts only
// beyond -contact_tolerance (rounding may sink it by a few ULPs).
double interpenetration_floor(const World& world, std::size_t p);

// Index into world.pairs of the first interpenetrating pair, or -1.
int first_interpenetrating_pair(World& world, const Configuration& configuration);

} // namespace impulse
