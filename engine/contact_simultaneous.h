// Simultaneous contact (solver.contacts = simultaneous; docs/engine.md,
// "Simultaneous contact"): every touching point of every touching pair at the
// collision time is solved together, Newton's law of restitution at each
// point with non-negative impulses, as one small linear complementarity problem
// (the formulation is stated in contact_simultaneous.cpp, the solver in lcp.h).
#pragma once

#include "world.h"

#include <vector>

namespace impulse {

enum class SimultaneousOutcome {
    resolved,         // impulses applied, one event per point that took an impulse
    none_approaching, // touching but nothing approaches: resting contact
    unsolved,         // the LCP solver found no solution
};

struct SimultaneousResult {
    SimultaneousOutcome outcome = SimultaneousOutcome::none_approaching;
    int body_a = -1; // on failure: a pair to name
    int body_b = -1;
};

// At the bodies' current states: gathers the points of every pair within
// solver.contact_tolerance that approach or touch (points already separating
// are left out), solves for the impulses, applies them and appends one event
// per point that took an impulse, in pair and point order. world stepping only
// (it tests world.pairs).
SimultaneousResult resolve_simultaneous_contacts(World& world, double time,
                                                 std::vector<CollisionEvent>& events);

} // namespace impulse
