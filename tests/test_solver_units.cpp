// The island solvers are unit-free: masses times c give the same relative
// normal velocities w and impulses times c (A = J M^-1 J^T scales by 1/c, so
// lambda = c lambda solves w = A lambda + q with the same w). Found by an
// outside review: a pile of density 1e200 stopped with "no solution", a 2 x 2
// block's products underflowing to 0 in the pivoting solver; the solvers now
// work in a power-of-two unit of impulse (lcp.cpp, mprgp.cpp), which for c a
// power of two must give the same bits times c.
#include "contact_problem.h"
#include "lcp.h"
#include "mprgp.h"
#include "support/contact_problems.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

using namespace impulse;
using namespace impulse::test::contact_problems;

namespace {

// Every dynamic body's mass and moment of inertia times c.
Problem heavier(Problem p, double c) {
    for (Body& body : p.world.bodies) {
        body.inv_mass /= c;
        body.inv_inertia /= c;
    }
    return p;
}

std::vector<double> velocities(const Problem& p, const std::vector<double>& lambda) {
    std::vector<double> w = times(delassus_matrix(p.world, p.points), lambda);
    for (std::size_t i = 0; i < w.size(); ++i) {
        w[i] += p.q[i];
    }
    return w;
}

std::vector<double> by_mprgp(const Problem& p, double tolerance) {
    std::vector<double> lambda;
    MprgpScratch scratch;
    const PgsResult r = solve_mprgp(p.world, p.points, p.q, lambda, {tolerance, 100000}, scratch);
    REQUIRE(r.converged);
    return lambda;
}

} // namespace

TEST_CASE("The pivoting solver is unit-free: masses times 1e200 or 1e-200 keep w, impulses "
          "scale",
          "[unit][lcp][solver-units]") {
    std::mt19937_64 rng(20261125);
    for (int trial = 0; trial < 100; ++trial) {
        const Problem p = random_problem(rng);
        const LcpSolution base = solve_lcp(delassus_matrix(p.world, p.points), p.q);
        REQUIRE(base.solved);
        for (const double c : {1e200, 1e-200}) {
            INFO("trial " << trial << ", masses times " << c);
            const Problem scaled = heavier(p, c);
            const LcpSolution s = solve_lcp(delassus_matrix(scaled.world, scaled.points), p.q);
            REQUIRE(s.solved);
            // w is unique; lambda is when A is not singular, so only w is
            // compared, at the solver's own tolerance of 1e-9 max |q|.
            double largest = 0.0;
            for (const double q : p.q) {
                largest = std::max(largest, std::fabs(q));
            }
            for (std::size_t i = 0; i < p.q.size(); ++i) {
                CHECK(std::isfinite(s.lambda[i]));
                CHECK(std::fabs(s.w[i] - base.w[i]) <= 1e-8 * largest);
            }
        }
    }
}

TEST_CASE("Masses times a power of two give the same impulses times it, bit for bit",
          "[unit][lcp][mprgp][solver-units]") {
    const double c = std::ldexp(1.0, 600);
    std::mt19937_64 rng(25);
    for (int trial = 0; trial < 50; ++trial) {
        INFO("trial " << trial);
        const Problem p = random_problem(rng);
        const Problem scaled = heavier(p, c);
        const LcpSolution base = solve_lcp(delassus_matrix(p.world, p.points), p.q);
        const LcpSolution s = solve_lcp(delassus_matrix(scaled.world, scaled.points), p.q);
        REQUIRE(base.solved == s.solved);
        for (std::size_t i = 0; i < s.lambda.size(); ++i) {
            CHECK(s.lambda[i] == c * base.lambda[i]);
        }
        const std::vector<double> iterated = by_mprgp(p, d / h);
        const std::vector<double> iterated_scaled = by_mprgp(scaled, d / h);
        for (std::size_t i = 0; i < iterated.size(); ++i) {
            CHECK(iterated_scaled[i] == c * iterated[i]);
        }
    }
}

TEST_CASE("MPRGP carries a column of boxes of 1e200 kg: each contact carries the weight above",
          "[unit][mprgp][solver-units]") {
    // The contact under box k carries h g times the mass of boxes k and up;
    // a residual r bounds box k's velocity by (k + 1) r (test_mprgp.cpp).
    const double c = 1e200;
    for (const int boxes : {8, 50}) { // 16 points (unscaled) and 100
        INFO(boxes << " boxes");
        const Problem column_of = heavier(column(boxes), c);
        const double tolerance = d / h;
        const std::vector<double> lambda = by_mprgp(column_of, tolerance);
        double carried = 0.0;
        double bound = 0.0;
        for (int k = boxes - 1; k >= 0; --k) {
            carried += c * graded_mass(k);
            bound += c * graded_mass(k) * (k + 1) * tolerance;
            const std::size_t i = 2 * static_cast<std::size_t>(k);
            CHECK(std::fabs(lambda[i] + lambda[i + 1] - h * g * carried) <= bound);
        }
        const std::vector<double> w = velocities(column_of, lambda);
        for (const double v : w) {
            CHECK(v >= -tolerance * (1.0 + 1e-6));
        }
    }
}
