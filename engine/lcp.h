// The small linear complementarity problems of simultaneous contact
// (docs/engine.md, "Simultaneous contact"): given an n x n matrix A and a vector
// q, find lambda with
//
//     lambda >= 0,   w = A lambda + q >= 0,   lambda_i w_i = 0 for every i.
//
// The interface is plain std::vector so that no caller compiles Eigen: the
// solver's translation unit alone includes it, with its vectorisation off
// (lcp.cpp says why).
#pragma once

#include <vector>

namespace impulse {

struct LcpSettings {
    // w_i and A_ii lambda_i (both velocities in contact problems) count as zero
    // within this fraction of max_i |q_i|: that much is rounding, not physics.
    double tolerance = 1e-9;
    // A principal block whose pivots fall below this fraction of its largest
    // (or, 2 x 2, whose determinant falls below this fraction of A_00 A_11)
    // is treated as singular: a rank-revealing minimum-norm solve.
    double singular_threshold = 1e-10;
    // Principal pivots before the solver gives up on the least-index rule and
    // falls back to trying every active set; 0 means max(64, 8 n).
    int max_pivots = 0;
    // The fallback tries all 2^n active sets, so only this far.
    int max_enumerated = 12;
};

struct LcpSolution {
    bool solved = false;
    std::vector<double> lambda; // >= 0 (values within the tolerance of 0 are set to 0)
    std::vector<double> w;      // A lambda + q at that lambda
    int pivots = 0;             // principal pivots taken by the least-index rule
    int enumerated = 0;         // active sets tried by the fallback (0 when not needed)
};

// A is row-major (A[i * n + k]) with positive diagonal, meant to be symmetric
// positive semidefinite (a Delassus matrix J M^-1 J^T); q has n entries.
// Deterministic: the same bits on every platform for the same input.
// `warm` (empty, or n entries) guesses the answer: the pivoting starts from
// the points with warm_i > 0 and every approaching point (q_i < 0) instead
// of the approaching points alone. The answer is the solve of the final
// active set's block, so a guess changes how many block solves are made,
// not the impulses, except where a point sits within the tolerance of both
// conditions and either set is an answer (a time-stepping pile, warm from
// its last step: 3.8 block solves per problem cold, 1.06 warm).
LcpSolution solve_lcp(const std::vector<double>& A, const std::vector<double>& q,
                      const LcpSettings& settings = {}, const std::vector<double>& warm = {});

} // namespace impulse
