#include "world.h"

#include "configuration.h"
#include "contact_candidates.h"
#include "contact_simultaneous.h"
#include "contact_single.h"
#include "continuous_collision.h"
#include "local_stepping.h"
#include "manifold.h"
#include "time_of_impact.h"
#include "time_stepping.h"

#include <cmath>

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

// The contact model at a collision found between `pair` at `time`.
std::optional<StepError> resolve_contacts(World& world, const Pair& pair, double time,
                                          std::vector<CollisionEvent>& events) {
    switch (world.solver.contacts) {
    case ContactMode::single:
        if (!resolve_single_contact(world, pair, time, events)) {
            return StepError{StepFailure::resting_contact, time, pair.a, pair.b};
        }
        return std::nullopt;
    case ContactMode::simultaneous: {
        const SimultaneousResult r = resolve_simultaneous_contacts(world, time, events);
        switch (r.outcome) {
        case SimultaneousOutcome::resolved:
            return std::nullopt;
        case SimultaneousOutcome::none_approaching:
            return StepError{StepFailure::resting_contact, time, pair.a, pair.b};
        case SimultaneousOutcome::unsolved:
            return StepError{StepFailure::contact_problem_unsolved, time, r.body_a, r.body_b};
        }
        break;
    }
    }
    return StepError{StepFailure::resting_contact, time, pair.a, pair.b};
}

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
        if (world.solver.resting) {
            // Which points rest, and the forces that hold them, for this interval.
            int a = -1;
            int b = -1;
            if (!find_resting_contacts(world, a, b)) {
                return StepError{StepFailure::contact_problem_unsolved, t0 + elapsed, a, b};
            }
            // The inelastic impulse that stops the resting points changed the
            // velocities: the interval starts from them.
            start = configuration_of(world);
        }
        // 1. Integrate every body forward by the rest of the step.
        double h = dt - elapsed;
        advance_all(world, start, h, trial);
        int pair_at_h = first_interpenetrating_pair(world, trial);
        if (world.solver.ccd) {
            // Sweep the whole rest of the step, not only its end: the first
            // sample that interpenetrates bounds the search instead of h.
            const SweptContact swept = first_swept_contact(world, start, h);
            if (!swept.converged) {
                const Pair& stalled = world.pairs[static_cast<std::size_t>(swept.stalled_pair)];
                return StepError{StepFailure::sweep_not_converged, t0 + elapsed, stalled.a,
                                 stalled.b};
            }
            if (swept.pair >= 0 && swept.time < h) {
                h = swept.time;
                advance_all(world, start, h, trial);
            }
            pair_at_h = swept.pair;
        }
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
        if (std::optional<StepError> error = resolve_contacts(world, pair, t0 + elapsed, events)) {
            return error;
        }
        ++world.work.collisions;
        if (++collisions > world.solver.max_collisions_per_step) {
            return StepError{StepFailure::too_many_collisions, t0 + elapsed, pair.a, pair.b};
        }
        start = configuration_of(world);
    }
}

// The event-driven step: the seed's loop or local stepping.
std::optional<StepError> step_events(World& world, double t0, double dt,
                                     std::vector<CollisionEvent>& events) {
    switch (world.solver.stepping) {
    case Stepping::world:
        return step_world(world, t0, dt, events);
    case Stepping::local:
        return step_local(world, t0, dt, events);
    }
    return step_world(world, t0, dt, events);
}

bool starts_in_time_stepping(const World& world) {
    int dynamic = 0;
    for (const Body& body : world.bodies) {
        dynamic += body.is_static() ? 0 : 1;
    }
    return starts_in_time_stepping(world.solver, dynamic);
}

// The failures that say the events model cannot carry the scene on, where
// time-stepping can: a contact at rest, a Zeno cascade, a contact problem with
// no solution. Not ccd's sweep unable to bound a pair: time-stepping does not
// sweep, so a fast thin spinner elsewhere in the scene could then pass
// through a wall unseen (an outside review built one).
bool time_stepping_carries_on(StepFailure failure) {
    return failure == StepFailure::resting_contact || failure == StepFailure::too_many_collisions ||
           failure == StepFailure::contact_problem_unsolved;
}

std::optional<StepError> step_by_time_stepping(World& world, double t0, double dt,
                                               std::vector<CollisionEvent>& events) {
    if (world.work.time_stepping_from_step < 0) {
        world.work.time_stepping_from_step = world.work.steps;
    }
    return step_time_stepping(world, t0, dt, events);
}

// true when some pair may move through each other within the next step,
// which the events model, testing overlap only at a step's end, would not
// see (docs/engine.md, "Dense contact", automatic): the pair's closing speed bounded from
// its velocities now, the turning of its farthest points and, against a
// static body, what gravity adds within the step, moves it at least the sum
// of its two thicknesses (twice the inradii), and its separation now is
// within that travel, so it can meet within the step. Collisions within the
// step can speed a body up; the next step's check sees that speed.
bool could_pass_through(const World& world, double dt) {
    for (const Pair& pair : world.pairs) {
        const Body& a = world.bodies[static_cast<std::size_t>(pair.a)];
        const Body& b = world.bodies[static_cast<std::size_t>(pair.b)];
        const double ra = rotation_radius(a.shape);
        const double rb = rotation_radius(b.shape);
        const double fall = a.is_static() != b.is_static() ? length(world.gravity) * dt : 0.0;
        const double closing = length(a.state.velocity - b.state.velocity) +
                               ra * std::abs(a.state.angular_velocity) +
                               rb * std::abs(b.state.angular_velocity) + fall;
        if (closing * dt < 2.0 * (inradius(a.shape) + inradius(b.shape))) {
            continue; // too thick to pass through within the step
        }
        const double gap =
            separation(a.shape, transform_of(a.state), b.shape, transform_of(b.state));
        if (!(gap > closing * dt)) {
            return true; // near enough to meet within the step
        }
    }
    return false;
}

// automatic: events while they carry the scene; a step they cannot finish, or
// one in which a pair could pass through unseen, is taken by time-stepping
// (whose candidate points cover the step's whole motion), which then carries
// the rest.
std::optional<StepError> step_automatic(World& world, double t0, double dt,
                                        std::vector<CollisionEvent>& events) {
    if (world.work.time_stepping_from_step >= 0 || starts_in_time_stepping(world)) {
        return step_by_time_stepping(world, t0, dt, events);
    }
    if (!world.solver.ccd && could_pass_through(world, dt)) {
        world.work.time_stepping_for_speed = 1;
        world.work.time_stepping_switched = 1;
        return step_by_time_stepping(world, t0, dt, events);
    }
    const Configuration start = configuration_of(world);
    const std::size_t events_at_start = events.size();
    const long long steps = world.work.steps;
    std::optional<StepError> error = step_events(world, t0, dt, events);
    if (!error || !time_stepping_carries_on(error->failure)) {
        return error;
    }
    commit(world, start);
    events.resize(events_at_start);
    world.resting_contacts.any = false;
    world.work.steps = steps; // the step is taken once, by time-stepping
    world.work.time_stepping_switched = 1;
    return step_by_time_stepping(world, t0, dt, events);
}

} // namespace

std::optional<StepError> step(World& world, double t0, double dt,
                              std::vector<CollisionEvent>& events) {
    world.step_dt = dt;
    if (!world.solver.resting) {
        return step_events(world, t0, dt, events);
    }
    switch (world.solver.resting_method) {
    case RestingMethod::events:
        return step_events(world, t0, dt, events);
    case RestingMethod::time_stepping:
        return step_by_time_stepping(world, t0, dt, events);
    case RestingMethod::automatic:
        return step_automatic(world, t0, dt, events);
    }
    return step_events(world, t0, dt, events);
}

} // namespace impulse
