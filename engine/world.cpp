#include "world.h"

#include "configuration.h"
#include "local_stepping.h"
#include "single_contact.h"
#include "time_of_impact.h"

namespace impulse {

World make_world(std::vector<Body> bodies, Vec2 gravity, double restitution,
                 const SolverSettings& solver) {
    World world;
    world.bodies = std::move(bodies);
    world.gravity = gravity;
    world.restitution = restitution;
    world.solver = solver;
    if (solver.stepping == Stepping::local) {
        return world;
    }
    const int n = static_cast<int>(world.bodies.size());
    for (int i = 0; i < n; ++i) {
        for (int k = i + 1; k < n; ++k) {
            if (world.bodies[i].is_static() && world.bodies[k].is_static()) {
                continue; // static bodies never collide with each other
            }
            world.pairs.push_back(pair_of(world, i, k));
        }
    }
    return world;
}

namespace {

// The seed's loop: every collision rewinds the whole world to its time and
// integrates every body again from there.
std::optional<StepError> step_world(World& world, double t0, double dt,
                                    std::vector<CollisionEvent>& events) {
    ++world.work.steps;
    Configuration start = configuration_of(world);
    Configuration trial;
    Configuration at_impact;
    double elapsed = 0.0;
    int collisions = 0;
    for (;;) {
        // 1. Integrate every body forward by the rest of the step.
        const double h = dt - elapsed;
        advance_all(world, start, h, trial);
        const int pair_at_h = first_interpenetrating_pair(world, trial);
        if (pair_at_h < 0) {
            commit(world, trial);
            return std::nullopt;
        }

        // 2. Something interpenetrates: search back for the time of collision.
        const TimeOfImpact toi = time_of_impact(world, start, h, trial, pair_at_h, at_impact);
        const Pair pair = world.pairs[toi.pair];
        commit(world, at_impact);
        elapsed += toi.time;
        if (!toi.converged) {
            return StepError{StepFailure::toi_not_converged, t0 + elapsed, pair.a, pair.b};
        }

        // 3. Resolve the collision there, accept it, and go on with the rest of the step.
        if (!resolve_single_contact(world, pair, t0 + elapsed, events)) {
            return StepError{StepFailure::resting_contact, t0 + elapsed, pair.a, pair.b};
        }
        ++world.work.collisions;
        if (++collisions > world.solver.max_collisions_per_step) {
            return StepError{StepFailure::too_many_collisions, t0 + elapsed, pair.a, pair.b};
        }
        start = configuration_of(world);
    }
}

} // namespace

std::optional<StepError> step(World& world, double t0, double dt,
                              std::vector<CollisionEvent>& events) {
    switch (world.solver.stepping) {
    case Stepping::world:
        return step_world(world, t0, dt, events);
    case Stepping::local:
        return step_local(world, t0, dt, events);
    }
    return step_world(world, t0, dt, events);
}

} // namespace impulse
