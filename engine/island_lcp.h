// One island's contact problem, solved to a stated tolerance by the solver its
// size calls for (docs/engine.md, "Dense contact"): the pivoting solver
// (solve_lcp, lcp.h) up to direct_solve_points points, exact to 1e-9 of
// max |q_i| at O(n^3) per pivot; projected Gauss-Seidel (solve_pgs, pgs.h)
// above, at O(n) per sweep, until every point's residual is within the
// tolerance given.
#pragma once

#include "time_stepping_scratch.h"
#include "world.h"

namespace impulse {

// At or below this many points an island is solved directly.
inline constexpr std::size_t direct_solve_points = 16;

// The solver of islands above direct_solve_points: MPRGP (mprgp.h), measured
// against projected Gauss-Seidel (pgs.h) in docs/engine.md; PGS stays for
// that comparison.
enum class IterativeSolver { pgs, mprgp };
inline constexpr IterativeSolver iterative_solver = IterativeSolver::mprgp;

// MPRGP's cap in matrix products: this many per solver.max_search_iterations
// (2000 at the default 200; one product costs about one PGS sweep; a cold
// pile of 1000 discs needs about 1650, scaled).
inline constexpr int iterative_products_per_search_iteration = 10;

struct IslandSolve {
    bool solved = true;    // false: the pivoting solver found no solution, or MPRGP found
                           // the problem unbounded (no solution either, mprgp.h)
    bool converged = true; // false: the sweep cap stopped the iterative solver
    double residual = 0.0; // the iterative solver's last residual
};

// Solves w = A lambda + q >= 0, lambda >= 0, lambda . w = 0 over problem.points
// (A = J M^-1 J^T at the bodies' current states) into problem.lambda, which
// holds the warm start on entry (the iterative solvers' first iterate, the
// pivoting solver's first active set).
// tolerance is the iterative solver's residual bound (a velocity);
// cap_factor multiplies the iterative solver's product cap (the overlap
// guard's problems take a larger one, overlap_guard.h).
IslandSolve solve_island(World& world, IslandProblem& problem, double tolerance,
                         int cap_factor = 1);

} // namespace impulse
