// MPRGP (engine/mprgp.h) on problems with no solution: a slab pressed between
// two walls of opposite normals deeper than its slot makes the QP unbounded
// below, and MPRGP must say so (MprgpResult::unbounded) within a few
// products instead of running the impulses to infinity until its cap; and on
// problems that only look like it (a singular A, a slot exactly as thick as
// the slab, walls a milliradian from opposite) it must still solve.
#include "contact_problem.h"
#include "island_lcp.h"
#include "mprgp.h"
#include "support.h"
#include "support/contact_problems.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <random>
#include <vector>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::static_body;
using namespace impulse::test::contact_problems;

namespace {

// The island solver's default cap: 10 products per search iteration, 200.
constexpr int cap = iterative_products_per_search_iteration * 200;

constexpr double mass = 2.0;
constexpr double half = 0.1; // the slab's half thickness

// A 1 x 0.2 m slab (body 2) between a floor (body 0) and a ceiling (body 1)
// whose normals are exactly opposite, `into_floor` into the floor and
// `below_ceiling` under the ceiling (negative: into it). Its points are the
// slab's corners on each face (the floor's first), q_i = gap_i / h: the
// overlap guard's position problem. Translation only unless `turns`.
Problem wedged_slab(double into_floor, double below_ceiling, bool turns) {
    const double y = half - into_floor;
    Problem p{make_world({static_body(make_box(4.0, 0.5), {0.0, -0.5}),
                          static_body(make_box(2.0, 0.5), {0.0, y + half + below_ceiling + 0.5}),
                          dynamic_body(make_box(0.5, half), mass, {0.0, y}, 0.0, {}, 0.0, turns)},
                         {0.0, -g}, 0.0, SolverSettings{}),
              {},
              {}};
    for (const double x : {-0.5, 0.5}) {
        p.points.push_back(point_of(p.world, 2, 0, {x, 0.0}, {0.0, 1.0}));
        p.q.push_back(-into_floor / h);
    }
    for (const double x : {-0.5, 0.5}) {
        p.points.push_back(point_of(p.world, 2, 1, {x, y + half + below_ceiling}, {0.0, -1.0}));
        p.q.push_back(below_ceiling / h);
    }
    number_pairs(p);
    return p;
}

// Farkas' certificate that w = A l + q >= 0 has no l >= 0: y >= 0 with
// A y = 0 and q . y < 0 (then y . w = q . y < 0 for every l).
bool no_solution(const Problem& p, const std::vector<double>& y) {
    const std::vector<double> A = delassus_matrix(p.world, p.points);
    const std::vector<double> Ay = times(A, y);
    double qy = 0.0;
    double scale = 0.0; // A y's rounding: at most n eps max |A_ij| sum y, far below 1e-12 of it
    for (std::size_t i = 0; i < y.size(); ++i) {
        qy += p.q[i] * y[i];
        for (std::size_t j = 0; j < y.size(); ++j) {
            scale = std::max(scale, std::fabs(A[i * y.size() + j]) * y[j]);
        }
    }
    const auto null = [&](double v) {
        return std::fabs(v) <= 1e-12 * scale * static_cast<double>(y.size());
    };
    return std::all_of(Ay.begin(), Ay.end(), null) && qy < 0.0 &&
           std::all_of(y.begin(), y.end(), [](double v) { return v >= 0.0; });
}

bool all_finite(const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// The LCP's conditions on lambda, w from the dense A: lambda >= 0, w >= -tol,
// min(A_ii lambda_i, w_i) <= tol.
bool meets_lcp(const Problem& p, const std::vector<double>& lambda, double tolerance) {
    const std::vector<double> A = delassus_matrix(p.world, p.points);
    const std::vector<double> Al = times(A, lambda);
    const std::size_t n = lambda.size();
    for (std::size_t i = 0; i < n; ++i) {
        const double w = Al[i] + p.q[i];
        const double slack = tolerance * (1.0 + 1e-6);
        if (!(lambda[i] >= 0.0) || w < -slack || std::min(A[i * n + i] * lambda[i], w) > slack) {
            return false;
        }
    }
    return true;
}

} // namespace

TEST_CASE("MPRGP reports a slab pressed between opposite walls as unbounded, in a few products",
          "[mprgp]") {
    // 3 mm into the floor and 1 mm under the ceiling: any move out of the
    // floor takes it 2 mm into the ceiling. With the floor's points pushing
    // l_f and the ceiling's l_c, w_f + w_c = (g_f + g_c) / h = -2e-3 / h for
    // every impulse: no solution. Translation only: y = (1, 1, 1, 1).
    // Turning too: the corners are at the same x on both faces, so the
    // same y balances the torques as well.
    const double tolerance = d / h;
    for (const bool turns : {false, true}) {
        INFO((turns ? "turning" : "translation only"));
        const Problem p = wedged_slab(3e-3, 1e-3, turns);
        REQUIRE(no_solution(p, {1.0, 1.0, 1.0, 1.0}));
        std::vector<double> lambda;
        MprgpScratch scratch;
        const MprgpResult r =
            solve_mprgp(p.world, p.points, p.q, lambda, {tolerance, cap}, scratch);
        INFO(r.sweeps << " products, residual " << r.residual);
        CHECK(r.unbounded);
        CHECK_FALSE(r.converged);
        CHECK(r.sweeps < cap / 10); // not run to the cap
        CHECK(all_finite(lambda));
        CHECK(std::isfinite(r.residual));
        CHECK(r.residual > tolerance);
        CHECK(all_clear(scratch));

        // The island solver (pivoting first, MPRGP its fallback) calls it
        // unsolved, as the callers read a pivoting failure.
        IslandProblem island;
        island.points = p.points;
        island.q = p.q;
        World world = p.world;
        const IslandSolve solve = solve_island(world, island, tolerance);
        CHECK_FALSE(solve.solved);
        CHECK_FALSE(solve.converged);
        CHECK(all_finite(island.lambda));
        CHECK(world.work.solver_sweeps < cap / 10);
    }
}

TEST_CASE("MPRGP still solves a singular A: two equal rows, a slot as thick as the slab, walls "
          "a milliradian from opposite",
          "[mprgp]") {
    const double tolerance = d / h;
    MprgpScratch scratch;

    SECTION("two equal rows: a box on the floor, translation only, falling at g h") {
        // The two corners' rows are equal (y = (1, -1) is A's null space, not
        // a ray of impulses that only rise). Physics: the floor stops the
        // box, l_1 + l_2 = m g h, each corner's w = 0.
        Problem p{make_world({static_body(make_box(2.0, 0.5), {0.0, -0.5}),
                              dynamic_body(make_box(0.5, half), mass, {0.0, half}, 0.0,
                                           {0.0, -g * h}, 0.0, false)},
                             {0.0, -g}, 0.0, SolverSettings{}),
                  {},
                  {}};
        for (const double x : {-0.5, 0.5}) {
            p.points.push_back(point_of(p.world, 1, 0, {x, 0.0}, {0.0, 1.0}));
            p.q.push_back(p.points.back().vn);
        }
        number_pairs(p);
        REQUIRE(p.q[0] == -(g * h));
        const std::vector<double> A = delassus_matrix(p.world, p.points);
        REQUIRE(A[0] == A[1]); // singular: equal rows
        REQUIRE(A[2] == A[3]);
        std::vector<double> lambda;
        const MprgpResult r =
            solve_mprgp(p.world, p.points, p.q, lambda, {tolerance, cap}, scratch);
        INFO(r.sweeps << " products");
        CHECK_FALSE(r.unbounded);
        CHECK(r.converged);
        CHECK(r.residual <= tolerance);
        CHECK(meets_lcp(p, lambda, tolerance));
        CHECK(std::fabs(lambda[0] + lambda[1] - mass * g * h) <= mass * tolerance);
    }

    SECTION("a slot exactly as thick as the slab, started far along the null ray") {
        // 2 mm into the floor and 2 mm clear of the ceiling: g_f + g_c = 0, so
        // the ray y = (1, 1, 1, 1) with A y = 0 is flat (q . y = 0), and every
        // lambda + t y of a solution is one. Started at 1000 N s on every
        // point, well out along that ray. Physics: the floor's impulses exceed
        // the ceiling's by m * 2 mm / h (the slab moves up by 2 mm in a step),
        // and no w is negative.
        const Problem p = wedged_slab(2e-3, 2e-3, false);
        std::vector<double> lambda(4, 1000.0);
        const MprgpResult r =
            solve_mprgp(p.world, p.points, p.q, lambda, {tolerance, cap}, scratch);
        INFO(r.sweeps << " products");
        CHECK_FALSE(r.unbounded);
        CHECK(r.converged);
        CHECK(meets_lcp(p, lambda, tolerance));
        const double lift = lambda[0] + lambda[1] - lambda[2] - lambda[3];
        CHECK(std::fabs(lift - mass * 2e-3 / h) <= 2.0 * mass * tolerance);
    }

    SECTION("walls a milliradian from opposite: the slab slides out sideways") {
        // The ceiling's normal turned by theta = 1e-3 rad: A y = 0 no longer
        // holds (its curvature along y is about theta^2 / m, far above
        // rounding), and pushing the slab along the ceiling frees it. Both
        // points at w = 0 (translation only, one point per wall):
        // dv_y = -g_f / h, sin(theta) dv_x = (-g_c - cos(theta) g_f) / h, and
        // m dv = l_f n_f + l_c n_c gives l_c = m dv_x / sin(theta),
        // l_f = m dv_y + l_c cos(theta): a large impulse, but a solution.
        const double theta = 1e-3;
        const double g_f = -3e-3;
        const double g_c = 1e-3;
        Problem p{make_world({static_body(make_box(2.0, 0.5), {0.0, -0.5}),
                              static_body(make_box(2.0, 0.5), {0.0, 5.0}),
                              dynamic_body(make_box(0.5, half), mass, {0.0, half + g_f}, 0.0, {},
                                           0.0, false)},
                             {0.0, -g}, 0.0, SolverSettings{}),
                  {},
                  {}};
        p.points.push_back(point_of(p.world, 2, 0, {0.0, 0.0}, {0.0, 1.0}));
        p.q.push_back(g_f / h);
        p.points.push_back(
            point_of(p.world, 2, 1, {0.0, 2.0 * half}, {std::sin(theta), -std::cos(theta)}));
        p.q.push_back(g_c / h);
        number_pairs(p);
        std::vector<double> lambda;
        const MprgpResult r =
            solve_mprgp(p.world, p.points, p.q, lambda, {tolerance, cap}, scratch);
        INFO(r.sweeps << " products");
        CHECK_FALSE(r.unbounded);
        CHECK(r.converged);
        CHECK(meets_lcp(p, lambda, tolerance));
        const double dv_x = (-g_c - std::cos(theta) * g_f) / (h * std::sin(theta));
        const double l_c = mass * dv_x / std::sin(theta);
        const double l_f = mass * (-g_f / h) + l_c * std::cos(theta);
        CHECK(lambda[1] == Approx(l_c).epsilon(1e-6));
        CHECK(lambda[0] == Approx(l_f).epsilon(1e-6));
    }
    CHECK(all_clear(scratch));
}

TEST_CASE("MPRGP finds the unbounded ray once an unrelated point has left the free set",
          "[mprgp]") {
    // The wedged slab of the first test, translation only, and a disc on the
    // floor beside it (under no ceiling) moving up at 1 m/s (q = +1 m/s: it
    // separates, its impulse must go to 0). Warm started with every impulse
    // at 1 N s: the first direction lowers the ceiling's and the disc's
    // impulses, and no direction is a ray of rising impulses until the
    // disc's impulse has reached 0 and left the free set. Physics: the disc's answer is 0 and
    // the slab's problem has no solution (y = (1, 1, 1, 1, 0)).
    const double tolerance = d / h;
    Problem p = wedged_slab(3e-3, 1e-3, false);
    p.world = make_world({p.world.bodies[0], p.world.bodies[1], p.world.bodies[2],
                          dynamic_body(make_circle(0.2), 1.0, {3.0, 0.2}, 0.0, {0.0, 1.0})},
                         {0.0, -g}, 0.0, SolverSettings{});
    p.points.push_back(point_of(p.world, 3, 0, {3.0, 0.0}, {0.0, 1.0}));
    p.q.push_back(p.points.back().vn);
    number_pairs(p);
    REQUIRE(p.q[4] == 1.0);
    REQUIRE(no_solution(p, {1.0, 1.0, 1.0, 1.0, 0.0}));
    std::vector<double> lambda(5, 1.0);
    MprgpScratch scratch;
    const MprgpResult r = solve_mprgp(p.world, p.points, p.q, lambda, {tolerance, cap}, scratch);
    INFO(r.sweeps << " products, residual " << r.residual);
    CHECK(r.unbounded);
    CHECK_FALSE(r.converged);
    CHECK(r.sweeps < cap / 10);
    CHECK(all_finite(lambda));
    CHECK(lambda[4] == 0.0); // the disc's point left before the ray was found
    CHECK(all_clear(scratch));
}

TEST_CASE("MPRGP reports unbounded on 200 random problems with a wedged slab added", "[mprgp]") {
    // Each random problem of test_mprgp.cpp (solvable alone) gains a slab
    // between two static walls of opposite normals at a random angle, 1 to
    // 3 corner pairs each on one line along the normal (so the pairs'
    // forces balance and so do their torques, turning or not), and a point
    // or two against the problem's other bodies. The slab is g_f < 0 into
    // one wall and g_c < -g_f / 2 clear of the other: y = 1 on the wall
    // points is Farkas' certificate (A y = 0, q . y = (g_f + g_c) n_pairs / h
    // < 0), whatever the rest of the problem does.
    std::mt19937_64 rng(14019);
    const double tolerance = d / h;
    MprgpScratch scratch;
    int most = 0;
    for (int trial = 0; trial < 200; ++trial) {
        Problem p = random_problem(rng);
        const double angle = impulse::test::uniform(rng, 0.0, 6.283185307179586);
        const Vec2 n{std::cos(angle), std::sin(angle)};
        const Vec2 c{impulse::test::uniform(rng, -2.0, 2.0), impulse::test::uniform(rng, 3.0, 5.0)};
        const bool turns = rng() % 2 == 0;
        std::vector<Body> bodies = p.world.bodies;
        const int first = static_cast<int>(bodies.size());
        bodies.push_back(static_body(make_box(0.5, 0.5), c - 0.6 * n));
        bodies.push_back(static_body(make_box(0.5, 0.5), c + 0.6 * n));
        bodies.push_back(dynamic_body(make_box(0.3, 0.1),
                                      impulse::test::log_uniform(rng, 0.1, 10.0), c, angle, {}, 0.0,
                                      turns));
        const int slab = first + 2;
        p.world = make_world(bodies, {0.0, -g}, 0.0, SolverSettings{});
        const double g_f = -impulse::test::uniform(rng, 1e-4, 5e-3);
        const double g_c = impulse::test::uniform(rng, 0.0, -0.5 * g_f);
        const int pairs = 1 + static_cast<int>(rng() % 3);
        std::vector<double> y(p.points.size(), 0.0);
        for (int k = 0; k < pairs; ++k) {
            const Vec2 P = c + impulse::test::uniform(rng, -0.3, 0.3) * perp(n);
            p.points.push_back(point_of(p.world, slab, first, P - 0.1 * n, n));
            p.q.push_back(g_f / h);
            p.points.push_back(point_of(p.world, slab, first + 1, P + 0.1 * n, -1.0 * n));
            p.q.push_back(g_c / h);
            y.insert(y.end(), {1.0, 1.0});
        }
        for (int k = static_cast<int>(rng() % 3); k > 0; --k) {
            const int other = 1 + static_cast<int>(rng() % static_cast<unsigned>(first - 1));
            p.points.push_back(point_of(p.world, std::min(slab, other), std::max(slab, other),
                                        c + Vec2{impulse::test::uniform(rng, -0.3, 0.3), 0.0},
                                        perp(n)));
            p.q.push_back(impulse::test::uniform(rng, -1.0, 1.0));
            y.push_back(0.0);
        }
        number_pairs(p);
        INFO("trial " << trial << ", " << p.points.size() << " points");
        REQUIRE(no_solution(p, y));
        std::vector<double> lambda;
        if (trial % 2 == 0) {
            for (std::size_t i = 0; i < p.points.size(); ++i) {
                lambda.push_back(impulse::test::uniform(rng, -0.5, 1.0));
            }
        }
        const MprgpResult r =
            solve_mprgp(p.world, p.points, p.q, lambda, {tolerance, cap}, scratch);
        INFO(r.sweeps << " products");
        CHECK(r.unbounded); // within the cap: not run to it
        CHECK_FALSE(r.converged);
        CHECK(all_finite(lambda));
        most = std::max(most, r.sweeps);
    }
    std::printf("MPRGP, 200 random unbounded problems: at most %d products\n", most);
    CHECK(all_clear(scratch));
}
