#include "configuration.h"

#include "integrator.h"
#include "narrow_phase_query.h"

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

BodyState advance_body(World& world, std::size_t i, const BodyState& from, double h) {
    const Body& body = world.bodies[i];
    if (body.is_static()) {
        return from;
    }
    ++world.work.body_advances;
    if (world.resting_contacts.any) {
        return advance_under(world.solver.integrator, from, world.resting_contacts.accelerations[i],
                             body.rotates(), h);
    }
    return advance(world.solver.integrator, from, world.gravity, body.rotates(), h);
}

void advance_all(World& world, const Configuration& from, double h, Configuration& to) {
    to.resize(from.size());
    for (std::size_t i = 0; i < from.size(); ++i) {
        to[i] = advance_body(world, i, from[i], h);
    }
}

double interpenetration_floor(const World& world, std::size_t p) {
    return world.resting_contacts.any && world.resting_contacts.pair_resting[p] != 0
               ? -world.solver.contact_tolerance
               : 0.0;
}

int first_interpenetrating_pair(World& world, const Configuration& configuration) {
    // Each body's rotation once per configuration, not once per pair it is in.
    std::vector<Transform>& xf = world.scratch_transforms;
    xf.resize(configuration.size());
    for (std::size_t i = 0; i < configuration.size(); ++i) {
        xf[i] = transform_of(configuration[i]);
    }
    for (std::size_t p = 0; p < world.pairs.size(); ++p) {
        const Pair& pair = world.pairs[p];
        if (pair_separation(world, pair, xf[static_cast<std::size_t>(pair.a)],
                            xf[static_cast<std::size_t>(pair.b)]) <
            interpenetration_floor(world, p)) {
            return static_cast<int>(p);
        }
    }
    return -1;
}

} // namespace impulse
