// The narrow-phase queries the step makes of a pair of bodies, each counted
// once in world.work.narrow_phase_queries: its signed separation, which every
// search asks (the seed's end-of-step test, the bisection, the secant search,
// ccd's samples, local stepping), and its contact points, which the contact
// models ask. Callers never count by hand, so the counter is the number of
// queries made.
#pragma once

#include "configuration.h"
#include "manifold.h"

namespace impulse {

// Negative exactly when the pair interpenetrates (manifold.h, separation()).
double pair_separation(World& world, const Pair& pair, const Transform& xa, const Transform& xb);

inline double pair_separation(World& world, const Pair& pair, const BodyState& a,
                              const BodyState& b) {
    return pair_separation(world, pair, transform_of(a), transform_of(b));
}

inline double pair_separation(World& world, const Configuration& configuration, const Pair& pair) {
    return pair_separation(world, pair, configuration[static_cast<std::size_t>(pair.a)],
                           configuration[static_cast<std::size_t>(pair.b)]);
}

// The pair's contact points at the bodies' current states (manifold.h,
// collide(), with the solver's contact_tolerance and vertex_normal).
Manifold pair_manifold(World& world, const Pair& pair);

} // namespace impulse
