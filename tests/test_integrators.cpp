// Motion between collisions under uniform gravity, against closed forms.
#include "integrator.h"
#include "support.h"

#include <catch2/catch.hpp>

using namespace impulse;

namespace {
BodyState integrate(Integrator integrator, BodyState s, Vec2 g, double dt, int steps) {
    for (int k = 0; k < steps; ++k) {
        s = advance(integrator, s, g, true, dt);
    }
    return s;
}
} // namespace

TEST_CASE("Verlet and RK4 move a body exactly under constant gravity", "[integrators]") {
    const Vec2 g{0.3, -9.81};
    const BodyState s0{{1.0, 10.0}, 0.25, {2.0, 3.0}, 1.5};
    for (Integrator integrator : {Integrator::verlet, Integrator::rk4}) {
        for (double dt : {1.0 / 30.0, 1.0 / 60.0, 0.001}) {
            const int steps = static_cast<int>(2.0 / dt + 0.5);
            const double t = steps * dt;
            const BodyState s = integrate(integrator, s0, g, dt, steps);
            // x(t) = x0 + v0 t + g t^2 / 2 and v(t) = v0 + g t, to rounding only.
            CHECK(s.position.x == Approx(1.0 + 2.0 * t + 0.5 * g.x * t * t).epsilon(1e-12));
            CHECK(s.position.y == Approx(10.0 + 3.0 * t + 0.5 * g.y * t * t).epsilon(1e-12));
            CHECK(s.velocity.x == Approx(2.0 + g.x * t).epsilon(1e-12));
            CHECK(s.velocity.y == Approx(3.0 + g.y * t).epsilon(1e-12));
            CHECK(s.angle == Approx(0.25 + 1.5 * t).epsilon(1e-12));
        }
    }
}

TEST_CASE("Euler and symplectic Euler lag and lead by g dt t / 2", "[integrators]") {
    // Summing the updates by hand: explicit Euler gives y0 + v0 t + g dt^2 N (N - 1) / 2,
    // symplectic Euler y0 + v0 t + g dt^2 N (N + 1) / 2, with t = N dt.
    const Vec2 g{0.0, -9.81};
    const BodyState s0{{0.0, 10.0}, 0.0, {0.0, 3.0}, 0.0};
    const double dt = 1.0 / 60.0;
    const int n = 120;
    const double t = n * dt;
    const BodyState e = integrate(Integrator::euler, s0, g, dt, n);
    const BodyState se = integrate(Integrator::symplectic_euler, s0, g, dt, n);
    CHECK(e.position.y == Approx(10.0 + 3.0 * t + g.y * dt * dt * n * (n - 1) / 2).epsilon(1e-12));
    CHECK(se.position.y == Approx(10.0 + 3.0 * t + g.y * dt * dt * n * (n + 1) / 2).epsilon(1e-12));
    CHECK(e.velocity.y == Approx(3.0 + g.y * t).epsilon(1e-12));
    CHECK(se.velocity.y == Approx(3.0 + g.y * t).epsilon(1e-12));
}

TEST_CASE("Without gravity there is no force pass; without rotation no angular work",
          "[integrators]") {
    const BodyState s0{{1.0, 2.0}, 0.7, {3.0, -4.0}, 5.0};
    for (Integrator integrator :
         {Integrator::euler, Integrator::symplectic_euler, Integrator::verlet, Integrator::rk4}) {
        const BodyState s = advance(integrator, s0, {0, 0}, false, 0.125);
        CHECK(s.velocity == s0.velocity); // bit-identical
        CHECK(s.angle == s0.angle);
        CHECK(s.position == Vec2{1.0 + 0.125 * 3.0, 2.0 - 0.125 * 4.0});
    }
}
