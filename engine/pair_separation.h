// The signed separation of a pair of bodies in given poses: the one
// narrow-phase query every search makes (the seed's end-of-step test, the
// bisection, the secant search, ccd's samples, local stepping), each counted
// once in world.work.narrow_phase_queries. Callers never count by hand, so the
// counter is the number of queries made.
#pragma once

#include "configuration.h"

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

} // namespace impulse
