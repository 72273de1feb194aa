// Principal pivoting started from a guessed active set (lcp.h, `warm`): the
// time-stepping islands of at most direct_solve_points points start from the
// points that pushed in the step before. For a P-matrix the LCP has one
// solution whatever set the pivoting starts from, and the impulses are the
// solve of the final set's block, so a guess changes only how many block
// solves are made: the right set, no pivot at all.
#include "lcp.h"
#include "support/contact_problems.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

using namespace impulse;
using namespace impulse::test::contact_problems;

TEST_CASE("A warm guess of the active set: the same answer, fewer pivots", "[unit][lcp]") {
    // The three-ball cradle's problem: [[2, -1], [-1, 2]], q = (-2, 0). Started
    // from the approaching point 0 alone (lambda 1), w_1 = -1 pulls point 1
    // in: one pivot to lambda = (4/3, 2/3).
    const std::vector<double> A = row_major({{2, -1}, {-1, 2}});
    const std::vector<double> q{-2, 0};
    const LcpSolution cold = solve_lcp(A, q);
    REQUIRE(cold.solved);
    CHECK(cold.pivots == 1);

    SECTION("the answer's own active set: no pivot, the same bits") {
        const LcpSolution warm = solve_lcp(A, q, {}, cold.lambda);
        REQUIRE(warm.solved);
        CHECK(warm.pivots == 0);
        CHECK(warm.lambda == cold.lambda);
        CHECK(warm.w == cold.w);
    }
    SECTION("a point that pushed before but now separates is dropped") {
        // q > 0 everywhere: the guess (point 0 active) is wrong; lambda = 0, w = q.
        const LcpSolution warm = solve_lcp(A, {3.0, 2.0}, {}, {5.0, 0.0});
        REQUIRE(warm.solved);
        CHECK(warm.pivots == 1);
        CHECK(warm.lambda == std::vector<double>{0.0, 0.0});
        CHECK(warm.w == std::vector<double>{3.0, 2.0});
    }
}

TEST_CASE("Warm and cold pivoting agree on random contact problems", "[unit][lcp]") {
    // Random Delassus problems (boxes over a floor, up to 10 points): w is
    // unique for every LCP with A positive semidefinite (the velocity closest
    // to the start in M's norm), so a warm solve's w must be the cold one's,
    // from any guess. Started from the cold answer, the pivoting starts from
    // its active set and every approaching point (lcp.h): where those are
    // the same set, no pivot and the same bits.
    std::mt19937_64 rng(20261126);
    int solved = 0;
    int from_answer = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const Problem p = random_problem(rng);
        const std::vector<double> A = delassus_matrix(p.world, p.points);
        const LcpSolution cold = solve_lcp(A, p.q);
        if (!cold.solved) {
            continue;
        }
        ++solved;
        INFO("trial " << trial << ", " << p.points.size() << " points");
        double scale = 0.0;
        for (const double v : p.q) {
            scale = std::max(scale, std::fabs(v));
        }
        std::vector<double> guess(p.points.size());
        for (double& entry : guess) {
            entry = rng() % 2 == 0 ? 0.0 : 1.0;
        }
        for (const std::vector<double>& start : {cold.lambda, guess}) {
            const LcpSolution warm = solve_lcp(A, p.q, {}, start);
            REQUIRE(warm.solved);
            for (std::size_t i = 0; i < p.points.size(); ++i) {
                CHECK(std::fabs(warm.w[i] - cold.w[i]) <= 1e-9 * scale);
            }
        }
        const LcpSolution again = solve_lcp(A, p.q, {}, cold.lambda);
        bool covers = true; // the answer's set holds every approaching point
        for (std::size_t i = 0; i < p.points.size(); ++i) {
            covers = covers && (p.q[i] >= 0.0 || cold.lambda[i] > 0.0);
        }
        if (covers && cold.enumerated == 0) {
            ++from_answer;
            CHECK(again.pivots == 0);
            CHECK(again.lambda == cold.lambda);
        }
    }
    CHECK(solved >= 250);
    CHECK(from_answer >= 100);
}
