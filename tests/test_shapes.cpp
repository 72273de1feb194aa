#include "shape.h"

#include <catch2/catch.hpp>

using namespace impulse;

TEST_CASE("Box inertia is M (4a^2 + 4b^2) / 12", "[shapes]") {
    for (const auto& [a, b] : {std::pair{0.5, 0.5}, {1.0, 0.5}, {2.5, 0.05}, {50.0, 0.5}}) {
        const MassProperties mp = mass_properties(make_box(a, b));
        CHECK(mp.area == Approx(4 * a * b).epsilon(1e-15));
        CHECK(mp.centroid.x == Approx(0.0).margin(1e-15 * a));
        CHECK(mp.centroid.y == Approx(0.0).margin(1e-15 * b));
        CHECK(mp.inertia_per_unit_mass == Approx((4 * a * a + 4 * b * b) / 12.0).epsilon(1e-14));
    }
}

TEST_CASE("Disc inertia is M r^2 / 2", "[shapes]") {
    const MassProperties mp = mass_properties(make_circle(0.3));
    CHECK(mp.inertia_per_unit_mass == Approx(0.045).epsilon(1e-15));
    CHECK(mp.area == Approx(3.141592653589793 * 0.09).epsilon(1e-15));
}

TEST_CASE("Right triangle: area, centroid and polar moment by hand", "[shapes]") {
    // Legs 3 and 6 along the axes: area 9, centroid (1, 2); about the centroid
    // Ix + Iy = area (b^2 + h^2) / 18 = 9 * 45 / 18, per unit mass (b^2 + h^2)/18 = 2.5.
    const Vec2 v[3] = {{0, 0}, {3, 0}, {0, 6}};
    const MassProperties mp = mass_properties(make_polygon(v, 3));
    CHECK(mp.area == Approx(9.0).epsilon(1e-15));
    CHECK(mp.centroid.x == Approx(1.0).epsilon(1e-15));
    CHECK(mp.centroid.y == Approx(2.0).epsilon(1e-15));
    CHECK(mp.inertia_per_unit_mass == Approx(2.5).epsilon(1e-14));
}

TEST_CASE("Polygon normals are outward unit vectors", "[shapes]") {
    const Shape box = make_box(2.0, 1.0);
    REQUIRE(box.polygon.count == 4);
    CHECK(box.polygon.normals[0] == Vec2{0, -1});
    CHECK(box.polygon.normals[1] == Vec2{1, 0});
    CHECK(box.polygon.normals[2] == Vec2{0, 1});
    CHECK(box.polygon.normals[3] == Vec2{-1, 0});
}
