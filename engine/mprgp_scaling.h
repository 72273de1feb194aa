// The scaled problem MPRGP iterates on (mprgp.h, "Diagonal scaling"): above
// diagonal_scaling_points points (or when asked) each point's row scaled by
// 1 / sqrt(A_ii), otherwise every row by one power of two (impulse_unit.h).
#pragma once

#include "mprgp.h"

namespace impulse {

// Rows, diagonals, scales, slots and vector sizes for one call of
// solve_mprgp; the warm start projected onto lambda >= 0 and scaled into
// s.mu. Returns the bound B on ||A^|| (mprgp.h), computed exactly from the
// scaled rows' M^-1 norms.
double prepare_scaled_problem(const World& world, const std::vector<ContactPoint>& points,
                              const std::vector<double>& q, std::vector<double>& lambda,
                              MprgpScratch& s, MprgpScaling scaling);

} // namespace impulse
