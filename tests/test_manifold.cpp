// Narrow phase: separation, contact points and the normal's direction.
#include "manifold.h"

#include <catch2/catch.hpp>

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
