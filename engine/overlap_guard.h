// The end-of-step checks of time-stepping (docs/engine.md, "Dense contact").
// The holding problem keeps every point's gap linearised at the step's start;
// a body that turns, or one a neighbour pushed into a third body, can still
// end a little inside another. The overlap guard moves such bodies apart
// (positions only, velocities untouched).
#pragma once

#include "time_stepping_scratch.h"
#include "world.h"

namespace impulse {

// Passes at most. The guard moves bodies by translation only, in which a
// polygon pair's separation is linear until the closest features change and a
// circle's normal turns only at second order, so each pass leaves a small
// fraction of the overlap before it (a turning correction of a small
// spinning box swings its corner back in: measured, it did not converge).
// Measured in pile-boxes-1000 while it falls (impacts at 10 to 16 m/s): each
// pass leaves about a tenth, from 11 cm after the holding step, so 4 passes
// left up to 2e-5 m and 8 reach the 1e-6 m target with room; a pass after
// the overlap is within d costs one measurement and ends the loop.
inline constexpr int max_overlap_guard_passes = 8;

// The guard's position problem may take this many times the product cap of
// the impact and holding solves (island_lcp.h): it is the last word on
// overlap, where an unconverged holding solve only leaves work for it. In
// pile-boxes-10000 at 2.1 s its pile-wide problems (about 8,000 points)
// stopped at the 2,000-product cap in every pass, and the 8 passes left
// 2.3e-7 m, growing to 1.0e-2 m by 3 s; with four times the cap the pile kept
// every overlap within d through that time at about the same products per
// step (fewer passes). Scenes whose guard problems converge are unchanged.
inline constexpr int guard_cap_factor = 4;

// At the step's end poses, while some candidate pair is deeper than
// contact_tolerance d (at most max_overlap_guard_passes times): the bodies
// joined through candidate pairs within d (touching or deeper) form groups,
// and every group with a pair deeper than d solves its own position problem,
// w = A m + g / h >= 0, m >= 0, m . w = 0 over all its points within d plus
// twice the deepest overlap (by solve_island: pivoting up to 16 points, MPRGP
// above), with A the translational part of J M^-1 J^T, and moves its bodies
// by h M^-1 J^T m (positions only; angles and velocities untouched). Solving a group at
// once moves a body squeezed between the floor and a heavy neighbour together
// with that neighbour; pair by pair, the two would pass the overlap back and
// forth, shrinking it only by the mass ratio per pass. Marks the bodies moved
// in s.guard_moved (the energy guard checks them) and counts passes in
// world.work.overlap_guard_passes. When the moves carried some body past its
// reach (the distance the step's candidate pairs were sized for), the pairs
// are found again around the current poses, grown by how far it went beyond,
// and the passes run once more (world.work.overlap_guard_pair_rebuilds): a
// pair the step did not foresee, such as a box pushed into a wall, is held too.
// A group whose iterative solve stopped unconverged is solved again as if every
// body had the same mass (world.work.overlap_guard_equal_masses). If the passes
// still end with a pair deeper than d, its dynamic bodies are marked in
// s.guard_stuck, and guard_energy sends their units back to the step's start.
// With pairs_stale (the step's reach retries ran out while a body could
// still have met one it held no point with) the pairs are found again around
// the end poses before the first pass, so every overlap is among them.
void guard_overlaps(World& world, double h, TimeSteppingScratch& s, bool pairs_stale = false);

} // namespace impulse
