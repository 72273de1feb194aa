// The overlap guard's position problem (overlap_guard.h) on worlds whose
// answer is known: under translation alone the least move that takes a body
// out of the floor lifts it by exactly its overlap.
#include "manifold.h"
#include "mprgp.h"
#include "overlap_guard.h"
#include "support.h"
#include "support/guard_scratch.h"
#include "time_stepping_scratch.h"
#include "world.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <vector>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::static_body;
using impulse::test::time_stepping;

namespace {

// `count` squares of half side 0.1 m side by side on a static floor, each
// face to face with its neighbours and turned by 1e-8 rad, so that one bottom
// corner is 2e-9 m (2 d) deeper than the other; the deeper is sunk 2 d, 3 d or
// 4 d into the floor (`sunk`), the other within the guard's margin (d + 2 x
// the deepest). The scratch holds every floor and neighbour pair.
struct SunkenRow {
    World world;
    std::vector<double> sunk;
    TimeSteppingScratch s;
};

SunkenRow sunken_row(int count) {
    const double half = 0.1;
    const double turn = 1e-8;
    SunkenRow row{make_world({static_body(make_box(10.0, 0.5), {0.0, -0.5})}, {0.0, -9.81}, 0.5,
                             time_stepping()),
                  {},
                  {}};
    const double d = row.world.solver.contact_tolerance;
    for (int k = 0; k < count; ++k) {
        row.sunk.push_back((2 + k % 3) * d);
        const double y = half * (std::cos(turn) + std::sin(turn)) - row.sunk.back();
        row.world.bodies.push_back(dynamic_body(make_box(half, half), 1.0 + 0.5 * (k % 4),
                                                {(2 * k - count) * half, y}, turn));
    }
    std::vector<CandidatePair> pairs;
    for (int k = 1; k <= count; ++k) {
        pairs.push_back({0, k, 1.0});
        if (k < count) {
            pairs.push_back({k, k + 1, 1.0});
        }
    }
    row.s = test::guard_scratch(row.world, pairs);
    row.s.reach.assign(row.world.bodies.size(), 1.0);
    return row;
}

// Puts every body of the row back where it started.
void restart(SunkenRow& row) {
    for (std::size_t b = 0; b < row.world.bodies.size(); ++b) {
        row.world.bodies[b].state = row.s.start[b];
    }
}

} // namespace

TEST_CASE("the overlap guard lifts a row of sunken boxes by their overlaps, face rows merged",
          "[overlap-guard]") {
    // 140 floor points, with the side points a problem above
    // diagonal_scaling_points, whose two rows per face contact the guard
    // merges into one, which must keep the deeper corner's gap. The side
    // normals are all but horizontal, so the least move lifts each box by its
    // deeper corner's overlap and moves none sideways or round: every floor
    // gap ends within d of 0 in one pass (keeping the shallower corner's gap
    // would leave 2 d for a second).
    const int count = 70;
    SunkenRow row = sunken_row(count);
    World& world = row.world;
    const double d = world.solver.contact_tolerance;
    REQUIRE(2 * count > static_cast<int>(diagonal_scaling_points)); // the floor's points alone
    guard_overlaps(world, 1.0 / 60.0, row.s);
    CHECK(world.work.overlap_guard_unsolved == 0);
    // A polygon pair's gap is linear in a translation until its closest
    // features change, so one solved pass is exact: a second pass would
    // mean the first left some corner deeper than d.
    CHECK(world.work.overlap_guard_passes == 1);
    for (int k = 1; k <= count; ++k) {
        const Body& box = world.bodies[static_cast<std::size_t>(k)];
        const BodyState& before = row.s.start[static_cast<std::size_t>(k)];
        const double gap = separation(world.bodies[0].shape, transform_of(world.bodies[0].state),
                                      box.shape, transform_of(box.state));
        INFO("box " << k << ": floor gap " << gap << " m");
        CHECK(std::fabs(gap) <= d);
        CHECK(std::fabs(box.state.position.y - before.position.y -
                        row.sunk[static_cast<std::size_t>(k - 1)]) <= d);
        CHECK(std::fabs(box.state.position.x - before.position.x) <= d);
        CHECK(box.state.angle == before.angle);
    }
}

TEST_CASE("the overlap guard's first pass starts a large problem from the last step's answer",
          "[overlap-guard]") {
    // The same sunken row met twice, as in a pile whose holding step leaves
    // the same overlaps step after step. The first time the guard's problem
    // is solved cold, to its tolerance; the second time its first pass starts
    // from that answer, which already meets the tolerance, so MPRGP makes the
    // one product that measures its residual and moves the boxes as before.
    SunkenRow row = sunken_row(70);
    World& world = row.world;
    const double h = 1.0 / 60.0;
    guard_overlaps(world, h, row.s);
    const long long cold = world.work.overlap_guard_products;
    REQUIRE(world.work.overlap_guard_passes == 1);
    REQUIRE(cold > 1);
    REQUIRE_FALSE(world.guard_warm_impulses.empty());
    std::vector<BodyState> lifted;
    for (const Body& b : world.bodies) {
        lifted.push_back(b.state);
    }
    restart(row);
    guard_overlaps(world, h, row.s);
    CHECK(world.work.overlap_guard_products - cold == 1);
    const double d = world.solver.contact_tolerance;
    for (std::size_t b = 1; b < world.bodies.size(); ++b) {
        INFO("box " << b);
        CHECK(std::fabs(world.bodies[b].state.position.y - lifted[b].position.y) <= d);
        CHECK(std::fabs(world.bodies[b].state.position.x - lifted[b].position.x) <= d);
    }
}

TEST_CASE("the overlap guard starts a problem of at most diagonal_scaling_points cold",
          "[overlap-guard]") {
    // 20 squares: 40 floor points and 19 face contacts, below the threshold.
    // Met twice, the second solve makes the products of the first: nothing
    // was kept to start from, so small problems (every canonical pile's) are
    // solved as they always were.
    SunkenRow row = sunken_row(20);
    World& world = row.world;
    const double h = 1.0 / 60.0;
    guard_overlaps(world, h, row.s);
    const long long cold = world.work.overlap_guard_products;
    REQUIRE(cold > 1);
    CHECK(world.guard_warm_impulses.empty());
    restart(row);
    guard_overlaps(world, h, row.s);
    CHECK(world.work.overlap_guard_products == 2 * cold);
}

TEST_CASE("the overlap guard finds the pairs again when the step's retries ran out",
          "[overlap-guard]") {
    // Two unit-mass discs of r = 0.1 m, 1e-4 m into each other, with no
    // candidate pair between them: what a step leaves when a body outran its
    // reach more often than the step retries (pile-discs-10000 at 2.4 s: two
    // discs 5.1e-4 m deep that the guard never saw). Told the pairs are
    // stale, the guard finds them around the end poses and moves the discs
    // apart along the line of centres, 5e-5 m each (equal masses share the
    // move equally); without being told, it leaves them.
    const double r = 0.1;
    const double into = 1e-4;
    const auto discs = [&] {
        return make_world({dynamic_body(make_circle(r), 1.0, {0.0, 0.0}),
                           dynamic_body(make_circle(r), 1.0, {2.0 * r - into, 0.0})},
                          {0.0, 0.0}, 0.5, time_stepping());
    };
    const double d = discs().solver.contact_tolerance;

    World told = discs();
    TimeSteppingScratch s = test::guard_scratch(told, {});
    guard_overlaps(told, 1.0 / 60.0, s, true);
    const double gap = told.bodies[1].state.position.x - told.bodies[0].state.position.x - 2.0 * r;
    CHECK(std::fabs(gap) <= d);
    CHECK(std::fabs(told.bodies[0].state.position.x + 0.5 * into) <= d);
    CHECK(told.bodies[0].state.position.y == 0.0);

    World untold = discs();
    TimeSteppingScratch u = test::guard_scratch(untold, {});
    guard_overlaps(untold, 1.0 / 60.0, u);
    CHECK(untold.bodies[0].state.position.x == 0.0);
    CHECK(untold.work.overlap_guard_passes == 0);
}

TEST_CASE("pairs found again cover only their grow around the poses they were found at",
          "[overlap-guard]") {
    // Three unit-mass discs of r = 0.1 m in a row: A 2 cm into B, C 5 mm
    // beyond B, and no candidate pair (the step's retries ran out). Found
    // again around the end poses, the pairs hold A and B but not B and C, far
    // more than d apart. Equal masses share the separating move, so B goes
    // 1 cm towards C, 5 mm into it, yet stays well within the 1 m the step
    // had reached from its start: measured from the start, nothing outran the
    // pairs. Measured from where they were found, B went 1 cm past their d,
    // and the pairs found again around B hold C, which the passes move on.
    const double r = 0.1;
    const double into = 0.02;
    const double beyond_b = 5e-3;
    World world = make_world({dynamic_body(make_circle(r), 1.0, {0.0, 0.0}),
                              dynamic_body(make_circle(r), 1.0, {2.0 * r - into, 0.0}),
                              dynamic_body(make_circle(r), 1.0, {4.0 * r - into + beyond_b, 0.0})},
                             {0.0, 0.0}, 0.5, time_stepping());
    const double d = world.solver.contact_tolerance;
    TimeSteppingScratch s = test::guard_scratch(world, {});
    s.reach.assign(world.bodies.size(), 1.0);
    guard_overlaps(world, 1.0 / 60.0, s, true);
    const auto gap = [&world, r](std::size_t i, std::size_t k) {
        return world.bodies[k].state.position.x - world.bodies[i].state.position.x - 2.0 * r;
    };
    CHECK(world.work.overlap_guard_pair_rebuilds >= 2); // the stale pairs', then B's move's
    CHECK(gap(0, 1) >= -d);
    CHECK(gap(1, 2) >= -d);
    for (const char stuck : s.guard_stuck) {
        CHECK(stuck == 0); // separated by the passes, not left to the energy guard
    }
}
