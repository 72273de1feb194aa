// The contact problem in body-velocity form, shared by the iterative island
// solvers (pgs.h, mprgp.h): each point's row of J and its column of M^-1 J^T,
// over the island's bodies numbered in slots, so that A = J M^-1 J^T is never
// formed and a product with it costs O(points).
#pragma once

#include "contact_problem.h"

#include <cstddef>
#include <vector>

namespace impulse {

// One point's row of J and its column of M^-1 J^T, with the bodies' slots in
// dv. Slot 0 stands for every static body: its k and r are zero, so it stays 0.
struct PgsRow {
    int slot_a = 0;
    int slot_b = 0;
    double nx = 0.0, ny = 0.0, rn_a = 0.0, rn_b = 0.0; // J_i = (n, rn_a | -n, -rn_b)
    double ka_x = 0.0, ka_y = 0.0, ra = 0.0;           // A's velocity change per unit lambda_i
    double kb_x = 0.0, kb_y = 0.0, rb = 0.0;           // B's, with its minus sign
};

// The body's slot in dv: 0 for every static body (zero inverse mass and
// inertia, so its velocity change stays exactly 0), else its own from 1 on,
// handed out in the order bodies are first met. `local_of_body` (the world's
// size, -1 between calls) and `bodies` (each slot's world index) are the
// solver's scratch.
inline int slot_of(const World& world, int body, std::vector<int>& local_of_body,
                   std::vector<int>& bodies) {
    const auto b = static_cast<std::size_t>(body);
    if (world.bodies[b].is_static()) {
        return 0;
    }
    int& slot = local_of_body[b];
    if (slot < 0) {
        bodies.push_back(body);
        slot = static_cast<int>(bodies.size()); // slot 0 is the static bodies'
    }
    return slot;
}

// Point p's row: +lambda n on A and -lambda n on B (restitution.h,
// apply_impulse).
inline PgsRow row_of(const World& world, const ContactPoint& p, std::vector<int>& local_of_body,
                     std::vector<int>& bodies) {
    const Body& a = world.bodies[static_cast<std::size_t>(p.a)];
    const Body& b = world.bodies[static_cast<std::size_t>(p.b)];
    const Vec2 n = p.contact.normal;
    PgsRow r;
    r.slot_a = slot_of(world, p.a, local_of_body, bodies);
    r.slot_b = slot_of(world, p.b, local_of_body, bodies);
    r.nx = n.x;
    r.ny = n.y;
    r.rn_a = p.rn_a;
    r.rn_b = p.rn_b;
    r.ka_x = a.inv_mass * n.x;
    r.ka_y = a.inv_mass * n.y;
    r.ra = a.inv_inertia * p.rn_a;
    r.kb_x = -(b.inv_mass * n.x);
    r.kb_y = -(b.inv_mass * n.y);
    r.rb = -(b.inv_inertia * p.rn_b);
    return r;
}

} // namespace impulse
