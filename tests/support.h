// Small builders shared by the physics tests.
#pragma once

#include "shape.h"
#include "world.h"

#include <cmath>
#include <random>
#include <vector>

namespace impulse::test {

inline Body dynamic_body(const Shape& shape, double mass, Vec2 position, double angle = 0.0,
                         Vec2 velocity = {}, double angular_velocity = 0.0, bool rotates = true) {
    Body body;
    body.shape = shape;
    body.state = {position, angle, velocity, angular_velocity};
    body.inv_mass = 1.0 / mass;
    body.inv_inertia = rotates ? 1.0 / (mass * mass_properties(shape).inertia_per_unit_mass) : 0.0;
    return body;
}

inline Body static_body(const Shape& shape, Vec2 position, double angle = 0.0) {
    Body body;
    body.shape = shape;
    body.state = {position, angle, {}, 0.0};
    return body;
}

// Uniform double in [lo, hi) from the generator's raw bits, so the sequence is
// the same with every standard library (std::uniform_real_distribution is not).
inline double uniform(std::mt19937_64& rng, double lo, double hi) {
    const double unit = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * unit;
}

// log-uniform in [lo, hi): for mass ratios and speeds spanning decades.
inline double log_uniform(std::mt19937_64& rng, double lo, double hi) {
    return lo * std::pow(hi / lo, uniform(rng, 0.0, 1.0));
}

inline bool close_relative(double value, double exact, double rel, double scale = 0.0) {
    const double reference = std::fabs(exact) > scale ? std::fabs(exact) : scale;
    return std::fabs(value - exact) <= rel * reference;
}

// Drop from contact gap h0 under gravity g (docs/physics.md, written out by hand
// here so the tests do not check the harness with its own formulas):
// t1 = sqrt(2 h0 / g), v1 = g t1, impact n + 1 at t1 + sum_{k=1..n} 2 e^k v1 / g,
// rebound speed e^n v1, apex gap e^(2n) h0, all impacts over at t_inf.
struct Drop {
    double h0, g, e;
    double t1() const { return std::sqrt(2.0 * h0 / g); }
    double v1() const { return g * t1(); }
    double impact_time(int n) const { // n = 1, 2, ...
        double t = t1();
        double ek = 1.0;
        for (int k = 1; k < n; ++k) {
            ek *= e;
            t += 2.0 * ek * v1() / g;
        }
        return t;
    }
    double t_inf() const { return t1() + 2.0 * v1() * e / (g * (1.0 - e)); }
    // Halfway between impacts n and n + 1: a run this long sees exactly n impacts.
    double duration(int n) const {
        return impact_time(n) + 0.5 * (impact_time(n + 1) - impact_time(n));
    }
};

// The corner of a box of half extents a x b turned by `angle` that flat
// ground below touches first, relative to the box's centre.
inline Vec2 lowest_corner(double a, double b, double angle) {
    const Rotation q = rotation_of(angle);
    Vec2 lowest = rotate(q, {a, b});
    for (Vec2 corner : {Vec2{-a, b}, Vec2{-a, -b}, Vec2{a, -b}}) {
        const Vec2 w = rotate(q, corner);
        if (w.y < lowest.y) {
            lowest = w;
        }
    }
    return lowest;
}

// That corner, rx from the centre along x, landing at speed v on static
// ground (docs/physics.md, Eq. 9 for one point):
// j = (1 + e) v / (1/M + rx^2 / I), with I = M (4a^2 + 4b^2) / 12.
struct CornerLanding {
    double a, b, mass, e, rx;
    double inertia() const { return mass * (4 * a * a + 4 * b * b) / 12.0; }
    double impulse(double v) const { return (1.0 + e) * v / (1.0 / mass + rx * rx / inertia()); }
};

// Runs the world step by step from t = 0 until `steps` are done or an error.
inline std::vector<CollisionEvent> run_steps(World& world, double dt, long long steps) {
    std::vector<CollisionEvent> events;
    for (long long k = 0; k < steps; ++k) {
        if (step(world, static_cast<double>(k) * dt, dt, events)) {
            break;
        }
    }
    return events;
}

// Dense contact by time-stepping from t = 0 (docs/engine.md, "Dense contact"),
// with the secant search its event steps would use.
inline SolverSettings time_stepping(Integrator integrator = Integrator::verlet,
                                    Stepping stepping = Stepping::world) {
    SolverSettings solver;
    solver.integrator = integrator;
    solver.toi = TimeOfImpactMethod::secant;
    solver.stepping = stepping;
    solver.resting = true;
    solver.resting_method = RestingMethod::time_stepping;
    return solver;
}

} // namespace impulse::test
