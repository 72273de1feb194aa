// Dense contact under parameters its authors did not choose (issue 14: "every
// invariant holding for parameters you did not choose"): each case is a
// failure an outside campaign of random piles found (docs/engine.md, "Dense
// contact", "Found by an outside campaign"), cut down to the smallest world
// that shows it, and asserts the invariant that failed.
#include "manifold.h"
#include "overlap_guard.h"
#include "support.h"
#include "support/files.h"
#include "support/guard_scratch.h"
#include "support/tool.h"
#include "time_stepping_scratch.h"
#include "world.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::static_body;
using impulse::test::time_stepping;
using namespace impulse::test;

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
    TimeSteppingScratch s = guard_scratch(
        world, {{0, 2, world.solver.contact_tolerance}, {1, 2, world.solver.contact_tolerance}});
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
    TimeSteppingScratch s = guard_scratch(
        world, {{0, 2, world.solver.contact_tolerance}, {1, 2, world.solver.contact_tolerance}});
    guard_overlaps(world, h, s);
    const auto gap_of = [&world](std::size_t i) {
        return separation(world.bodies[i].shape, transform_of(world.bodies[i].state),
                          world.bodies[2].shape, transform_of(world.bodies[2].state));
    };
    CHECK(finite(world.bodies[2].state));
    CHECK(world.work.overlap_guard_turns >= 1);
    CHECK(world.work.overlap_guard_unsolved == 0);
    CHECK(gap_of(0) >= -1e-6); // the issue's max-overlap target
    CHECK(gap_of(1) >= -1e-6);
    CHECK(world.bodies[2].state.angle < 0.0);               // clockwise
    CHECK(world.bodies[2].state.angle > -4.0 * into / 0.4); // a small turn
}

TEST_CASE("the energy guard returns no island into a neighbour the overlap guard moved with it",
          "[dense-robust]") {
    // Five triangles (masses 1.4 to 99 kg) dropped into a V, e = 0.5, verlet,
    // dt 1/120, drawn at random. At 2.6 s one overlap-guard group held b0 and
    // b1 (one island) and b2 (another): it separated them by 2.9 mm; the
    // energy guard then found b0 and b1's island lifted with no kinetic
    // energy to pay (K = 1e-31 J) and returned it to its poses at the step's
    // start, while b2 kept its move: b0 and b2 overlapped by 6.1e-5 m. The
    // energy guard now checks an island together with every island a guard
    // group joined it to. The scene states the invariants: no overlap deeper
    // than 1e-6 m (docs/formats.md, max-overlap), energy never gained.
    const std::string scene =
        R"json({"schema": "impulse/scene@1", "name": "five-triangles", "description": "", "gravity": [0.0, -9.81], "restitution": 0.5, "dt": 0.008333333333333333, "duration": 2.7, "solver": {"integrator": "verlet", "stepping": "world", "resting": true, "resting_method": "time-stepping"}, "bodies": [
{"name": "v-left", "static": true, "shape": {"box": [1.60076640988722, 0.5]}, "position": [-1.5228406364597367, 0.5795108747740646], "angle": -0.6755217243859739},
{"name": "v-right", "static": true, "shape": {"box": [1.60076640988722, 0.5]}, "position": [1.5228406364597367, 0.5795108747740646], "angle": 0.6755217243859739},
{"name": "wall-left", "static": true, "shape": {"box": [0.5, 10.5]}, "position": [-1.3590169943749475, 10.5]},
{"name": "wall-right", "static": true, "shape": {"box": [0.5, 10.5]}, "position": [1.3590169943749475, 10.5]},
{"name": "b0", "shape": {"polygon": [[0.07825459781089154, 0.0], [-0.03912729890544575, 0.0677704696671662], [-0.039127298905445806, -0.06777046966716617]]}, "mass": 4.287426, "position": [-0.5707338737226939, 3.9255122168038965], "angle": -0.5940036278536747},
{"name": "b1", "shape": {"polygon": [[0.14068491832412505, 0.0], [-0.0703424591620625, 0.12183671319803117], [-0.0703424591620626, -0.12183671319803113]]}, "mass": 98.749821, "position": [-0.29217725456855687, 3.9255122168038965], "angle": 1.0502144104369346},
{"name": "b2", "shape": {"polygon": [[0.05594111835247704, 0.0], [-0.027970559176238505, 0.048446429609357], [-0.027970559176238544, -0.04844642960935698]]}, "mass": 1.408281, "position": [-0.036684952204211335, 3.9255122168038965], "angle": -2.2584656590609944},
{"name": "b3", "shape": {"polygon": [[0.09321579180261516, 0.0], [-0.04660789590130756, 0.08072724373494597], [-0.04660789590130762, -0.08072724373494594]]}, "mass": 22.475911, "position": [0.4828831342845567, 3.9255122168038965], "angle": 1.5496620041850306},
{"name": "b4", "shape": {"polygon": [[0.18352742857792723, 0.0], [-0.09176371428896357, 0.15893941543971915], [-0.0917637142889637, -0.1589394154397191]]}, "mass": 1.753021, "position": [-0.6697310703269834, 4.299908171102868], "angle": -0.3436221821051162}],
"expectations": [{"kind": "max-overlap", "atol": 1e-06}, {"kind": "energy-non-increasing", "rtol": 1e-12}]})json";
    const TempDir tmp;
    spit(tmp.dir / "five.json", scene);
    const Outcome o = run_tool(
        {"run", (tmp.dir / "five.json").string(), "--out", (tmp.dir / "out.json").string()});
    INFO(o.err);
    CHECK(o.exit_code == 0); // 1 would be a failed expectation: the overlap
}
