// A set of contact points as one problem (simultaneous contact, resting
// contact): each point's terms of Eq. 9 and the Delassus matrix A = J M^-1 J^T,
// the change of every point's relative normal velocity per unit impulse at
// every point, which both the impulse and the force LCPs are built on.
#pragma once

#include "world.h"

#include <vector>

namespace impulse {

// A point of the problem with the terms of Eq. 9 it needs.
struct ContactPoint {
    int pair = 0; // index in world.pairs
    int a = 0;    // the normal points toward a (contact.h)
    int b = 0;
    Contact contact;
    double rn_a = 0.0; // perp(r_AP) . n  (Eq. 9)
    double rn_b = 0.0; // perp(r_BP) . n
    double vn = 0.0;   // v1_AB . n  (Eqs. 1, 2)
};

// The point `contact` of world.pairs[pair] at the bodies' current states, with
// its relative normal velocity vn.
ContactPoint contact_point(const World& world, int pair, const Contact& contact, double vn);

// A_ij for points i and j.
double delassus(const World& world, const ContactPoint& i, const ContactPoint& j);

// The whole matrix, row-major, with A_ij and A_ji the same bits.
std::vector<double> delassus_matrix(const World& world, const std::vector<ContactPoint>& points);

} // namespace impulse
