// The world and its step: Hecker's simulation loop (PHYSICS.md, "The
// simulation loop of the seed").
#pragma once

#include "body.h"
#include "contact.h"
#include "solver_settings.h"

#include <optional>
#include <vector>

namespace impulse {

// Two bodies that can collide. The normal of their contacts points toward a;
// when one of them is static, a is the dynamic one.
struct Pair {
    int a = 0;
    int b = 0;
};

// Machine-independent measures of the work a run did (for cost comparisons).
struct WorkCounters {
    long long steps = 0;
    long long narrow_phase_queries = 0;
    long long toi_iterations = 0;
    long long collisions = 0;
};

struct World {
    std::vector<Body> bodies;
    std::vector<Pair> pairs; // every pair that is not two static bodies, in body order
    Vec2 gravity;
    double restitution = 1.0; // e
    SolverSettings solver;
    WorkCounters work;
    std::vector<Transform> scratch_transforms; // reused by the interpenetration test
};

World make_world(std::vector<Body> bodies, Vec2 gravity, double restitution,
                 const SolverSettings& solver);

enum class StepFailure {
    toi_not_converged,   // the bisection could not reach toi_tolerance
    too_many_collisions, // more than solver.max_collisions_per_step within one step
    resting_contact,     // touching, interpenetrating next, yet not approaching
};

struct StepError {
    StepFailure failure;
    double time = 0.0;
    int body_a = -1;
    int body_b = -1;
};

// Advances the world from time t0 by dt, appending every resolved collision to
// events. On failure the world is left at the last consistent configuration.
std::optional<StepError> step(World& world, double t0, double dt,
                              std::vector<CollisionEvent>& events);

} // namespace impulse
