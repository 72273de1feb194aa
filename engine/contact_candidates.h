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

// How far turning by angle_change (radians, either sign) can carry a point of
// the shape: the chord 2 R sin(|angle_change| / 2), bounded by R |angle_change|
// and by the diameter 2 R, whichever is smaller. The diameter bound keeps a
// body spinning many turns within a step (a rod at 3000 rad/s) from reaching
// metres away, which it cannot (docs/engine.md, "Dense contact").
double turning_reach(const Shape& shape, double angle_change);

// At the bodies' current states (x_k, v_k) and step h: fills s.poses,
// s.reach, s.boxes, s.pairs (sorted by (a, b)), s.points and s.feature (in
// (a, b, k) order) and s.links (one per point). Pairs come from a uniform grid
// whatever the stepping, and are sorted, so world and local stepping find the
// same points in the same order. A body's reach is at least
// s.reach_floor[i] (sized to the world).
void find_contact_candidates(World& world, double h, TimeSteppingScratch& s);

// The overlap guard's pairs when its moves carried a body past its reach: at
// the bodies' current poses, every pair whose boxes, each dynamic body's
// grown by `grow`, overlap; refills s.poses, s.boxes, s.pairs (sorted by
// (a, b)) and what they cover (s.reach, `grow` for each dynamic body, and
// s.paired_at), and leaves s.points as they were.
void find_pairs_around(World& world, double grow, TimeSteppingScratch& s);

// Body b's box over a step from `start` to its current state: its boxes at
// both poses, each grown by `turn` (at least R |angle change|, how far turning
// carries a vertex off its straight path), by d and by the rounding of its
// corners.
Aabb swept_box(const World& world, std::size_t b, const BodyState& start, double turn);

// Files the swept boxes of s.outran (from s.swept) in s.outran_grid, for
// meets_unheld; once per attempt, after the list is complete.
void file_outran(TimeSteppingScratch& s);

// Whether body b, which ended the step further from its start than its reach
// (its box in s.boxes was grown for less), may have touched a body the step
// held no point with. Its swept box (start and end poses, grown by its
// turning and d) is tested against every other body's: s.boxes[k] for a body
// that kept within its reach (that box covers its whole motion), swept[k] for
// one that did not (outran lists them, is_outran[k] != 0 flags them). Yes when the boxes meet and
// the pair is no candidate, or when it is and its manifold at the end poses has a point deeper than
// d (a point farther apart at the start than the pair's reach, not held). s.grid and s.pairs are
// the step's; swept and is_outran are per body; s.outran_grid is file_outran's.
bool meets_unheld(World& world, int b, const std::vector<int>& outran,
                  const std::vector<Aabb>& swept, const std::vector<char>& is_outran,
                  TimeSteppingScratch& s);

// a_i = J_i M^-1 f: the relative normal acceleration gravity alone gives the
// point (0 between two dynamic bodies, g . n against a static one).
double gravity_normal_acceleration(const World& world, const ContactPoint& point);

// The point of `contact` between bodies a and b at their current states, as a
// row of a contact problem; `pair` is only an identity (delassus() compares it).
ContactPoint candidate_point(const World& world, int pair, int a, int b, const Contact& contact);

} // namespace impulse
