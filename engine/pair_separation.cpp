#include "pair_separation.h"

#include "manifold.h"

namespace impulse {

double pair_separation(World& world, const Pair& pair, const Transform& xa, const Transform& xb) {
    ++world.work.narrow_phase_queries;
    return separation(world.bodies[static_cast<std::size_t>(pair.a)].shape, xa,
                      world.bodies[static_cast<std::size_t>(pair.b)].shape, xb);
}

} // namespace impulse
