// Projected Gauss-Seidel for large contact islands (docs/engine.md, "Dense
// contact"). Solves the same LCP as solve_lcp (lcp.h),
//
//     lambda >= 0,   w = A lambda + q >= 0,   lambda_i w_i = 0,
//
// with A = J M^-1 J^T of the given points, but in body-velocity form: A is
// never formed, each point costs O(1) per sweep, and a warm start from the
// previous step's lambda leaves a settled pile one or two sweeps from done.
#pragma once

#include "contact_rows.h"

#include <vector>

namespace impulse {

struct PgsSettings {
    // Stop when every point's residual max(-w_i, min(A_ii lambda_i, w_i)) is at
    // most this (a velocity, m/s).
    double tolerance = 0.0;
    int max_sweeps = 200;
};

struct PgsResult {
    bool converged = false;
    int sweeps = 0;
    double residual = 0.0; // the largest residual after the last sweep
};

// Scratch kept between calls: per-body entries sized to the world once, reset
// only where a call touched them, so a call costs O(its island).
struct PgsScratch {
    std::vector<int> local_of_body; // -1 between calls
    std::vector<double> dv_x;       // per slot: the velocity change M^-1 J^T lambda
    std::vector<double> dv_y;
    std::vector<double> dw;
    std::vector<double> diagonal; // per point: A_ii, the bits delassus() gives
    std::vector<int> bodies;      // the world index of each slot past 0
    std::vector<PgsRow> rows;     // per point
};

// points' a and b are world body indices (their `pair` is not used); q has one
// entry per point; lambda holds the warm start on entry (zeros if its size
// differs) and the solution on return. Sweeps go through the points in the
// order given, then in reverse, alternately; at least one sweep is made. After
// each sweep one extra pass computes every w_i of the lambda as it stands and
// the residual from them: that exact residual, never an estimate taken during
// the sweep, decides convergence and is what PgsResult reports. A sweep costs
// about 28 flops per point (w_i, the update, the two bodies' dv) and the pass
// about 14. Negative warm-start entries are taken as 0. Deterministic: fixed
// order, only + - * /.
PgsResult solve_pgs(const World& world, const std::vector<ContactPoint>& points,
                    const std::vector<double>& q, std::vector<double>& lambda,
                    const PgsSettings& settings, PgsScratch& scratch);

} // namespace impulse
