// The island solve's relaxing tolerance (island_lcp.h, RelaxingTolerance),
// which the holding step uses: an iterative solve goes to the tight residual
// within its budget of products and, if it is not there, on to the relaxed
// one. Read on a column of boxes, whose contact impulses physics gives: the
// contact under box k carries h g times the mass above it.
#include "island_lcp.h"
#include "support/contact_problems.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <vector>

using namespace impulse;
using namespace impulse::test::contact_problems;

namespace {

IslandProblem cold(const Problem& c) {
    IslandProblem problem;
    problem.points = c.points;
    problem.q = c.q;
    problem.lambda.assign(c.points.size(), 0.0);
    return problem;
}

// Every contact of the column within the error a residual `tolerance` allows:
// one residual per box at or below it (the contact under box k carries h g
// times the mass of boxes k and above).
void check_carries_the_column(const std::vector<double>& lambda, int boxes, double tolerance) {
    double carried = 0.0;
    double bound = 0.0;
    for (int k = boxes - 1; k >= 0; --k) {
        carried += graded_mass(k);
        bound += graded_mass(k) * (k + 1) * tolerance;
        const std::size_t i = 2 * static_cast<std::size_t>(k);
        INFO("box " << k);
        CHECK(std::fabs(lambda[i] + lambda[i + 1] - h * g * carried) <= bound);
    }
}

} // namespace

TEST_CASE("An island solve that misses the tight residual within its budget relaxes to the other",
          "[island-lcp]") {
    // The 50-box column needs a few hundred products to d / h cold
    // (test_mprgp.cpp); a residual of 1e-30 m/s is below the rounding of its
    // impulses (about 1e-16 of h g times the column's mass), so no number of
    // products reaches it: alone, the solve runs to the cap and is counted
    // unconverged. Relaxing to d / h after 50 products, it must stop there
    // converged, well within the cap, not counted unconverged, and carry the
    // column as d / h allows.
    const int boxes = 50;
    Problem c = column(boxes);
    const double relaxed = d / h;
    const RelaxingTolerance tolerance{1e-30, relaxed, 50};
    const long long cap = iterative_products_per_search_iteration *
                          static_cast<long long>(c.world.solver.max_search_iterations);

    IslandProblem fine = cold(c);
    const long long before_fine = c.world.work.solver_sweeps;
    REQUIRE_FALSE(solve_island(c.world, fine, tolerance.tight).converged);
    REQUIRE(c.world.work.solver_sweeps - before_fine >= cap);

    IslandProblem problem = cold(c);
    const long long unconverged = c.world.work.unconverged_islands;
    const long long before = c.world.work.solver_sweeps;
    const IslandSolve relaxing = solve_island(c.world, problem, tolerance);
    const long long products = c.world.work.solver_sweeps - before;
    CHECK(relaxing.converged);
    CHECK(relaxing.residual <= relaxed);
    CHECK(c.world.work.unconverged_islands == unconverged);
    CHECK(products > tolerance.relax_after);
    CHECK(products < cap / 2);
    check_carries_the_column(problem.lambda, boxes, relaxed);
}

TEST_CASE("An island solve that reaches the tight residual within its budget never relaxes",
          "[island-lcp]") {
    // The same column, solved to d / h with a budget one product above what
    // that takes and a relaxed residual a million times coarser: the answer
    // and the products are those of the tight solve alone, bit for bit. So
    // with a relaxed residual no coarser than the tight one, whatever the
    // budget (10 products here): nothing to relax to, the cap is the limit.
    Problem c = column(50);
    const double tight = d / h;
    IslandProblem alone = cold(c);
    const long long before_alone = c.world.work.solver_sweeps;
    REQUIRE(solve_island(c.world, alone, tight).converged);
    const long long products = c.world.work.solver_sweeps - before_alone;

    for (const RelaxingTolerance tolerance :
         {RelaxingTolerance{tight, tight * 1e6, static_cast<int>(products) + 1},
          RelaxingTolerance{tight, tight, 10}}) {
        IslandProblem problem = cold(c);
        const long long before = c.world.work.solver_sweeps;
        const IslandSolve solve = solve_island(c.world, problem, tolerance);
        INFO("relaxed " << tolerance.relaxed << ", budget " << tolerance.relax_after);
        CHECK(solve.converged);
        CHECK(c.world.work.solver_sweeps - before == products);
        CHECK(problem.lambda == alone.lambda);
    }
}
