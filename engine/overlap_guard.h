// The end-of-step checks of time-stepping (docs/engine.md, "Dense contact").
// The holding problem keeps every point's gap linearised at the step's start;
// a body that turns, or one a neighbour pushed into a third body, can still
// end a little inside another. The overlap guard moves such bodies apart
// (positions only, velocities untouched).
#pragma once

#include "time_stepping_scratch.h"
#include "world.h"

namespace impulse {

// Passes at most. For one pair each pass removes the linear part of the
// overlap, leaving the rotation's second-order remainder, about (omega h)^2 of
// the one before; in a jammed pile moving one pair apart presses its
// neighbours together, and the passes converge as Gauss-Seidel does.
inline constexpr int max_overlap_guard_passes = 4;

// At the step's end poses, while some candidate pair is deeper than
// contact_tolerance (at most max_overlap_guard_passes times): each such pair
// in (a, b) order, at the poses as the pairs before it left them, solves its
// own w = A m + g / h >= 0, m >= 0, m . w = 0 over its points within
// contact_tolerance (at most two: a direct solve) and moves its two bodies by
// h M^-1 J^T m, a nonlinear Gauss-Seidel on positions. Counts passes in
// world.work.overlap_guard_passes.
void guard_overlaps(World& world, double h, TimeSteppingScratch& s);

} // namespace impulse
