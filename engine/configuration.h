// The poses of all bodies at one instant, and the questions the step asks of
// them: where is everything after h seconds, and does any pair interpenetrate?
#pragma once

#include "world.h"

#include <vector>

namespace impulse {

using Configuration = std::vector<BodyState>;

Configuration configuration_of(const World& world);
void commit(World& world, const Configuration& configuration);

// Moves every dynamic body h seconds forward from `from` into `to`.
void advance_all(World& world, const Configuration& from, double h, Configuration& to);

double pair_separation(const World& world, const Configuration& configuration, const Pair& pair);

// Index into world.pairs of the first interpenetrating pair, or -1.
int first_interpenetrating_pair(World& world, const Configuration& configuration);

} // namespace impulse
