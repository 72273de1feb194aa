// MPRGP for large contact islands (docs/engine.md, "Dense contact"): Dostal's
// modified proportioning with reduced gradient projections. It solves the same
// LCP as solve_pgs (pgs.h) and solve_lcp (lcp.h),
//
//     lambda >= 0,   w = A lambda + q >= 0,   lambda_i w_i = 0,
//
// as the optimality condition of the bound-constrained convex QP
// min 1/2 l^T A l + q^T l subject to l >= 0 (its gradient is w). Conjugate
// gradient steps on the free set (lambda_i > 0), expansion steps (a gradient
// step of fixed length 1.9 / ||A||, projected onto l >= 0) when a CG step
// would leave the feasible set, and proportioning steps (into the active set's
// negative gradient) when that gradient dominates. It converges in about
// sqrt(cond A) products where Gauss-Seidel needs about cond A sweeps: a cold
// column of 50 boxes in a few hundred products instead of ~35,000 sweeps.
#pragma once

#include "contact_problem.h"
#include "pgs.h"

#include <cstddef>
#include <vector>

namespace impulse {

// The smallest island MPRGP scales (more points than this). Settle times of
// frictionless piles are chaotic in the converged solution: scaled, the
// solution moves within the tolerance, and pile-polygons (islands of at most
// 50 points) then rocks past its at-rest time, and one random 40-body pile of
// tests/test_dense_sweeps.cpp past its 60 s rest budget (islands up to about
// 120 points). So the threshold is fitted, not derived: small islands keep the
// unscaled iteration (the 200 random problems of tests/test_mprgp.cpp take at
// most 60 products either way), large ones, where a mass ratio of 1:100 costs
// up to six times the products (a column of 150 boxes: 4312 against 967), are
// scaled.
inline constexpr std::size_t diagonal_scaling_points = 128;

// Scratch kept between calls: per-body entries sized to the world once, reset
// only where a call touched them, so a call costs O(its island) and, once its
// vectors have grown to the largest island, allocates nothing.
struct MprgpScratch {
    std::vector<int> local_of_body; // -1 between calls
    std::vector<int> bodies;        // the world index of each slot past 0
    std::vector<PgsRow> rows;       // per point: its row of J and column of M^-1 J^T
    std::vector<double> diagonal;   // per point: A_ii, the bits delassus() gives
    std::vector<double> scale;      // per point: 1 / sqrt(A_ii) (1 where A_ii = 0)
    std::vector<double> scaled_q;   // per point: scale_i q_i
    std::vector<double> mu;         // per point: lambda_i / scale_i, the scaled unknown
    std::vector<double> dv_x;       // per slot: M^-1 J^T x of the vector a product takes
    std::vector<double> dv_y;
    std::vector<double> dw;
    std::vector<double> gradient;      // per point: w = A lambda + q
    std::vector<double> direction;     // per point: the search direction p
    std::vector<double> product;       // per point: A p
    std::vector<double> ray;           // per point: min(p, 0), a candidate unbounded ray
    std::vector<double> ray_product;   // per point: A ray
    std::vector<double> ray_residual;  // per point: refining the ray (mprgp.cpp, refine_ray)
    std::vector<double> ray_direction; // per point: the same
    std::vector<double> ray_direction_product; // per point: A ray_direction
    std::vector<double> anchor_mu;             // per point: mu at the cycle test's anchor
    std::vector<double> anchor_gradient;       // per point: the gradient there
};

// solve_pgs's result, and whether the problem has no solution.
struct MprgpResult : PgsResult {
    // A ray the iteration was about to step along proved the QP unbounded
    // below (the LCP without a solution; solve_mprgp). converged is then
    // false, lambda the last iterate (finite, no answer) and residual its.
    bool unbounded = false;
};

// The contract of solve_pgs: points' a and b are world body indices (their
// `pair` is not used); q has one entry per point; lambda holds the warm start
// on entry (zeros if its size differs, negative entries taken as 0) and the
// solution on return. PgsResult.residual is max_i max(-w_i, min(A_ii lambda_i,
// w_i)) of the returned lambda with w from a fresh product (A^ mu + q^, below),
// never from the iteration's running gradient; converged says it is at most
// settings.tolerance.
//
// PgsResult.sweeps counts matrix-vector products A x, each made in
// body-velocity form (J^T x into per-body dv, then J dv: about 26 flops per
// point, A never formed), and the iteration adds about 10 flops per point of
// dot products and updates: one product costs about what one PGS sweep plus
// its residual pass costs. settings.max_sweeps caps the products the iteration
// makes; one more may follow to measure the residual of the lambda returned. A
// cold start makes no product for its first gradient (it is q); a warm start
// that already meets the tolerance costs exactly one product and is returned
// unchanged.
//
// Diagonal scaling (above diagonal_scaling_points points): the iteration runs on mu = D^1/2 lambda
// with D = diag(A), i.e. on A^ = D^-1/2 A D^-1/2 (unit diagonal) and q^ = D^-1/2 q. The bound
// lambda >= 0 is mu >= 0, so MPRGP applies unchanged, and the scaled gradient
// is D^-1/2 w, so the residual is computed per point in the original units
// (its scaled value times sqrt(A_ii)) and settings.tolerance keeps its
// meaning. Mass ratios of 1:100 make A's diagonal span four orders of
// magnitude; the scaling removes that part of cond A (docs/engine.md).
// Islands of at most diagonal_scaling_points points are solved unscaled
// with one common scale, a power of two (the bits of the unscaled iteration,
// exactly rescaled; impulse_unit.h, row_unit): see that constant.
//
// ||A^|| is bounded exactly and cheaply, never estimated: with s_ib the M^-1
// norm of point i's scaled row of J on its body b and S_b the sum of s over
// the body's points, Cauchy-Schwarz gives m^T A^ m <= sum_i m_i^2 (s_ia S_a +
// s_ib S_b), so ||A^|| <= max_i (s_ia S_a + s_ib S_b). A only has to be
// positive semidefinite (redundant points of one manifold, a body held by
// many): a direction of zero curvature takes the step to the bound, or a
// projected gradient step, so nothing divides by zero and no regularisation
// is added. A point between static bodies only (A_ii = 0) is left unscaled.
//
// Unbounded problems (docs/engine.md, "The island solver"): no lambda meets
// the conditions when a ray y >= 0 has A y = 0 and q.y < 0 (a slab pressed
// between two walls of opposite normals deeper than its slot). The
// iteration stops with `unbounded` set, instead of running the impulses
// towards infinity to the cap, when a ray that raises impulses only has
// curvature within the rounding of its own computation ((2 n + 8) eps B
// |y|^2, B the bound above) and descends faster than the tolerance forgives.
// The rays tried: a step's direction with no bound ahead, as it comes;
// directions nearly so, and the impulses' growth since the products 1, 2, 4,
// 8, ..., each projected onto A's null space first (a few more products,
// spent only where a cheap gate passes). A solvable problem passes only if
// its solutions are beyond what the rounding lets the iteration compute.
//
// Deterministic: fixed order, only + - * / sqrt, no threads.
//
// `scaling`: by_size scales the diagonal above diagonal_scaling_points
// points only; diagonal scales it whatever the size (island_lcp.cpp's retry
// of a small island found unbounded, whose masses may span more than the
// unscaled iteration resolves).
enum class MprgpScaling { by_size, diagonal };
MprgpResult solve_mprgp(const World& world, const std::vector<ContactPoint>& points,
                        const std::vector<double>& q, std::vector<double>& lambda,
                        const PgsSettings& settings, MprgpScratch& scratch,
                        MprgpScaling scaling = MprgpScaling::by_size);

} // namespace impulse
