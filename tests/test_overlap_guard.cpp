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

TEST_CASE("the overlap guard lifts a row of sunken boxes by their overlaps, face rows merged",
          "[overlap-guard]") {
    // 70 squares side by side, each face to face with its neighbours and
    // turned by 1e-8 rad, so that one bottom corner is 2e-9 m (2 d) deeper
    // than the other; the deeper is sunk 2 d, 3 d or 4 d into the floor, the
    // other within the guard's margin (d + 2 x the deepest). 140 floor points,
    // with the side points a problem above diagonal_scaling_points, whose two
    // rows per face contact the guard merges into one, which must keep the
    // deeper corner's gap. The side normals are all but horizontal, so the
    // least move lifts each box by its deeper corner's overlap and moves none
    // sideways or round: every floor gap ends within d of 0 in one pass
    // (keeping the shallower corner's gap would leave 2 d for a second).
    const int count = 70;
    const double half = 0.1;
    const double turn = 1e-8;
    World world = make_world({static_body(make_box(10.0, 0.5), {0.0, -0.5})}, {0.0, -9.81}, 0.5,
                             time_stepping());
    const double d = world.solver.contact_tolerance;
    std::vector<double> sunk;
    for (int k = 0; k < count; ++k) {
        sunk.push_back((2 + k % 3) * d);
        const double y = half * (std::cos(turn) + std::sin(turn)) - sunk.back();
        world.bodies.push_back(dynamic_body(make_box(half, half), 1.0 + 0.5 * (k % 4),
                                            {(2 * k - count) * half, y}, turn));
    }
    REQUIRE(2 * count > static_cast<int>(diagonal_scaling_points)); // the floor's points alone
    TimeSteppingScratch s;
    for (const Body& b : world.bodies) {
        s.start.push_back(b.state);
        s.poses.push_back(transform_of(b.state));
    }
    s.reach.assign(world.bodies.size(), 1.0);
    for (int k = 1; k <= count; ++k) {
        s.pairs.push_back({0, k, 1.0});
        if (k < count) {
            s.pairs.push_back({k, k + 1, 1.0});
        }
    }
    guard_overlaps(world, 1.0 / 60.0, s);
    CHECK(world.work.overlap_guard_unsolved == 0);
    // A polygon pair's gap is linear in a translation until its closest
    // features change, so one solved pass is exact: a second pass would
    // mean the first left some corner deeper than d.
    CHECK(world.work.overlap_guard_passes == 1);
    for (int k = 1; k <= count; ++k) {
        const Body& box = world.bodies[static_cast<std::size_t>(k)];
        const BodyState& before = s.start[static_cast<std::size_t>(k)];
        const double gap = separation(world.bodies[0].shape, transform_of(world.bodies[0].state),
                                      box.shape, transform_of(box.state));
        INFO("box " << k << ": floor gap " << gap << " m");
        CHECK(std::fabs(gap) <= d);
        CHECK(std::fabs(box.state.position.y - before.position.y -
                        sunk[static_cast<std::size_t>(k - 1)]) <= d);
        CHECK(std::fabs(box.state.position.x - before.position.x) <= d);
        CHECK(box.state.angle == before.angle);
    }
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
