// Narrow phase: separation, contact points and the normal's direction.
#include "manifold.h"
#include "run.h"
#include "scene.h"
#include "trajectory.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

using namespace impulse;

namespace {
Transform at(Vec2 p, double angle = 0.0) {
    return {p, rotation_of(angle)};
}
constexpr double tol = 1e-9;
} // namespace

TEST_CASE("Circle pair: gap, normal toward A, point between the surfaces", "[manifold]") {
    const Shape a = make_circle(1.0), b = make_circle(0.5);
    const Manifold m = collide(a, at({3, 4}), b, at({0, 0}), 1.0);
    CHECK(m.separation == Approx(3.5).epsilon(1e-15)); // |(3, 4)| - 1.5
    CHECK(m.point_count == 0);                         // farther apart than the tolerance
    const Manifold touching = collide(a, at({0.9, 1.2}), b, at({0, 0}), tol);
    REQUIRE(touching.point_count == 1);
    CHECK(touching.separation == Approx(0.0).margin(1e-15));
    CHECK(touching.normal.x == Approx(0.6).epsilon(1e-15));
    CHECK(touching.normal.y == Approx(0.8).epsilon(1e-15));
    CHECK(touching.points[0].point.x == Approx(0.3).epsilon(1e-14));
    CHECK(touching.points[0].point.y == Approx(0.4).epsilon(1e-14));
}

TEST_CASE("Separation sign: overlap is negative, touching zero, apart positive", "[manifold]") {
    const Shape box = make_box(0.5, 0.5);
    const Shape ground = make_box(10, 0.5);
    CHECK(separation(box, at({0, 0.5}), ground, at({0, -0.5})) == 0.0);
    CHECK(separation(box, at({0, 0.75}), ground, at({0, -0.5})) == 0.25);
    CHECK(separation(box, at({0, 0.25}), ground, at({0, -0.5})) == -0.25);
    CHECK(separation(make_circle(0.5), at({0, 0.4}), ground, at({0, -0.5})) ==
          Approx(-0.1).epsilon(1e-14));
}

TEST_CASE("A box landing flat touches at two points, normal toward the box", "[manifold]") {
    const Manifold m =
        collide(make_box(1, 0.5), at({0.25, 0.5}), make_box(10, 0.5), at({0, -0.5}), tol);
    REQUIRE(m.point_count == 2);
    CHECK(m.normal == Vec2{0, 1});
    CHECK(m.points[0].point.y == 0.0);
    CHECK(m.points[1].point.y == 0.0);
    CHECK(std::min(m.points[0].point.x, m.points[1].point.x) == -0.75);
    CHECK(std::max(m.points[0].point.x, m.points[1].point.x) == 1.25);
}

TEST_CASE("A tilted box touches at its lowest corner only", "[manifold]") {
    const double angle = 0.5235987755982988; // 30 degrees
    const Shape box = make_box(1, 0.5);
    // Lowest corner of a 2x1 box at 30 degrees: rotate (1, -0.5) and (-1, -0.5), take the lower.
    const Rotation q = rotation_of(angle);
    const Vec2 c1 = rotate(q, {1, -0.5}), c2 = rotate(q, {-1, -0.5});
    const Vec2 lowest = c1.y < c2.y ? c1 : c2;
    const Manifold m =
        collide(box, at({0, -lowest.y}, angle), make_box(10, 0.5), at({0, -0.5}), tol);
    REQUIRE(m.point_count == 1);
    CHECK(m.normal == Vec2{0, 1});
    CHECK(m.points[0].point.x == Approx(lowest.x).epsilon(1e-14));
    CHECK(m.points[0].point.y == Approx(0.0).margin(1e-15));
}

TEST_CASE("The normal points toward A whichever shape A is", "[manifold]") {
    const Shape circle = make_circle(0.5), box = make_box(0.5, 0.5);
    // A above B: the normal points up; swap them and it points down.
    CHECK(collide(circle, at({0, 1}), box, at({0, 0}), tol).normal == Vec2{0, 1});
    CHECK(collide(box, at({0, 1}), circle, at({0, 0}), tol).normal == Vec2{0, 1});
    CHECK(collide(box, at({0, 0}), circle, at({0, 1}), tol).normal == Vec2{0, -1});
    CHECK(collide(box, at({0, 1}), box, at({0, 0}), tol).normal == Vec2{0, 1});
    CHECK(collide(box, at({0, 0}), box, at({0, 1}), tol).normal == Vec2{0, -1});
}

TEST_CASE("Circle against a polygon's corner takes the normal from the corner", "[manifold]") {
    // Circle centre on the diagonal beyond the corner (0.5, 0.5) of a unit box.
    const double d = 0.5 / std::sqrt(2.0);
    const Manifold m =
        collide(make_circle(0.5), at({0.5 + d, 0.5 + d}), make_box(0.5, 0.5), at({0, 0}), tol);
    REQUIRE(m.point_count == 1);
    CHECK(m.separation == Approx(0.0).margin(1e-15));
    CHECK(m.normal.x == Approx(std::sqrt(0.5)).epsilon(1e-15));
    CHECK(m.normal.y == Approx(std::sqrt(0.5)).epsilon(1e-15));
    CHECK(m.points[0].point.x == Approx(0.5).epsilon(1e-15));
}

TEST_CASE("Box on a narrower box: the contact points are clipped to the overlap", "[manifold]") {
    // A 4-wide box resting on a 1-wide post: the touching segment is the post's top.
    const Manifold m = collide(make_box(2, 0.5), at({0, 1}), make_box(0.5, 0.5), at({0, 0}), tol);
    REQUIRE(m.point_count == 2);
    CHECK(m.normal == Vec2{0, 1});
    CHECK(std::min(m.points[0].point.x, m.points[1].point.x) == -0.5);
    CHECK(std::max(m.points[0].point.x, m.points[1].point.x) == 0.5);
}

// ---------------------------------------------------------------- vertex/vertex

namespace {

constexpr double degree = 0.017453292519943295;
constexpr double deg10 = 0.17453292519943295;
constexpr double deg30 = 0.5235987755982988;
constexpr double deg45 = 0.7853981633974483;

// The transform that puts the local point `corner` of a body turned by `angle`
// at `where`.
Transform corner_at(Vec2 corner, double angle, Vec2 where) {
    const Rotation q = rotation_of(angle);
    return {where - rotate(q, corner), q};
}

// The same configuration turned by theta about the origin.
Transform turned(const Transform& xf, double angle, double theta) {
    return {rotate(rotation_of(theta), xf.p), rotation_of(angle + theta)};
}

Manifold collide_with(VertexNormal mode, const Transform& xa, const Transform& xb) {
    const Shape square = make_box(0.5, 0.5);
    return collide(square, xa, square, xb, tol, mode);
}

} // namespace

TEST_CASE("Squares at 45 degrees corner to corner on the x axis: the bisector is the axis",
          "[manifold][unit]") {
    // A's left corner (local (-0.5, 0.5) turned 45 degrees) and B's right corner
    // (local (0.5, -0.5)) both at the origin. The edges at each corner make the
    // same two lines, x = +-y: A's separating normals (toward A) are the
    // negated cone [-45, 45] degrees of its left corner, B's the cone [-45, 45]
    // of its right corner, so they intersect in all of it and the bisector is
    // (1, 0).
    const Transform xa = corner_at({-0.5, 0.5}, deg45, {0, 0});
    const Transform xb = corner_at({0.5, -0.5}, deg45, {0, 0});

    const Manifold bisector = collide_with(VertexNormal::bisector, xa, xb);
    REQUIRE(bisector.point_count == 1);
    CHECK(bisector.normal.x == Approx(1.0).epsilon(1e-15));
    CHECK(bisector.normal.y == Approx(0.0).margin(1e-15));
    CHECK(bisector.points[0].normal == bisector.normal);
    CHECK(bisector.points[0].point.x == Approx(0.0).margin(1e-15));
    CHECK(bisector.points[0].point.y == Approx(0.0).margin(1e-15));
    CHECK(bisector.points[0].separation == Approx(0.0).margin(1e-15));

    // The seed takes a face of the pair: its normal is 45 degrees off the axis.
    const Manifold seed = collide_with(VertexNormal::reference_face, xa, xb);
    REQUIRE(seed.point_count >= 1);
    CHECK(seed.normal.x == Approx(std::sqrt(0.5)).epsilon(1e-15));
    CHECK(std::abs(seed.normal.y) == Approx(std::sqrt(0.5)).epsilon(1e-15));

    // Swapping the bodies only turns the normal round.
    const Manifold swapped = collide_with(VertexNormal::bisector, xb, xa);
    REQUIRE(swapped.point_count == 1);
    CHECK(swapped.normal == -bisector.normal);
    CHECK(swapped.points[0].point == bisector.points[0].point);
    CHECK(swapped.points[0].separation == bisector.points[0].separation);
}

TEST_CASE("Corner to corner with the corners a hair apart or a hair into each other",
          "[manifold][unit]") {
    // The time-of-impact search stops anywhere in the contact band, where the
    // seed's clipping may miss the face sideways or leave a sliver of two
    // points at the corner: either way one point and the axis.
    for (const double gap : {-4e-10, -1e-12, 0.0, 1e-12, 4e-10}) {
        INFO("gap " << gap);
        const Transform xa = corner_at({-0.5, 0.5}, deg45, {0.5 * gap, 0});
        const Transform xb = corner_at({0.5, -0.5}, deg45, {-0.5 * gap, 0});
        const Manifold m = collide_with(VertexNormal::bisector, xa, xb);
        REQUIRE(m.point_count == 1);
        CHECK(m.normal.x == Approx(1.0).epsilon(1e-15));
        CHECK(m.normal.y == Approx(0.0).margin(1e-15));
        CHECK(m.points[0].point.x == Approx(0.0).margin(1e-15));
        CHECK(m.points[0].point.y == Approx(0.0).margin(1e-15));
        CHECK(m.points[0].separation == Approx(gap).margin(1e-15));
    }
}

TEST_CASE("A corner inside a face is vertex/edge: both modes give the face normal",
          "[manifold][unit]") {
    // A square at 45 degrees with its lowest corner (local (-0.5, -0.5)) on the
    // top face of an upright square, 0.2 from the face's middle.
    const Transform xa = corner_at({-0.5, -0.5}, deg45, {0.2, 0.5});
    const Transform xb = at({0, 0});
    for (const VertexNormal mode : {VertexNormal::reference_face, VertexNormal::bisector}) {
        const Manifold m = collide_with(mode, xa, xb);
        REQUIRE(m.point_count == 1);
        CHECK(m.normal == Vec2{0, 1});
        CHECK(m.points[0].point.x == Approx(0.2).epsilon(1e-15));
        CHECK(m.points[0].point.y == Approx(0.5).epsilon(1e-15));
        CHECK(collide_with(mode, xb, xa).normal == Vec2{0, -1});
    }
}

TEST_CASE("Flush edges are edge/edge: the bisector mode keeps both points and the face",
          "[manifold][unit]") {
    // Equal squares stacked exactly: each contact point is a corner of both,
    // but the contact is the shared edge.
    const Manifold m = collide_with(VertexNormal::bisector, at({0, 1}), at({0, 0}));
    REQUIRE(m.point_count == 2);
    CHECK(m.normal == Vec2{0, 1});
    CHECK(std::min(m.points[0].point.x, m.points[1].point.x) == -0.5);
    CHECK(std::max(m.points[0].point.x, m.points[1].point.x) == 0.5);
}

TEST_CASE("Corner of a square at 30 degrees on the corner of one at 10 degrees: the bisector",
          "[manifold][unit]") {
    // B turned 10 degrees, its corner local (0.5, -0.5) at the origin: the edges
    // meeting there have outward normals at -80 and 10 degrees, so B's cone is
    // [-80, 10]. A turned 30 degrees, its corner local (-0.5, 0.5) at the
    // origin: normals at 120 and 210 degrees; the normals toward A are their
    // negatives, [-60, 30]. The intersection is [-60, 10], its bisector -25
    // degrees: n = (cos 25, -sin 25).
    const Transform xa = corner_at({-0.5, 0.5}, deg30, {0, 0});
    const Transform xb = corner_at({0.5, -0.5}, deg10, {0, 0});
    const Manifold m = collide_with(VertexNormal::bisector, xa, xb);
    REQUIRE(m.point_count == 1);
    CHECK(m.normal.x == Approx(0.90630778703665).epsilon(1e-15));
    CHECK(m.normal.y == Approx(-0.42261826174069944).epsilon(1e-15));
    CHECK(m.points[0].point.x == Approx(0.0).margin(1e-15));
    CHECK(m.points[0].point.y == Approx(0.0).margin(1e-15));

    // Strictly inside both cones, by sin 15 (A's -60 bound) and sin 35 (B's 10 bound).
    const Rotation qa = rotation_of(deg30), qb = rotation_of(deg10);
    const Vec2 b_from = rotate(qb, {0, -1}), b_to = rotate(qb, {1, 0});
    const Vec2 a_from = -rotate(qa, {0, 1}), a_to = -rotate(qa, {-1, 0});
    CHECK(cross(b_from, m.normal) == Approx(std::sin(55 * degree)).epsilon(1e-14));
    CHECK(cross(m.normal, b_to) == Approx(std::sin(35 * degree)).epsilon(1e-14));
    CHECK(cross(a_from, m.normal) == Approx(std::sin(35 * degree)).epsilon(1e-14));
    CHECK(cross(m.normal, a_to) == Approx(std::sin(55 * degree)).epsilon(1e-14));

    // The seed's is a face normal of one of them, not the bisector.
    const Manifold seed = collide_with(VertexNormal::reference_face, xa, xb);
    CHECK(dot(seed.normal, m.normal) < std::cos(30 * degree));

    // No dependence on which body is A.
    const Manifold swapped = collide_with(VertexNormal::bisector, xb, xa);
    REQUIRE(swapped.point_count == 1);
    CHECK(swapped.normal == -m.normal);
    CHECK(swapped.points[0].point == m.points[0].point);
}

TEST_CASE("Turning a vertex/vertex configuration turns its bisector normal", "[manifold][unit]") {
    struct Case {
        Vec2 corner_a;
        double angle_a;
        Vec2 corner_b;
        double angle_b;
    };
    for (const Case& c : {Case{{-0.5, 0.5}, deg45, {0.5, -0.5}, deg45},
                          Case{{-0.5, 0.5}, deg30, {0.5, -0.5}, deg10}}) {
        const Transform xa = corner_at(c.corner_a, c.angle_a, {0.3, -0.7});
        const Transform xb = corner_at(c.corner_b, c.angle_b, {0.3, -0.7});
        const Manifold m = collide_with(VertexNormal::bisector, xa, xb);
        REQUIRE(m.point_count == 1);
        for (const double theta : {0.3, 1.0, 1.5707963267948966, 2.5, -2.0, 3.141592653589793}) {
            INFO("angles " << c.angle_a << ", " << c.angle_b << " turned by " << theta);
            const Manifold t = collide_with(VertexNormal::bisector, turned(xa, c.angle_a, theta),
                                            turned(xb, c.angle_b, theta));
            REQUIRE(t.point_count == 1);
            const Vec2 expected = rotate(rotation_of(theta), m.normal);
            CHECK(t.normal.x == Approx(expected.x).margin(1e-14));
            CHECK(t.normal.y == Approx(expected.y).margin(1e-14));
            const Vec2 point = rotate(rotation_of(theta), m.points[0].point);
            CHECK(t.points[0].point.x == Approx(point.x).margin(1e-14));
            CHECK(t.points[0].point.y == Approx(point.y).margin(1e-14));
        }
    }
}

namespace {

// The value of a trajectory column in the first frame at or after time t.
double column_at(const harness::Trajectory& trajectory, const std::string& column, double t) {
    const auto c = std::find(trajectory.columns.begin(), trajectory.columns.end(), column);
    REQUIRE(c != trajectory.columns.end());
    const auto index = static_cast<std::size_t>(c - trajectory.columns.begin());
    for (const std::vector<double>& frame : trajectory.frames) {
        if (frame[0] >= t) {
            return frame[index];
        }
    }
    FAIL("no frame at or after t = " << t);
    return 0.0;
}

} // namespace

TEST_CASE("corner-to-corner: the bisector bounces the squares straight back, the seed spins them",
          "[manifold][unit]") {
    harness::Scene scene = harness::load_scene(std::string(IMPULSE_SOURCE_DIR) +
                                               "/harness/scenes/corner-to-corner.json");
    REQUIRE(scene.solver.vertex_normal == VertexNormal::bisector);
    const harness::Trajectory bisector = harness::run_scene(scene);
    REQUIRE(bisector.events.size() == 1);
    CHECK(bisector.events[0].normal[0] == Approx(-1.0).epsilon(1e-15));
    CHECK(bisector.events[0].normal[1] == Approx(0.0).margin(1e-15));
    CHECK(std::abs(column_at(bisector, "left.omega", 1.5)) < 1e-14);
    CHECK(std::abs(column_at(bisector, "right.omega", 1.5)) < 1e-14);

    // The seed's normal is a face normal at 45 degrees, n = -(1, 1) / sqrt(2)
    // or -(1, -1) / sqrt(2) toward the left square, with r_AP = (sqrt(2) / 2, 0):
    // r x n = -+1/2, and with M = 1, I = 1/6, v_rel = 2:
    // j = (1 + e) (v_rel / sqrt(2)) / (2 / M + 2 (1/2)^2 / I) = 2 sqrt(2) / 5 (Eq. 9)
    // and each square turns at |r x n| j / I = 6 sqrt(2) / 5 rad/s.
    scene.solver.vertex_normal = VertexNormal::reference_face;
    const harness::Trajectory seed = harness::run_scene(scene);
    REQUIRE(!seed.events.empty());
    CHECK(std::abs(seed.events[0].normal[0]) == Approx(std::sqrt(0.5)).epsilon(1e-15));
    CHECK(seed.events[0].impulse == Approx(2.0 * std::sqrt(2.0) / 5.0).epsilon(1e-12));
    const double t_after = seed.events[0].t; // before the spinning squares meet again
    CHECK(std::abs(column_at(seed, "left.omega", t_after)) ==
          Approx(6.0 * std::sqrt(2.0) / 5.0).epsilon(1e-12));
    CHECK(std::abs(column_at(seed, "right.omega", t_after)) ==
          Approx(6.0 * std::sqrt(2.0) / 5.0).epsilon(1e-12));
}
