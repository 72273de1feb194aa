// Projected Gauss-Seidel (engine/pgs.h) against the LCP's own conditions, the
// pivoting solver (lcp.h) and answers from physics: a column of boxes carried
// by the floor, a single point, a settled pile.
#include "lcp.h"
#include "pgs.h"
#include "restitution.h"
#include "support.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <random>
#include <vector>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::log_uniform;
using impulse::test::static_body;
using impulse::test::uniform;

namespace {

constexpr double g = 9.81;
constexpr double h = 1.0 / 60.0;
constexpr double d = 1e-9; // the default contact tolerance

// The point P of bodies i and k with its normal n pointing toward i, as the
// world's pair orders them, with vn from the bodies' current velocities.
ContactPoint point_between(const World& world, int i, int k, Vec2 P, Vec2 n_toward_i) {
    const Pair want = pair_of(world, i, k);
    int index = 0;
    while (world.pairs[static_cast<std::size_t>(index)].a != want.a ||
           world.pairs[static_cast<std::size_t>(index)].b != want.b) {
        ++index;
    }
    const Vec2 n = want.a == i ? n_toward_i : -1.0 * n_toward_i;
    const Contact contact{P, n, 0.0};
    const Body& a = world.bodies[static_cast<std::size_t>(want.a)];
    const Body& b = world.bodies[static_cast<std::size_t>(want.b)];
    return contact_point(world, index, contact, relative_normal_velocity(a, b, P, n));
}

std::vector<double> times(const std::vector<double>& A, const std::vector<double>& x) {
    const std::size_t n = x.size();
    std::vector<double> y(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = 0; k < n; ++k) {
            y[i] += A[i * n + k] * x[k];
        }
    }
    return y;
}

// A column of `count` unit boxes (masses 1 + 0.1 k) on a static floor (body
// 0), each at rest and then kicked by one step of gravity. Points bottom-up:
// the floor's two corners, then each box on the one below.
struct Column {
    World world;
    std::vector<ContactPoint> points;
    std::vector<double> q;
};

Column column(int count) {
    std::vector<Body> bodies{static_body(make_box(5.0, 0.5), {0.0, -0.5})};
    for (int k = 0; k < count; ++k) {
        bodies.push_back(
            dynamic_body(make_box(0.5, 0.5), 1.0 + 0.1 * k, {0.0, 0.5 + k}, 0.0, {0.0, -g * h}));
    }
    Column c{make_world(bodies, {0.0, -g}, 0.0, SolverSettings{}), {}, {}};
    for (int k = 0; k < count; ++k) {
        for (const double x : {-0.5, 0.5}) {
            c.points.push_back(
                point_between(c.world, k + 1, k, {x, static_cast<double>(k)}, {0.0, 1.0}));
        }
    }
    for (const ContactPoint& p : c.points) {
        c.q.push_back(p.vn); // the relative velocity gravity's kick gives: -g h on the floor
    }
    return c;
}

bool all_clear(const PgsScratch& s) {
    return std::all_of(s.local_of_body.begin(), s.local_of_body.end(),
                       [](int slot) { return slot == -1; });
}

} // namespace

TEST_CASE("a single point gets lambda = -q / A exactly", "[pgs]") {
    World world = make_world({dynamic_body(make_circle(0.3), 2.0, {0.0, 0.3}, 0.0, {0.0, -g * h}),
                              static_body(make_box(5.0, 0.5), {0.0, -0.5})},
                             {0.0, -g}, 0.0, SolverSettings{});
    const std::vector<ContactPoint> points{point_between(world, 0, 1, {0.0, 0.0}, {0.0, 1.0})};
    const std::vector<double> q{points[0].vn};
    REQUIRE(q[0] == -(g * h)); // from the velocity given
    std::vector<double> lambda;
    PgsScratch scratch;
    const PgsResult r = solve_pgs(world, points, q, lambda, {1e-12, 10}, scratch);
    CHECK(r.converged);
    CHECK(r.sweeps == 1);
    REQUIRE(lambda.size() == 1);
    CHECK(lambda[0] == -q[0] / delassus(world, points[0], points[0]));
    CHECK(lambda[0] == Approx(2.0 * g * h).epsilon(1e-15)); // m g h: the disc stops
    CHECK(all_clear(scratch));
    CHECK(scratch.local_of_body.size() >= world.bodies.size());
}

TEST_CASE("PGS meets the LCP conditions on 200 random Delassus problems", "[pgs]") {
    std::mt19937_64 rng(20261124);
    const double tolerance = 1e-8;
    for (int trial = 0; trial < 200; ++trial) {
        // 2-5 bodies (body 0 static), random masses, some not rotating, random
        // velocities; 1-10 points between random pairs at random places.
        const int n_bodies = 2 + static_cast<int>(rng() % 4);
        std::vector<Body> bodies{static_body(make_box(5.0, 0.5), {0.0, -0.5})};
        for (int i = 1; i < n_bodies; ++i) {
            const Vec2 at{uniform(rng, -2.0, 2.0), uniform(rng, 0.0, 2.0)};
            const Vec2 v{uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0)};
            bodies.push_back(dynamic_body(make_box(uniform(rng, 0.1, 0.5), uniform(rng, 0.1, 0.5)),
                                          log_uniform(rng, 0.1, 10.0), at, 0.0, v,
                                          uniform(rng, -1.0, 1.0), rng() % 4 != 0));
        }
        World world = make_world(bodies, {0.0, -g}, 0.0, SolverSettings{});
        std::vector<ContactPoint> points;
        std::vector<double> q;
        // A pair's points share its normal, as every manifold's do (manifold.h);
        // 1-10 points on random pairs at random places.
        std::vector<double> normal_of(world.pairs.size());
        for (double& angle : normal_of) {
            angle = uniform(rng, 0.0, 6.283185307179586);
        }
        const int n_points = 1 + static_cast<int>(rng() % 10);
        for (int p = 0; p < n_points; ++p) {
            const std::size_t k = rng() % world.pairs.size();
            const Pair pair = world.pairs[k];
            const Vec2 P{uniform(rng, -2.0, 2.0), uniform(rng, -0.5, 2.0)};
            points.push_back(point_between(world, pair.a, pair.b, P,
                                           {std::cos(normal_of[k]), std::sin(normal_of[k])}));
            // q = J v + a gap's worth (>= 0): v = 0 is feasible, so a solution exists.
            q.push_back(points.back().vn + (rng() % 2 == 0 ? 0.0 : uniform(rng, 0.0, 0.5)));
        }
        std::vector<double> lambda;
        PgsScratch scratch;
        const PgsResult r = solve_pgs(world, points, q, lambda, {tolerance, 100000}, scratch);
        INFO("trial " << trial << ", " << points.size() << " points, " << r.sweeps << " sweeps");
        REQUIRE(r.converged);
        CHECK(all_clear(scratch));

        // The conditions, with the dense matrix (rounding allowed on top of the tolerance).
        const std::vector<double> A = delassus_matrix(world, points);
        std::vector<double> w = times(A, lambda);
        const std::size_t n = points.size();
        for (std::size_t i = 0; i < n; ++i) {
            w[i] += q[i];
            CHECK(lambda[i] >= 0.0);
            CHECK(w[i] >= -tolerance * (1.0 + 1e-6));
            CHECK(std::min(A[i * n + i] * lambda[i], w[i]) <= tolerance * (1.0 + 1e-6));
        }
        // w is unique (J v of the one velocity closest to the start in M's
        // norm with J v >= 0), so the pivoting solver's must agree.
        const LcpSolution exact = solve_lcp(A, q);
        REQUIRE(exact.solved);
        for (std::size_t i = 0; i < n; ++i) {
            CHECK(std::fabs(w[i] - exact.w[i]) <= 10.0 * tolerance);
        }
    }
}

TEST_CASE("a column of 50 boxes converges cold; warm from its answer, one sweep", "[pgs]") {
    // Physics: every box ends at rest, so the impulse through the contact
    // under box k is h g (the mass of boxes k and up). A residual r bounds
    // each contact's relative velocity by r, so box k's by (k + 1) r.
    // Cold, either order takes tens of thousands of sweeps (34 857 bottom-up,
    // 34 858 top-down; "[pgs-measure]" prints them): only the floor's points
    // start approaching, and each Gauss-Seidel update shares a push between
    // two neighbours only, so the floor's push diffuses up the column: the
    // error shrinks per sweep by about 1 - c / n^2. No order makes a cold column converge in a
    // handful of sweeps; a warm start does (below), which is what a resting pile has.
    const double tolerance = d / h;
    Column c = column(50);
    for (const bool bottom_up : {true, false}) {
        std::vector<ContactPoint> points = c.points;
        std::vector<double> q = c.q;
        if (!bottom_up) {
            std::reverse(points.begin(), points.end());
            std::reverse(q.begin(), q.end());
        }
        std::vector<double> lambda;
        PgsScratch scratch;
        const PgsResult r = solve_pgs(c.world, points, q, lambda, {tolerance, 1000000}, scratch);
        INFO((bottom_up ? "bottom-up: " : "top-down: ") << r.sweeps << " sweeps");
        REQUIRE(r.converged);
        CHECK(r.residual <= tolerance);
        if (!bottom_up) {
            std::reverse(lambda.begin(), lambda.end());
        }
        double carried = 0.0; // the mass above, the top box first
        double bound = 0.0;
        for (int k = 49; k >= 0; --k) {
            carried += 1.0 + 0.1 * k;
            bound += (1.0 + 0.1 * k) * (k + 1) * tolerance;
            const double impulse = lambda[2 * static_cast<std::size_t>(k)] +
                                   lambda[2 * static_cast<std::size_t>(k) + 1];
            CHECK(std::fabs(impulse - h * g * carried) <= bound);
        }

        // Warm started from the answer physics gives (each corner under box k
        // carries half of h g times the mass above; the column is symmetric),
        // the first sweep already meets the tolerance.
        std::vector<double> answer(points.size());
        double above = 0.0;
        for (int k = 49; k >= 0; --k) {
            above += 1.0 + 0.1 * k;
            answer[2 * static_cast<std::size_t>(k)] = 0.5 * h * g * above;
            answer[2 * static_cast<std::size_t>(k) + 1] = 0.5 * h * g * above;
        }
        if (!bottom_up) {
            std::reverse(answer.begin(), answer.end());
        }
        const PgsResult warm = solve_pgs(c.world, points, q, answer, {tolerance, 1000}, scratch);
        CHECK(warm.converged);
        CHECK(warm.sweeps == 1);
        CHECK(all_clear(scratch));
    }
}

namespace {

// A settled pile: 1000 equal discs (r = 0.1, m = 1) in a triangular packing,
// rows of 40 and 39 alternating, on a static floor between static walls that
// touch the long rows' end discs. Every touching pair is a point (gap 0); q is
// the relative velocity one step of gravity gives (so only the floor's points
// start approaching), as the holding problem of a pile at rest.
struct Pile {
    World world;
    std::vector<ContactPoint> points;
    std::vector<double> q;
};

ContactPoint pile_point(const World& world, int pair, int a, int b, Vec2 P, Vec2 n) {
    const Body& ba = world.bodies[static_cast<std::size_t>(a)];
    const Body& bb = world.bodies[static_cast<std::size_t>(b)];
    ContactPoint p{pair, a, b, {P, n, 0.0}, 0.0, 0.0, 0.0};
    p.rn_a = dot(perp(P - ba.state.position), n);
    p.rn_b = dot(perp(P - bb.state.position), n);
    p.vn = relative_normal_velocity(ba, bb, P, n);
    return p;
}

Pile settled_pile(int count) {
    const double r = 0.1;
    const double rise = r * std::sqrt(3.0);
    Pile pile;
    std::vector<Body>& bodies = pile.world.bodies;
    bodies.push_back(static_body(make_box(10.0, 0.5), {0.0, -0.5}));           // floor
    bodies.push_back(static_body(make_box(0.5, 10.0), {-0.5 - r, 0.0}));       // left wall
    bodies.push_back(static_body(make_box(0.5, 10.0), {79.0 * r + 0.5, 0.0})); // right wall
    for (int k = 0; bodies.size() < static_cast<std::size_t>(count) + 3; ++k) {
        const int row = k / 79;
        const int in_pair = k % 79; // 0..39 a long row, 40..78 the short row above it
        const bool long_row = in_pair < 40;
        const int column = long_row ? in_pair : in_pair - 40;
        const double x = 2.0 * r * column + (long_row ? 0.0 : r);
        const double y = r + rise * (2 * row + (long_row ? 0 : 1));
        bodies.push_back(dynamic_body(make_circle(r), 1.0, {x, y}, 0.0, {0.0, -g * h}));
    }
    int pair = 0;
    const int n = static_cast<int>(bodies.size());
    for (int a = 3; a < n; ++a) {
        const Vec2 pa = bodies[static_cast<std::size_t>(a)].state.position;
        if (pa.y == r) {
            pile.points.push_back(
                pile_point(pile.world, pair++, a, 0, pa - Vec2{0.0, r}, {0.0, 1.0}));
        }
        if (pa.x == 0.0) {
            pile.points.push_back(
                pile_point(pile.world, pair++, a, 1, pa - Vec2{r, 0.0}, {1.0, 0.0}));
        }
        if (pa.x == 78.0 * r) {
            pile.points.push_back(
                pile_point(pile.world, pair++, a, 2, pa + Vec2{r, 0.0}, {-1.0, 0.0}));
        }
        for (int b = a + 1; b < n; ++b) {
            const Vec2 pb = bodies[static_cast<std::size_t>(b)].state.position;
            const Vec2 between = pa - pb;
            if (length(between) < 2.0 * r * (1.0 + 1e-9)) {
                const Vec2 normal = (1.0 / length(between)) * between;
                pile.points.push_back(
                    pile_point(pile.world, pair++, a, b, 0.5 * (pa + pb), normal));
            }
        }
    }
    for (const ContactPoint& p : pile.points) {
        pile.q.push_back(p.vn);
    }
    return pile;
}

} // namespace

TEST_CASE("a settled pile of 1000 discs converges to d/h, and warm in one sweep", "[pgs]") {
    // Physics: the pile ends at rest, so the floor carries the whole weight:
    // the floor's impulses add up to 1000 m g h (within what the residual
    // bound lets the velocities differ, one r per contact up 25 rows).
    const double tolerance = d / h;
    const Pile pile = settled_pile(1000);
    std::vector<double> lambda;
    PgsScratch scratch;
    const PgsResult cold =
        solve_pgs(pile.world, pile.points, pile.q, lambda, {tolerance, 1000000}, scratch);
    INFO(pile.points.size() << " points, cold " << cold.sweeps << " sweeps");
    REQUIRE(cold.converged);
    double floor_impulse = 0.0;
    for (std::size_t i = 0; i < pile.points.size(); ++i) {
        if (pile.points[i].b == 0) {
            floor_impulse += lambda[i];
        }
    }
    CHECK(std::fabs(floor_impulse - 1000.0 * g * h) <= 1000.0 * 26.0 * tolerance);
    const PgsResult warm =
        solve_pgs(pile.world, pile.points, pile.q, lambda, {tolerance, 1000000}, scratch);
    CHECK(warm.converged);
    CHECK(warm.sweeps == 1);
}

namespace {

// A random pile-like problem: `count` discs (radii 0.05-0.25, density 1, so
// masses 1:25) dropped one by one at random x between walls 8 m apart, each
// stopping where it first touches the floor or a disc below (random
// sequential deposition). Candidates are every pair closer than 0.01 m, with
// q = u + gap / h (the holding problem of a time step; u from gravity's kick).
Pile deposited_pile(int count, std::mt19937_64& rng) {
    Pile pile;
    std::vector<Body>& bodies = pile.world.bodies;
    bodies.push_back(static_body(make_box(10.0, 0.5), {0.0, -0.5}));
    std::vector<double> radius(1, 0.0);
    for (int k = 0; k < count; ++k) {
        const double r = uniform(rng, 0.05, 0.25);
        const double x = uniform(rng, -4.0 + r, 4.0 - r);
        double y = r;
        for (std::size_t j = 1; j < bodies.size(); ++j) {
            const Vec2 c = bodies[j].state.position;
            const double reach = radius[j] + r;
            if (std::fabs(x - c.x) < reach) {
                y = std::max(y, c.y + std::sqrt(reach * reach - (x - c.x) * (x - c.x)));
            }
        }
        radius.push_back(r);
        bodies.push_back(
            dynamic_body(make_circle(r), 3.141592653589793 * r * r, {x, y}, 0.0, {0.0, -g * h}));
    }
    int pair = 0;
    std::vector<double> gaps;
    for (int a = 1; a < static_cast<int>(bodies.size()); ++a) {
        const Vec2 pa = bodies[static_cast<std::size_t>(a)].state.position;
        const double ra = radius[static_cast<std::size_t>(a)];
        if (pa.y - ra < 0.01) {
            pile.points.push_back(pile_point(pile.world, pair++, a, 0, {pa.x, 0.0}, {0.0, 1.0}));
            gaps.push_back(std::max(0.0, pa.y - ra));
        }
        for (int b = a + 1; b < static_cast<int>(bodies.size()); ++b) {
            const Vec2 between = pa - bodies[static_cast<std::size_t>(b)].state.position;
            const double gap = length(between) - ra - radius[static_cast<std::size_t>(b)];
            if (gap < 0.01) {
                const Vec2 n = (1.0 / length(between)) * between;
                pile.points.push_back(pile_point(pile.world, pair++, a, b, pa - ra * n, n));
                gaps.push_back(std::max(0.0, gap));
            }
        }
    }
    for (std::size_t i = 0; i < pile.points.size(); ++i) {
        pile.q.push_back(pile.points[i].vn + gaps[i] / h);
    }
    return pile;
}

} // namespace

// The measurement behind docs/engine.md's numbers, printed rather than judged
// (hidden: run it with build/tests/impulse_tests "[pgs-measure]").
TEST_CASE("PGS sweeps to d/h on a column and a pile, cold and warm", "[.][pgs-measure]") {
    const double tolerance = d / h;
    const auto report = [&](const char* what, const World& world,
                            const std::vector<ContactPoint>& points, const std::vector<double>& q) {
        std::vector<double> lambda;
        PgsScratch scratch;
        const PgsResult capped = solve_pgs(world, points, q, lambda, {tolerance, 200}, scratch);
        lambda.clear();
        const PgsResult cold = solve_pgs(world, points, q, lambda, {tolerance, 1000000}, scratch);
        const PgsResult warm = solve_pgs(world, points, q, lambda, {tolerance, 1000000}, scratch);
        std::printf("%s: %zu points; cold %d sweeps; warm %d; residual after 200 cold sweeps "
                    "%.3g m/s (tolerance %.3g, g h %.3g)\n",
                    what, points.size(), cold.sweeps, warm.sweeps, capped.residual, tolerance,
                    g * h);
    };
    Column c = column(50);
    report("column of 50, bottom-up", c.world, c.points, c.q);
    std::reverse(c.points.begin(), c.points.end());
    std::reverse(c.q.begin(), c.q.end());
    report("column of 50, top-down", c.world, c.points, c.q);
    const Pile pile = settled_pile(1000);
    report("1000-disc pile, row by row", pile.world, pile.points, pile.q);
    std::mt19937_64 rng(1000);
    const Pile random_pile = deposited_pile(1000, rng);
    report("1000 discs, random deposition", random_pile.world, random_pile.points, random_pile.q);
    CHECK(true);
}
