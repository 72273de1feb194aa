// The scale each compared value is measured at (docs/gate-rules.md, "ULP and
// relative differences"): ULP and relative differences near zero are counted
// in rounding errors of that scale (scaled_difference.h), not of the value's
// own size.
#pragma once

#include "trajectory.h"

#include <array>
#include <cstddef>
#include <vector>

namespace impulse::harness {

// One scale per column of `gold.frames`, in column order:
// - a column's own largest finite |value| over the golden's frames;
// - a body's x and y share the larger of their two scales, and so do vx and
//   vy: a component that stays near zero (the x of a disc dropped straight)
//   is computed with the other one (normals, rotations), so its rounding is
//   of the vector's size;
// - an angle's scale is at least 1 rad: turning by dθ moves a body's points
//   by R dθ whatever θ is, so a change of an angle means what it means at a
//   radian (an angle of 1e-15 rad changed by 1e-16 is one rounding error of
//   a rotation, not a tenth of the value).
// 0 for a column with no finite value and no partner.
std::vector<double> column_scales(const Trajectory& gold);

// The largest finite |x| or |y| of any body over the golden's frames: the
// scale of a collision's contact point, a position in the scene.
double position_scale(const Trajectory& gold);

} // namespace impulse::harness
