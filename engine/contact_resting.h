// Resting contact (solver.resting; docs/engine.md, "Resting contact"). The
// seed's model knows only collisions, so a body coming to rest on another
// either bounces forever (e < 1: infinitely many ever smaller bounces before
// t_inf, a Zeno cascade) or is refused. Two rules end that:
//
// 1. A contact approaching slower than the rest speed v_rest = sqrt(2 |g| d)
//    (d = solver.contact_tolerance) is resolved with e = 0: its rebound would
//    rise less than d, below what the engine can tell from touching. The
//    cascade then ends at its last bounce, at most 2 e v_rest / (|g| (1 - e))
//    before the exact t_inf (the flights it skips).
// 2. Touching points whose relative normal speed is at most v_rest rest: they
//    carry contact forces f >= 0 that keep their relative normal acceleration
//    a >= 0, with f a = 0 (an LCP at the acceleration level, Baraff 1994), and
//    every body moves with gravity plus its contact forces, constant over the
//    interval. Resting pairs count as interpenetrating only beyond d.
#pragma once

#include "integrator.h"

#include <vector>

namespace impulse {

struct World;
struct Body;
struct Contact;

struct RestingContacts {
    bool any = false;                        // some pair rests: use the fields below
    std::vector<Acceleration> accelerations; // per body: gravity plus contact forces
    std::vector<char> pair_resting;          // per world.pairs entry
};

// v_rest: approach speeds at or below it end in rest (rule 1) or rest (rule 2).
double rest_speed(const World& world);

// The restitution a collision at this contact gets: world.restitution, or 0
// below the rest speed when solver.resting is on.
double effective_restitution(const World& world, const Body& a, const Body& b,
                             const Contact& contact);

// Finds the resting points at the bodies' current states, solves for their
// forces and fills world.resting_contacts. Returns false when the force LCP
// has no solution (then body_a and body_b name a pair in it).
bool find_resting_contacts(World& world, int& body_a, int& body_b);

} // namespace impulse
