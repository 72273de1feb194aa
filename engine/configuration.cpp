#include "configuration.h"

#include "integrator.h"
#include "manifold.h"

namespace impulse {

Configuration configuration_of(const World& world) {
    Configuration c;
    c.reserve(world.bodies.size());
    for (const Body& body : world.bodies) {
        c.push_back(body.state);
    }
    return c;
}

void commit(World& world, const Configuration& configuration) {
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
        world.bodies[i].state = configuration[i];
    }
}

void advance_all(World& world, const Configuration& from, double h, Configuration& to) {
    to.resize(from.size());
    for (std::size_t i = 0; i < from.size(); ++i) {
        const Body& body = world.bodies[i];
        if (body.is_static()) {
            to[i] = from[i];
            continue;
        }
        ++world.work.body_advances;
        to[i] = advance(world.solver.integrator, from[i], world.gravity, body.rotates(), h);
    }
}

double pair_separation(const World& world, const Configuration& configuration, const Pair& pair) {
    const Body& a = world.bodies[pair.a];
    const Body& b = world.bodies[pair.b];
    return separation(a.shape, transform_of(configuration[pair.a]), b.shape,
                      transform_of(configuration[pair.b]));
}

int first_interpenetrating_pair(World& world, const Configuration& configuration) {
    // Each body's rotation once per configuration, not once per pair it is in.
    std::vector<Transform>& xf = world.scratch_transforms;
    xf.resize(configuration.size());
    for (std::size_t i = 0; i < configuration.size(); ++i) {
        xf[i] = transform_of(configuration[i]);
    }
    for (std::size_t p = 0; p < world.pairs.size(); ++p) {
        ++world.work.narrow_phase_queries;
        const Pair& pair = world.pairs[p];
        if (separation(world.bodies[pair.a].shape, xf[pair.a], world.bodies[pair.b].shape,
                       xf[pair.b]) < 0.0) {
            return static_cast<int>(p);
        }
    }
    return -1;
}

} // namespace impulse
