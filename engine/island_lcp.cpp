#include "island_lcp.h"

#include "lcp.h"
#include "mprgp.h"
#include "pgs.h"

#include <algorithm>

namespace impulse {

namespace {

IslandSolve solve_directly(World& world, IslandProblem& problem) {
    const std::size_t n = problem.points.size();
    IslandSolve result;
    ++world.work.direct_solves;
    problem.A.resize(n * n);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i; j < n; ++j) {
            problem.A[i * n + j] = delassus(world, problem.points[i], problem.points[j]);
            problem.A[j * n + i] = problem.A[i * n + j];
        }
    }
    const LcpSolution solution = solve_lcp(problem.A, problem.q, {}, problem.lambda);
    result.solved = solution.solved;
    problem.lambda.assign(n, 0.0);
    if (solution.solved) {
        for (std::size_t i = 0; i < n; ++i) {
            problem.lambda[i] = solution.lambda[i];
        }
    }
    return result;
}

// Gauss-Seidel sweeps in the order of the points' heights against gravity,
// highest first (ties in the given order): a column's weight then travels down
// in one sweep and the alternate sweep carries the floor's answer back up
// (shock propagation, Guendelman 2003).
IslandSolve solve_iteratively(World& world, IslandProblem& p, double tolerance) {
    const std::size_t n = p.points.size();
    p.order.resize(n);
    p.height.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        p.order[i] = static_cast<int>(i);
        p.height[i] = -dot(world.gravity, p.points[i].contact.point);
    }
    std::sort(p.order.begin(), p.order.end(), [&](int x, int y) {
        const double hx = p.height[static_cast<std::size_t>(x)];
        const double hy = p.height[static_cast<std::size_t>(y)];
        return hx != hy ? hx > hy : x < y;
    });
    p.sorted_points.clear();
    p.sorted_q.clear();
    p.sorted_lambda.clear();
    for (const int i : p.order) {
        p.sorted_points.push_back(p.points[static_cast<std::size_t>(i)]);
        p.sorted_q.push_back(p.q[static_cast<std::size_t>(i)]);
        p.sorted_lambda.push_back(p.lambda[static_cast<std::size_t>(i)]);
    }
    PgsSettings settings;
    settings.tolerance = tolerance;
    settings.max_sweeps = world.solver.max_search_iterations;
    const PgsResult r =
        solve_pgs(world, p.sorted_points, p.sorted_q, p.sorted_lambda, settings, p.pgs);
    world.work.solver_sweeps += r.sweeps;
    if (!r.converged) {
        ++world.work.unconverged_islands;
    }
    for (std::size_t k = 0; k < n; ++k) {
        p.lambda[static_cast<std::size_t>(p.order[k])] = p.sorted_lambda[k];
    }
    IslandSolve result;
    result.converged = r.converged;
    result.residual = r.residual;
    return result;
}

// MPRGP (mprgp.h), warm started from problem.lambda: about sqrt(cond A)
// products where Gauss-Seidel needs about cond A sweeps, so a tall column
// converges cold within the cap and a settled pile in one product.
//
// An island of at most diagonal_scaling_points points is iterated unscaled,
// and there the unbounded test measures curvature against the bound on the
// whole of A: with masses spanning 1e12 in one island (a 1e12 kg disc among
// 1 to 10 kg ones, found by an outside review) the heavy disc's own
// directions are flatter than that bound's rounding, and a solvable holding
// problem was declared unbounded ("no solution"). Such an answer is tried
// once more, cold, with the diagonal scaled (unit diagonal: the heavy rows
// as curved as the light ones), and kept only if that converges; a problem
// with no solution stays so. Runs that were solved are untouched, bit for bit.
MprgpResult run_mprgp(World& world, IslandProblem& p, double tolerance, int max_products) {
    PgsSettings settings;
    settings.tolerance = tolerance;
    settings.max_sweeps = max_products;
    const MprgpResult r = solve_mprgp(world, p.points, p.q, p.lambda, settings, p.mprgp);
    world.work.solver_sweeps += r.sweeps;
    if (!r.unbounded || p.points.size() > diagonal_scaling_points) {
        return r;
    }
    p.scaled_lambda.assign(p.points.size(), 0.0);
    const MprgpResult scaled = solve_mprgp(world, p.points, p.q, p.scaled_lambda, settings, p.mprgp,
                                           MprgpScaling::diagonal);
    world.work.solver_sweeps += scaled.sweeps;
    ++world.work.unbounded_rescaled;
    if (!scaled.converged) {
        return r;
    }
    ++world.work.unbounded_rescaled_solved;
    p.lambda.swap(p.scaled_lambda);
    return scaled;
}

IslandSolve finish(World& world, const MprgpResult& r) {
    if (!r.converged) {
        ++world.work.unconverged_islands;
    }
    IslandSolve result;
    result.solved = !r.unbounded; // no solution, as the pivoting solver's failure says
    result.converged = r.converged;
    result.residual = r.residual;
    return result;
}

int product_cap(const World& world, int cap_factor) {
    return cap_factor * iterative_products_per_search_iteration *
           world.solver.max_search_iterations;
}

IslandSolve solve_by_mprgp(World& world, IslandProblem& p, double tolerance, int cap_factor) {
    return finish(world, run_mprgp(world, p, tolerance, product_cap(world, cap_factor)));
}

} // namespace

IslandSolve solve_island(World& world, IslandProblem& problem, double tolerance, int cap_factor) {
    if (problem.points.size() <= direct_solve_points) {
        const IslandSolve direct = solve_directly(world, problem);
        if (direct.solved) {
            return direct;
        }
        // Pivoting can cycle on a degenerate A (points of one manifold that
        // are redundant); MPRGP needs A only positive semidefinite.
        problem.lambda.assign(problem.points.size(), 0.0);
        return solve_by_mprgp(world, problem, tolerance, cap_factor);
    }
    if (iterative_solver == IterativeSolver::pgs) {
        return solve_iteratively(world, problem, tolerance);
    }
    return solve_by_mprgp(world, problem, tolerance, cap_factor);
}

} // namespace impulse
