// Dense contact under parameters its authors did not choose (issue 14: "every
// invariant holding for parameters you did not choose"): each case is a
// failure an outside campaign of random piles found (docs/engine.md, "Dense
// contact", "Found by an outside campaign"), cut down to the smallest world
// that shows it, and asserts the invariant that failed.
#include "manifold.h"
#include "overlap_guard.h"
#include "support.h"
#include "time_stepping_scratch.h"
#include "world.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::static_body;
using impulse::test::time_stepping;

namespace {

constexpr double h = 1.0 / 30.0;

bool finite(const BodyState& s) {
    return std::isfinite(s.position.x) && std::isfinite(s.position.y) && std::isfinite(s.angle) &&
           std::isfinite(s.velocity.x) && std::isfinite(s.velocity.y) &&
           std::isfinite(s.angular_velocity);
}

} // namespace

TEST_CASE("the overlap guard leaves a body that cannot fit where it is, finite, and says so",
          "[dense-robust]") {
    // A 0.2 m thick slab 3 mm into the floor with the ceiling 1 mm above it:
    // moving it out of the floor (translation, as the guard moves) takes it
    // 2 mm into the ceiling, so the guard's position problem has no solution
    // (w_floor + w_ceiling = (g_floor + g_ceiling) / h < 0 for any impulses).
    // Found in a random pile: a box wedged between two pegs whose corners were
    // closer than its thickness; the iterative solver ran the impulses to
    // infinity, and infinity times a static body's zero inverse mass made the
    // peg's velocity NaN.
    const double half = 0.1;
    const double into_floor = 3e-3;
    const double below_ceiling = 1e-3;
    const double y = half - into_floor;
    World world =
        make_world({static_body(make_box(2.0, 0.5), {0.0, -0.5}),
                    static_body(make_box(2.0, 0.5), {0.0, y + half + below_ceiling + 0.5}),
                    dynamic_body(make_box(0.5, half), 1.0, {0.0, y})},
                   {0.0, -9.81}, 0.5, time_stepping());
    TimeSteppingScratch s;
    for (const Body& b : world.bodies) {
        s.start.push_back(b.state);
        s.poses.push_back(transform_of(b.state));
    }
    s.reach.assign(3, 0.0);
    s.pairs = {{0, 2, world.solver.contact_tolerance}, {1, 2, world.solver.contact_tolerance}};
    const BodyState floor = world.bodies[0].state;
    const BodyState ceiling = world.bodies[1].state;
    guard_overlaps(world, h, s);
    for (const Body& b : world.bodies) {
        CHECK(finite(b.state));
    }
    // Static bodies are where the scene put them, and the slab stays: no move
    // of it can take out the overlap.
    CHECK(world.bodies[0].state.position.y == floor.position.y);
    CHECK(world.bodies[1].state.position.y == ceiling.position.y);
    CHECK(world.bodies[2].state.position.y == y);
    CHECK(world.work.overlap_guard_unsolved >= 1);
}

TEST_CASE("the overlap guard turns a slab free when no translation can separate it",
          "[dense-robust]") {
    // A 1 m slab 3 mm into a peg under its left end, with a peg 1 mm above its
    // right end: the normals are opposite, so no translation separates it
    // (as above), but turning it clockwise lifts the left end and lowers
    // the right: about 3 mm / 0.4 m = 7.5e-3 rad. Found in a random
    // pile: a box wedged between two pegs stayed 4.8 mm deep until this.
    const double into = 3e-3;
    const double above = 1e-3;
    World world = make_world({static_body(make_box(0.05, 0.05), {-0.4, -0.1 + into}),
                              static_body(make_box(0.05, 0.05), {0.4, 0.1 + above}),
                              dynamic_body(make_box(0.5, 0.05), 1.0, {0.0, 0.0})},
                             {0.0, -9.81}, 0.5, time_stepping());
    TimeSteppingScratch s;
    for (const Body& b : world.bodies) {
        s.start.push_back(b.state);
        s.poses.push_back(transform_of(b.state));
    }
    s.reach.assign(3, 0.0);
    s.pairs = {{0, 2, world.solver.contact_tolerance}, {1, 2, world.solver.contact_tolerance}};
    guard_overlaps(world, h, s);
    const auto gap_of = [&world](std::size_t i) {
        return separation(world.bodies[i].shape, transform_of(world.bodies[i].state),
                          world.bodies[2].shape, transform_of(world.bodies[2].state));
    };
    CHECK(finite(world.bodies[2].state));
    CHECK(world.work.overlap_guard_turns >= 1);
    CHECK(world.work.overlap_guard_unsolved == 0);
    CHECK(gap_of(0) >= -1e-6); // the max-overlap target
    CHECK(gap_of(1) >= -1e-6);
    CHECK(world.bodies[2].state.angle < 0.0);               // clockwise
    CHECK(world.bodies[2].state.angle > -4.0 * into / 0.4); // a small turn
}
