// The world and its step: Hecker's simulation loop (docs/physics.md, "The
// simulation loop of the seed").
#pragma once

#include "body.h"
#include "body_clock.h"
#include "broad_phase.h"
#include "contact.h"
#include "contact_resting.h"
#include "solver_settings.h"

#include <memory>
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
    long long body_advances = 0; // one body integrated over one interval
    // Local stepping: pairs found already interpenetrating and separating at the
    // start of their search, left to separate (docs/engine.md, "Local stepping").
    long long missed_grazes = 0;
    // Dense contact by time-stepping (docs/engine.md, "Dense contact").
    long long time_stepping_steps = 0;  // steps taken by the time-stepping method
    long long islands = 0;              // contact islands solved, summed over steps
    long long island_points = 0;        // contact points in those islands
    long long direct_solves = 0;        // island problems solved by pivoting (solve_lcp)
    long long solver_sweeps = 0;        // projected Gauss-Seidel sweeps
    long long unconverged_islands = 0;  // iterative solves stopped by the sweep cap
    long long overlap_guard_passes = 0; // position corrections after a step
    long long energy_guard_steps = 0;   // islands whose energy rise was removed
    double energy_guard_joules = 0.0;   // energy those islands had gained, removed
    // Which path each of those fallbacks took (tests assert them):
    long long energy_guard_rescaled = 0;    // islands whose velocities were scaled down
    long long energy_guard_returned = 0;    // islands sent back to x_k at rest (K < the rise)
    long long energy_guard_lone_bodies = 0; // bodies in no island that the overlap guard
                                            // moved, energy-checked on their own
    long long overlap_guard_unsolved = 0;   // guard groups whose position problem failed
    long long overlap_guard_turns = 0; // guard groups solved only by turning (overlap_guard.cpp)
                                       // (the overlap stays; max-overlap judges it)
    long long overlap_guard_pair_rebuilds = 0; // guard steps whose moves outran a reach
    long long overlap_guard_products = 0;      // the guard's share of solver_sweeps
    long long overlap_guard_equal_masses = 0;  // groups moved by their equal-mass answer
    // Energy-guard units sent back to x_k, at rest: the overlap guard left a
    // pair of them deeper than contact_tolerance (overlap_guard.cpp).
    long long overlap_guard_returned = 0;
    // Units sent back to x_k, at rest, because a unit sent back there met
    // them deeper than contact_tolerance (energy_guard.cpp).
    long long returned_units_met = 0;
    long long reach_retries = 0; // steps taken again because an impact outran a reach
    // Holding solves taken again, tightly, because their loose answer would
    // have carried a pair through itself (time_stepping.cpp, crossing).
    long long holding_solved_again = 0;
    // Small islands MPRGP found unbounded, tried again with diagonal scaling,
    // and of those the ones that converged (island_lcp.cpp, run_mprgp).
    long long unbounded_rescaled = 0;
    long long unbounded_rescaled_solved = 0;
    // resting_method automatic: the index of the first step taken by
    // time-stepping (steps before it were events), or -1 while events carry the scene.
    long long time_stepping_from_step = -1;
    // 1 when automatic switched from events to time-stepping (at any step,
    // the first included), 0 when it time-stepped from the start by its rule
    // for piles (starts_in_time_stepping) or never switched.
    long long time_stepping_switched = 0;
    // 1 when that switch was made because a pair could pass through each other
    // within the step (world.cpp, could_pass_through), 0 when events failed.
    long long time_stepping_for_speed = 0;
};

// Scratch memory of local stepping, kept between steps so a step allocates nothing.
struct LocalScratch {
    std::vector<BodyClock> clocks;
    std::vector<Aabb> boxes;
    UniformGrid grid;
    std::vector<PendingCollision> queue; // a heap ordered by later()
};

// Scratch memory of time-stepping (time_stepping_scratch.h), created on first
// use. A copy of a World starts with none: it is scratch, not state, and its
// contents need the contact-problem types that include this header.
struct TimeSteppingScratch;
class TimeSteppingScratchSlot {
  public:
    TimeSteppingScratchSlot() = default;
    TimeSteppingScratchSlot(const TimeSteppingScratchSlot&) {}
    TimeSteppingScratchSlot& operator=(const TimeSteppingScratchSlot&) { return *this; }
    TimeSteppingScratchSlot(TimeSteppingScratchSlot&&) noexcept = default;
    TimeSteppingScratchSlot& operator=(TimeSteppingScratchSlot&&) noexcept = default;
    ~TimeSteppingScratchSlot() = default;
    TimeSteppingScratch& get(); // time_stepping.cpp
  private:
    std::unique_ptr<TimeSteppingScratch, void (*)(TimeSteppingScratch*)> scratch_{nullptr, nullptr};
};

// The holding impulse a time-stepping contact point took in the last step,
// keyed by its pair and its index in the pair's manifold: the iterative
// solver's warm start. State, not scratch: a copy of the world keeps it.
struct WarmImpulse {
    int a = 0;
    int b = 0;
    int k = 0;
    double impulse = 0.0;
};

// The (a, b, k) order warm starts are kept in.
inline bool warm_key_before(const WarmImpulse& x, const WarmImpulse& y) {
    return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.k < y.k;
}

struct World {
    std::vector<Body> bodies;
    // Every pair that is not two static bodies, in body order: what the seed's
    // world stepping tests. Local stepping finds its pairs with the broad
    // phase instead and leaves this empty (N^2 pairs would not fit 10^4 bodies).
    std::vector<Pair> pairs;
    Vec2 gravity;
    double restitution = 1.0; // e
    SolverSettings solver;
    double step_dt = 0.0; // the step being taken (step() sets it; contact_resting.cpp reads it)
    WorkCounters work;
    std::vector<Transform> scratch_transforms; // reused by the interpenetration test
    LocalScratch local;
    RestingContacts resting_contacts; // solver.resting: this interval's contact forces
    // Time-stepping (solver.resting_method): last step's holding impulses in
    // (a, b, k) order, and scratch.
    std::vector<WarmImpulse> warm_impulses;
    // The overlap guard's first-pass answers of its large problems, in (a, b,
    // k) order, k the point's index among its pair's rows: the next step's
    // first pass starts from them (overlap_guard.cpp).
    std::vector<WarmImpulse> guard_warm_impulses;
    TimeSteppingScratchSlot ts;
};

// The pair of bodies i and k in the engine's order: a is the dynamic one when
// the other is static, else the lower index.
inline Pair pair_of(const World& world, int i, int k) {
    const int lo = i < k ? i : k;
    const int hi = i < k ? k : i;
    return world.bodies[static_cast<std::size_t>(lo)].is_static() ? Pair{hi, lo} : Pair{lo, hi};
}

World make_world(std::vector<Body> bodies, Vec2 gravity, double restitution,
                 const SolverSettings& solver);

enum class StepFailure {
    toi_not_converged,        // the time-of-impact search (bisection or secant) could not reach
                              // toi_tolerance within solver.max_search_iterations trials
    too_many_collisions,      // more than solver.max_collisions_per_step within one step
                              // (local stepping: for one body)
    resting_contact,          // touching, interpenetrating next, yet not approaching
    contact_problem_unsolved, // contacts: simultaneous: the impulse LCP found no solution
    sweep_not_converged,      // ccd: conservative advancement needed more than
                              // solver.max_search_iterations samples
    contact_pass_through,     // time-stepping: the holding answer carries a pair past its
                              // gap by more than the pair is thick (a crossing)
    swept_crossing,           // time-stepping with ccd: the step's motion carries a pair
                              // through each other where no contact point held it
};

struct StepError {
    StepFailure failure;
    double time = 0.0;
    int body_a = -1;
    int body_b = -1;
    // Time-stepping's island failures (contact_problem_unsolved,
    // contact_pass_through): the heaviest and the lightest dynamic body of the
    // island, -1 otherwise. Rounding alone can leave a problem unsolved whose
    // masses span more digits than a double carries (docs/engine.md, "Mass
    // ratios in one island"), and a message then names them.
    int heaviest = -1;
    int lightest = -1;
};

// Advances the world from time t0 by dt, appending every resolved collision to
// events. On failure the world is left at the last consistent configuration.
std::optional<StepError> step(World& world, double t0, double dt,
                              std::vector<CollisionEvent>& events);

} // namespace impulse
