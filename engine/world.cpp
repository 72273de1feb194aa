#include "world.h"

#include "configuration.h"
#include "manifold.h"
#include "restitution.h"
#include "time_of_impact.h"

namespace impulse {

World make_world(std::vector<Body> bodies, Vec2 gravity, double restitution,
                 const SolverSettings& solver) {
    World world;
    world.bodies = std::move(bodies);
    world.gravity = gravity;
    world.restitution = restitution;
    world.solver = solver;
    const int n = static_cast<int>(world.bodies.size());
    for (int i = 0; i < n; ++i) {
        for (int k = i + 1; k < n; ++k) {
            const bool i_static = world.bodies[i].is_static();
            const bool k_static = world.bodies[k].is_static();
            if (i_static && k_static) {
                continue; // static bodies never collide with each other
            }
            world.pairs.push_back(i_static ? Pair{k, i} : Pair{i, k});
        }
    }
    return world;
}

namespace {

// The seed resolves one point of one pair at a time: the deepest approaching
// point of the pair found by the time-of-impact search (ties go to the first).
bool resolve_single_contact(World& world, const Pair& pair, double time,
                            std::vector<CollisionEvent>& events) {
    Body& a = world.bodies[pair.a];
    Body& b = world.bodies[pair.b];
    ++world.work.narrow_phase_queries;
    const Manifold m = collide(a.shape, transform_of(a.state), b.shape, transform_of(b.state),
                               world.solver.contact_tolerance);
    int chosen = -1;
    for (int i = 0; i < m.point_count; ++i) {
        const Contact& c = m.points[i];
        if (relative_normal_velocity(a, b, c.point, c.normal) < 0.0 &&
            (chosen < 0 || c.separation < m.points[chosen].separation)) {
            chosen = i;
        }
    }
    if (chosen < 0) {
        return false;
    }
    const Contact& c = m.points[chosen];
    const Impulse impulse = resolve_collision(a, b, c, world.restitution);
    events.push_back(
        {time, pair.a, pair.b, c.point, c.normal, impulse.j, impulse.vn_before, impulse.vn_after});
    return true;
}

} // namespace

std::optional<StepError> step(World& world, double t0, double dt,
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

} // namespace impulse
