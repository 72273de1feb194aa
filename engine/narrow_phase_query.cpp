#include "narrow_phase_query.h"

namespace impulse {

double pair_separation(World& world, const Pair& pair, const Transform& xa, const Transform& xb) {
    ++world.work.narrow_phase_queries;
    return separation(world.bodies[static_cast<std::size_t>(pair.a)].shape, xa,
                      world.bodies[static_cast<std::size_t>(pair.b)].shape, xb);
}

Manifold pair_manifold(World& world, const Pair& pair) {
    ++world.work.narrow_phase_queries;
    const Body& a = world.bodies[static_cast<std::size_t>(pair.a)];
    const Body& b = world.bodies[static_cast<std::size_t>(pair.b)];
    return collide(a.shape, transform_of(a.state), b.shape, transform_of(b.state),
                   world.solver.contact_tolerance, world.solver.vertex_normal);
}

} // namespace impulse
