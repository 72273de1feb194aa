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

} // namespace impulse::test
