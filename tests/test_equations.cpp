// Each equation of docs/physics.md against numbers derived by hand.
#include "restitution.h"
#include "support.h"

#include <catch2/catch.hpp>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::static_body;

TEST_CASE("Eq. 7: velocity of a point on a rotating body", "[equations]") {
    const BodyState s{{0, 0}, 0.0, {1, 2}, 3.0};
    // perp((0.5, -1)) = (1, 0.5); v + w perp(r) = (1 + 3, 2 + 1.5)
    const Vec2 v = point_velocity(s, {0.5, -1.0});
    CHECK(v.x == 4.0);
    CHECK(v.y == 3.5);
}

TEST_CASE("Eqs. 1, 2: relative normal velocity is negative when approaching", "[equations]") {
    Body a = dynamic_body(make_circle(0.5), 2.0, {1, 0}, 0.0, {-1, 0});
    Body b = dynamic_body(make_circle(0.5), 1.0, {0, 0}, 0.0, {2, 0});
    CHECK(relative_normal_velocity(a, b, {0.5, 0}, {1, 0}) == -3.0);
}

TEST_CASE("Eq. 6: non-rotating head-on impulse", "[equations]") {
    // MA = 2, MB = 1, v1_AB . n = -1 - 2 = -3, e = 0.5:
    // j = -(1.5)(-3) / (1/2 + 1) = 3; vA2 = -1 + 3/2 = 0.5; vB2 = 2 - 3 = -1.
    const Shape box = make_box(0.5, 0.5);
    Body a = dynamic_body(box, 2.0, {1, 0}, 0.0, {-1, 0}, 0.0, false);
    Body b = dynamic_body(box, 1.0, {0, 0}, 0.0, {2, 0}, 0.0, false);
    const Impulse impulse = resolve_collision(a, b, {{0.5, 0}, {1, 0}, 0.0}, 0.5);
    CHECK(impulse.vn_before == -3.0);
    CHECK(impulse.j == 3.0);
    CHECK(a.state.velocity.x == 0.5);
    CHECK(b.state.velocity.x == -1.0);
    CHECK(impulse.vn_after == 1.5); // Eq. 3: -e times -3
    CHECK(a.state.angular_velocity == 0.0);
    CHECK(b.state.angular_velocity == 0.0);
}

TEST_CASE("Eq. 9: corner impact of a rotating body on static ground", "[equations]") {
    // MA = 2, IA = 0.5, rAP = (0.5, -0.5), n = (0, 1), vA = (0, -2), e = 1.
    // perp(rAP) . n = 0.5, so the denominator is 1/2 + 0.25/0.5 = 1 and j = 2 * 2 / 1 = 4;
    // vA2 = -2 + 4/2 = 0; wA2 = 0.5 * 4 / 0.5 = 4.
    Body a = dynamic_body(make_box(0.5, 0.5), 2.0, {0, 0.5}, 0.0, {0, -2});
    a.inv_inertia = 1.0 / 0.5;
    Body ground = static_body(make_box(5, 0.5), {0, -0.5});
    const Impulse impulse = resolve_collision(a, ground, {{0.5, 0}, {0, 1}, 0.0}, 1.0);
    CHECK(impulse.j == Approx(4.0).epsilon(1e-15));
    CHECK(a.state.velocity.y == Approx(0.0).margin(1e-15));
    CHECK(a.state.angular_velocity == Approx(4.0).epsilon(1e-15));
    CHECK(impulse.vn_after == Approx(2.0).epsilon(1e-15));
    CHECK(ground.state.velocity == Vec2{});
    CHECK(ground.state.angular_velocity == 0.0);
}

TEST_CASE("Eq. 9 reduces to Eq. 6 when the lever arm is along the normal", "[equations]") {
    // A circle's contact point lies on the normal through its centre: perp(r) . n = 0.
    Body a = dynamic_body(make_circle(1.0), 3.0, {0, 1}, 0.0, {0, -4});
    Body ground = static_body(make_box(5, 0.5), {0, -0.5});
    const Impulse impulse = resolve_collision(a, ground, {{0, 0}, {0, 1}, 0.0}, 0.25);
    // j = (1 + e) v M = 1.25 * 4 * 3 = 15; vy2 = -4 + 15/3 = 1 = e * 4.
    CHECK(impulse.j == 15.0);
    CHECK(a.state.velocity.y == 1.0);
    CHECK(a.state.angular_velocity == 0.0);
}

TEST_CASE("No impulse acts on a static body and e = 0 stops the normal motion", "[equations]") {
    Body a = dynamic_body(make_box(0.5, 0.5), 1.0, {0, 0.5}, 0.0, {1, -3}, 0.0, false);
    Body ground = static_body(make_box(5, 0.5), {0, -0.5});
    const Impulse impulse = resolve_collision(a, ground, {{0, 0}, {0, 1}, 0.0}, 0.0);
    CHECK(impulse.j == 3.0);
    CHECK(a.state.velocity.y == 0.0);
    CHECK(a.state.velocity.x == 1.0); // frictionless: tangential velocity untouched
    CHECK(impulse.vn_after == 0.0);
}
