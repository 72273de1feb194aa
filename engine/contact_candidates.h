// The contact points a time-stepping step must hold (docs/engine.md, "Dense
// contact"): every pair of bodies that the step's motion can bring together,
// with its manifold's points up to that distance apart (speculative contact,
// sized to the motion instead of a constant).
#pragma once

#include "time_stepping_scratch.h"
#include "world.h"

namespace impulse {

// The farthest a point of the shape lies from its centre of mass, for how far
// rotation can carry it (a circle's surface turns into itself: 0).
double rotation_radius(const Shape& shape);

// At the bodies' current states (x_k, v_k) and step h: fills s.poses,
// s.reach, s.boxes, s.pairs (sorted by (a, b)), s.points and s.feature (in
// (a, b, k) order) and s.links (one per point). Pairs come from a uniform grid
// whatever the stepping, and are sorted, so world and local stepping find the
// same points in the same order. A body's reach is at least
// s.reach_floor[i] (sized to the world).
void find_contact_candidates(World& world, double h, TimeSteppingScratch& s);

// The overlap guard's pairs when its moves carried a body past its reach: at
// the bodies' current poses, every pair whose boxes, each dynamic body's
// grown by `grow`, overlap; refills s.poses, s.boxes and s.pairs (sorted by
// (a, b)) and leaves s.points as they were.
void find_pairs_around(World& world, double grow, TimeSteppingScratch& s);

// a_i = J_i M^-1 f: the relative normal acceleration gravity alone gives the
// point (0 between two dynamic bodies, g . n against a static one).
double gravity_normal_acceleration(const World& world, const ContactPoint& point);

// The point of `contact` between bodies a and b at their current states, as a
// row of a contact problem; `pair` is only an identity (delassus() compares it).
ContactPoint candidate_point(const World& world, int pair, int a, int b, const Contact& contact);

} // namespace impulse
