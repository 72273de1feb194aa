// Contact problems for the tests of the LCP solvers (test_pgs.cpp,
// test_mprgp.cpp): one island's world, its points and q, built where physics
// knows the answer (a column of boxes, a settled packing of discs), and the
// checks both solvers' results are read with.
#pragma once

#include "../support.h"
#include "pgs.h"
#include "restitution.h"
#include "world.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <random>
#include <vector>

namespace impulse::test::contact_problems {

constexpr double g = 9.81;
constexpr double h = 1.0 / 60.0;
constexpr double d = 1e-9; // the default contact tolerance: d / h is the residual asked for

// One island's problem: the world, its points, q.
struct Problem {
    World world;
    std::vector<ContactPoint> points;
    std::vector<double> q;
};

// Point P between bodies a and b (world indices; a dynamic one first, as
// pair_of orders them) with normal n toward a and vn from their velocities.
// Its pair index is 0 until number_pairs (or the builder) sets it.
inline ContactPoint point_of(const World& world, int a, int b, Vec2 P, Vec2 n) {
    const Body& ba = world.bodies[static_cast<std::size_t>(a)];
    const Body& bb = world.bodies[static_cast<std::size_t>(b)];
    ContactPoint p{0, a, b, {P, n, 0.0}, 0.0, 0.0, 0.0};
    p.rn_a = dot(perp(P - ba.state.position), n);
    p.rn_b = dot(perp(P - bb.state.position), n);
    p.vn = relative_normal_velocity(ba, bb, P, n);
    return p;
}

// Every point's pair index, as delassus() tells points of one pair apart by it.
inline void number_pairs(Problem& p) {
    for (ContactPoint& point : p.points) {
        const Pair want = pair_of(p.world, point.a, point.b);
        int index = 0;
        while (p.world.pairs[static_cast<std::size_t>(index)].a != want.a ||
               p.world.pairs[static_cast<std::size_t>(index)].b != want.b) {
            ++index;
        }
        point.pair = index;
    }
}

// A dense matrix written row by row, as the pivoting solver takes it (lcp.h).
inline std::vector<double> row_major(std::initializer_list<std::initializer_list<double>> rows) {
    std::vector<double> out;
    for (const auto& row : rows) {
        out.insert(out.end(), row.begin(), row.end());
    }
    return out;
}

// A x for a dense n x n matrix A, row-major.
inline std::vector<double> times(const std::vector<double>& A, const std::vector<double>& x) {
    const std::size_t n = x.size();
    std::vector<double> y(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = 0; k < n; ++k) {
            y[i] += A[i * n + k] * x[k];
        }
    }
    return y;
}

// A solver's scratch is left for the next island: no body holds a slot.
template <typename Scratch> bool all_clear(const Scratch& s) {
    return std::all_of(s.local_of_body.begin(), s.local_of_body.end(),
                       [](int slot) { return slot == -1; });
}

// A random Delassus problem: 2-5 bodies (body 0 static), masses 1:100, some
// not rotating, random velocities; 1-10 points on random pairs at random
// places (solve_lcp's fallback reaches that far), a pair's points sharing its
// normal as a manifold's do, so repeated pairs make A singular. q = J v + a
// gap's worth (>= 0): v = 0 is feasible, so a solution exists.
inline Problem random_problem(std::mt19937_64& rng) {
    const int n_bodies = 2 + static_cast<int>(rng() % 4);
    std::vector<Body> bodies{static_body(make_box(5.0, 0.5), {0.0, -0.5})};
    for (int i = 1; i < n_bodies; ++i) {
        const Vec2 at{uniform(rng, -2.0, 2.0), uniform(rng, 0.0, 2.0)};
        const Vec2 v{uniform(rng, -1.0, 1.0), uniform(rng, -1.0, 1.0)};
        bodies.push_back(dynamic_body(make_box(uniform(rng, 0.1, 0.5), uniform(rng, 0.1, 0.5)),
                                      log_uniform(rng, 0.1, 10.0), at, 0.0, v,
                                      uniform(rng, -1.0, 1.0), rng() % 4 != 0));
    }
    Problem p{make_world(bodies, {0.0, -g}, 0.0, SolverSettings{}), {}, {}};
    std::vector<double> angle(p.world.pairs.size());
    for (double& a : angle) {
        a = uniform(rng, 0.0, 6.283185307179586);
    }
    const int n_points = 1 + static_cast<int>(rng() % 10);
    for (int k = 0; k < n_points; ++k) {
        const std::size_t pair = rng() % p.world.pairs.size();
        const Vec2 P{uniform(rng, -2.0, 2.0), uniform(rng, -0.5, 2.0)};
        p.points.push_back(point_of(p.world, p.world.pairs[pair].a, p.world.pairs[pair].b, P,
                                    {std::cos(angle[pair]), std::sin(angle[pair])}));
        p.q.push_back(p.points.back().vn + (rng() % 2 == 0 ? 0.0 : uniform(rng, 0.0, 0.5)));
    }
    number_pairs(p);
    return p;
}

// The masses of column(): 1 + 0.1 k, box k counted from the floor.
inline double graded_mass(int k) {
    return 1.0 + 0.1 * k;
}

// A column of `count` unit boxes (box k of mass mass_of(k)) on a static floor
// (body count), each at rest and then kicked by one step of gravity: q = -g h
// on the floor's two corner points, 0 between boxes. Points bottom-up, two
// under each box: lambda[2 k] and lambda[2 k + 1] carry box k.
inline Problem column(int count, double (*mass_of)(int) = graded_mass) {
    std::vector<Body> bodies;
    for (int k = 0; k < count; ++k) {
        bodies.push_back(
            dynamic_body(make_box(0.5, 0.5), mass_of(k), {0.0, 0.5 + k}, 0.0, {0.0, -g * h}));
    }
    bodies.push_back(static_body(make_box(5.0, 0.5), {0.0, -0.5}));
    Problem c{make_world(bodies, {0.0, -g}, 0.0, SolverSettings{}), {}, {}};
    for (int k = 0; k < count; ++k) {
        const int below = k == 0 ? count : k - 1;
        for (const double x : {-0.5, 0.5}) {
            c.points.push_back(point_of(c.world, std::min(k, below), std::max(k, below),
                                        {x, static_cast<double>(k)},
                                        k < below ? Vec2{0.0, 1.0} : Vec2{0.0, -1.0}));
        }
    }
    number_pairs(c);
    for (const ContactPoint& p : c.points) {
        c.q.push_back(p.vn);
    }
    return c;
}

// A settled triangular packing of `count` equal discs (r = 0.1, m = 1), long
// rows of `width` and short rows of width - 1 alternating, on a static floor
// between static walls touching the long rows' end discs. Every touching pair
// is a point (gap 0) and q is what one step of gravity gives: the holding
// problem of a pile at rest. Statics are bodies 0-2 (the floor is body 0);
// discs from 3, row by row.
inline Problem packing(int count, int width) {
    const double r = 0.1;
    const double rise = r * std::sqrt(3.0);
    const double right = 2.0 * r * (width - 1);
    std::vector<Body> bodies{static_body(make_box(1000.0, 0.5), {0.0, -0.5}),
                             static_body(make_box(0.5, 1000.0), {-0.5 - r, 0.0}),
                             static_body(make_box(0.5, 1000.0), {right + r + 0.5, 0.0})};
    for (int k = 0; bodies.size() < static_cast<std::size_t>(count) + 3; ++k) {
        const int row = k / (2 * width - 1);
        const int in_pair = k % (2 * width - 1);
        const bool long_row = in_pair < width;
        const int column = long_row ? in_pair : in_pair - width;
        const double x = 2.0 * r * column + (long_row ? 0.0 : r);
        const double y = r + rise * (2 * row + (long_row ? 0 : 1));
        bodies.push_back(dynamic_body(make_circle(r), 1.0, {x, y}, 0.0, {0.0, -g * h}));
    }
    // No make_world: its every-pair list would be quadratic in the discs.
    // Each touching pair has one point, so its pair index is the point's own.
    Problem pile;
    pile.world.bodies = bodies;
    const int n = static_cast<int>(bodies.size());
    for (int a = 3; a < n; ++a) {
        const Vec2 pa = bodies[static_cast<std::size_t>(a)].state.position;
        if (pa.y == r) {
            pile.points.push_back(point_of(pile.world, a, 0, pa - Vec2{0.0, r}, {0.0, 1.0}));
        }
        if (pa.x == 0.0) {
            pile.points.push_back(point_of(pile.world, a, 1, pa - Vec2{r, 0.0}, {1.0, 0.0}));
        }
        if (pa.x == right) {
            pile.points.push_back(point_of(pile.world, a, 2, pa + Vec2{r, 0.0}, {-1.0, 0.0}));
        }
        // Bodies go row by row, so every neighbour above lies within 2 width.
        for (int b = a + 1; b < std::min(n, a + 2 * width + 1); ++b) {
            const Vec2 pb = bodies[static_cast<std::size_t>(b)].state.position;
            const Vec2 between = pa - pb;
            if (length(between) < 2.0 * r * (1.0 + 1e-9)) {
                const Vec2 normal = (1.0 / length(between)) * between;
                pile.points.push_back(point_of(pile.world, a, b, 0.5 * (pa + pb), normal));
            }
        }
    }
    for (std::size_t i = 0; i < pile.points.size(); ++i) {
        pile.points[i].pair = static_cast<int>(i);
        pile.q.push_back(pile.points[i].vn);
    }
    return pile;
}

} // namespace impulse::test::contact_problems
