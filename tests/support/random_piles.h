// Seeded random piles for the dense-contact tests (test_dense_contact.cpp,
// test_dense_sweeps.cpp): discs, boxes and regular polygons of random sizes
// and masses dropped into a V, and the check that runs one, step by step,
// against every invariant of dense contact (docs/engine.md, "Dense contact").
#pragma once

#include "../support.h"
#include "contact_candidates.h"
#include "manifold.h"
#include "world.h"

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

namespace impulse::test::piles {

constexpr double g = 9.81;
constexpr double h60 = 1.0 / 60.0;

inline double mass_of(const Body& body) {
    return 1.0 / body.inv_mass;
}

// One seeded random pile of the property sweep: `count` bodies (discs, boxes
// and regular 3- to 6-gons, sizes 1:5, masses 1:100) at rest on a lattice of
// k x k sites (k * k >= count), each shifted at random within its site so
// that no column is a balanced (unstable) tower, above a V-shaped floor
// between two walls. The floor is slanted (15 degrees each way) because a
// body sliding on a flat frictionless floor keeps its speed until it meets
// something: such a pile is not at rest at any time, and no contact model
// can make it so.
struct PileCase {
    std::uint64_t seed = 1;
    int count = 5;
    double e = 0.0;
    Integrator integrator = Integrator::verlet;
    Stepping stepping = Stepping::world;
};

inline Shape random_shape(std::mt19937_64& rng, double size) {
    const double kind = test::uniform(rng, 0.0, 3.0);
    if (kind < 1.0) {
        return make_circle(size);
    }
    if (kind < 2.0) {
        return make_box(size, size * test::uniform(rng, 0.5, 1.0));
    }
    const int sides = 3 + static_cast<int>(test::uniform(rng, 0.0, 4.0));
    std::array<Vec2, 6> vertices{};
    for (int i = 0; i < sides; ++i) {
        const double angle = 2.0 * 3.141592653589793 * i / sides;
        vertices[static_cast<std::size_t>(i)] = {size * std::cos(angle), size * std::sin(angle)};
    }
    return make_polygon(vertices.data(), sides);
}

struct PileLayout {
    int columns = 1;
    double spacing = 0.6;    // more than every bounding diameter (a 0.2 x 0.2 box: 0.566)
    double half_width = 0.3; // the walls' inner faces are at x = +-half_width
    double floor_slope = 0.2617993877991494; // 15 degrees
    double lattice_base = 0.0;               // the V's height at the walls: row 0 sits above it
    // The top row's height above the V's lowest point, where a body can fall to.
    double top(int count) const {
        const int rows = (count + columns - 1) / columns;
        return lattice_base + spacing * (rows - 0.5);
    }
};

inline PileLayout layout_of(int count) {
    PileLayout layout;
    while (layout.columns * layout.columns < count) {
        ++layout.columns;
    }
    layout.half_width = 0.5 * layout.columns * layout.spacing;
    layout.lattice_base = layout.half_width * std::tan(layout.floor_slope);
    return layout;
}

inline double bounding_radius(const Shape& shape) {
    return shape.type == ShapeType::circle ? shape.radius : rotation_radius(shape);
}

inline World random_pile(const PileCase& pile) {
    std::mt19937_64 rng(pile.seed);
    const PileLayout layout = layout_of(pile.count);
    const double w = layout.half_width;
    const double slope = layout.floor_slope;
    // Two slabs whose top faces meet at the origin, each running past the
    // wall, then two walls: static bodies may overlap.
    const double reach = w / std::cos(slope) + 0.5;
    const Vec2 down_right{std::cos(slope), -std::sin(slope)};
    const Vec2 up_right{std::cos(slope), std::sin(slope)};
    const Vec2 left_normal{std::sin(slope), std::cos(slope)};
    const Vec2 right_normal{-std::sin(slope), std::cos(slope)};
    std::vector<Body> bodies{
        static_body(make_box(reach, 0.5), -(reach - 0.05) * down_right - 0.5 * left_normal, -slope),
        static_body(make_box(reach, 0.5), (reach - 0.05) * up_right - 0.5 * right_normal, slope),
        static_body(make_box(0.5, 10.0), {-w - 0.5, 10.0}),
        static_body(make_box(0.5, 10.0), {w + 0.5, 10.0})};
    for (int i = 0; i < pile.count; ++i) {
        const double size = test::uniform(rng, 0.04, 0.2);
        const Shape shape = random_shape(rng, size);
        const double mass = test::log_uniform(rng, 0.1, 10.0);
        // Kept in its site at any angle: by its bounding circle (a box's
        // corner reaches past its half size).
        const double room = 0.5 * layout.spacing - bounding_radius(shape);
        const double x =
            -w + layout.spacing * ((i % layout.columns) + 0.5) + test::uniform(rng, -room, room);
        const double y = layout.lattice_base + layout.spacing * ((i / layout.columns) + 0.5);
        const double angle = test::uniform(rng, -3.141592653589793, 3.141592653589793);
        bodies.push_back(dynamic_body(shape, mass, {x, y}, angle));
    }
    return make_world(std::move(bodies), {0.0, -g}, pile.e,
                      time_stepping(pile.integrator, pile.stepping));
}

// How long the pile is given to come to rest: 8 s, or, when more, the time a
// single drop from the pile's top needs to end its bounces, t1 (1 + e) / (1 -
// e) (docs/physics.md, "Drop": t_inf = t1 + 2 e v1 / (g (1 - e))), plus 2 s.
// At e = 0.9 from 2.7 m that is 16 s: a lone body would bounce that long.
inline int steps_to_rest(const PileCase& pile) {
    const double t1 = std::sqrt(2.0 * layout_of(pile.count).top(pile.count) / g);
    const double seconds = std::max(8.0, t1 * (1.0 + pile.e) / (1.0 - pile.e) + 2.0);
    return static_cast<int>(std::ceil(seconds / h60));
}

// The deepest interpenetration (-separation, 0 when nothing overlaps) of any
// pair with a dynamic body, by the engine's own narrow phase; pairs whose
// bounding circles are apart cannot overlap and are skipped.
inline double deepest_overlap(const World& world) {
    double deepest = 0.0;
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
        for (std::size_t j = i + 1; j < world.bodies.size(); ++j) {
            const Body& p = world.bodies[i];
            const Body& q = world.bodies[j];
            if (p.is_static() && q.is_static()) {
                continue;
            }
            const double reach = bounding_radius(p.shape) + bounding_radius(q.shape);
            if (length_squared(p.state.position - q.state.position) > reach * reach) {
                continue;
            }
            deepest = std::max(deepest, -separation(p.shape, transform_of(p.state), q.shape,
                                                    transform_of(q.state)));
        }
    }
    return deepest;
}

struct Energy {
    double kinetic = 0.0;
    double potential = 0.0;
    double scale = 0.0; // the sum of the terms' magnitudes, for rounding
    double total() const { return kinetic + potential; }
};

inline Energy energy_of(const World& world) {
    Energy energy;
    for (const Body& b : world.bodies) {
        if (b.is_static()) {
            continue;
        }
        const double m = mass_of(b);
        const double inertia = b.rotates() ? 1.0 / b.inv_inertia : 0.0;
        const double k = 0.5 * m * length_squared(b.state.velocity) +
                         0.5 * inertia * b.state.angular_velocity * b.state.angular_velocity;
        const double p = -m * dot(world.gravity, b.state.position);
        energy.kinetic += k;
        energy.potential += p;
        energy.scale += k + std::abs(p);
    }
    return energy;
}

inline bool finite(const World& world) {
    for (const Body& b : world.bodies) {
        const BodyState& s = b.state;
        if (!std::isfinite(s.position.x) || !std::isfinite(s.position.y) ||
            !std::isfinite(s.angle) || !std::isfinite(s.velocity.x) ||
            !std::isfinite(s.velocity.y) || !std::isfinite(s.angular_velocity)) {
            return false;
        }
    }
    return true;
}

// Explicit Euler's own gain in free flight under gravity, m |g|^2 h^2 / 2 per
// body per step (docs/physics.md, "Integrators"); the other integrators gain
// nothing in flight.
inline double free_flight_gain(const World& world, double h) {
    if (world.solver.integrator != Integrator::euler) {
        return 0.0;
    }
    double gain = 0.0;
    for (const Body& b : world.bodies) {
        if (!b.is_static()) {
            gain += 0.5 * mass_of(b) * length_squared(world.gravity) * h * h;
        }
    }
    return gain;
}

// Runs the pile at 60 Hz, checking every step: finite, no overlap deeper than
// 1e-6 m, energy not gained beyond rounding (and Euler's own flight), and the
// engine's fallback counters consistent. With rest_by > 0 it runs to rest_by
// + 1 s and requires the pile at rest over that last second, as the at-rest
// expectation does: kinetic energy at most 1e-9 of the energy the fall
// released, E(0) - P(t), at every step.
inline void check_pile_settles(const PileCase& pile, double rest_by) {
    World world = random_pile(pile);
    INFO("seed " << pile.seed << ", " << pile.count << " bodies, e " << pile.e << ", integrator "
                 << static_cast<int>(pile.integrator) << ", stepping "
                 << static_cast<int>(pile.stepping));
    const Energy start = energy_of(world);
    Energy last = start;
    std::vector<CollisionEvent> events;
    double deepest = 0.0;
    double worst_gain = 0.0;
    double moving_at = 0.0; // the last time the pile was not at rest
    const int steps =
        rest_by > 0.0 ? static_cast<int>(std::ceil((rest_by + 1.0) / h60)) : steps_to_rest(pile);
    for (int k = 0; k < steps; ++k) {
        if (const std::optional<StepError> error = step(world, k * h60, h60, events)) {
            FAIL_CHECK("step " << k << " failed (StepFailure " << static_cast<int>(error->failure)
                               << ") between bodies " << error->body_a << " and " << error->body_b);
            return;
        }
        if (!finite(world)) {
            FAIL_CHECK("a body's state is not finite after step " << k);
            return;
        }
        deepest = std::max(deepest, deepest_overlap(world));
        const Energy now = energy_of(world);
        const double allowed =
            1e-12 * std::max(now.scale, last.scale) + free_flight_gain(world, h60);
        worst_gain = std::max(worst_gain, (now.total() - last.total()) - allowed);
        if (now.kinetic > 1e-9 * (start.total() - now.potential)) {
            moving_at = (k + 1) * h60;
        }
        last = now;
    }
    const WorkCounters& work = world.work;
    INFO("deepest overlap " << deepest << " m, worst energy gain beyond rounding " << worst_gain
                            << " J; engine: " << work.unconverged_islands
                            << " unconverged islands, " << work.overlap_guard_passes
                            << " guard passes, " << work.overlap_guard_unsolved
                            << " unsolved guard groups, " << work.energy_guard_steps
                            << " energy-guard steps (" << work.energy_guard_rescaled
                            << " rescaled, " << work.energy_guard_returned << " returned to x_k, "
                            << work.energy_guard_lone_bodies << " lone bodies)");
    CHECK(deepest <= 1e-6);
    CHECK(worst_gain <= 0.0);
    // Every energy-guard action took one of its two paths.
    CHECK(work.energy_guard_rescaled + work.energy_guard_returned == work.energy_guard_steps);
    INFO("kinetic " << last.kinetic << " J of " << start.total() - last.potential
                    << " J released; last moving at t = " << moving_at << " s");
    if (rest_by > 0.0) {
        CHECK(moving_at <= rest_by);
    }
}

inline std::vector<PileCase> sweep_cases(int count, std::uint64_t first_seed) {
    const std::array<double, 4> restitutions{0.0, 0.3, 0.6, 0.9};
    const std::array<Integrator, 4> integrators{Integrator::euler, Integrator::symplectic_euler,
                                                Integrator::verlet, Integrator::rk4};
    std::vector<PileCase> cases;
    std::mt19937_64 rng(first_seed);
    for (int i = 0; i < count; ++i) {
        PileCase pile;
        pile.seed = first_seed + static_cast<std::uint64_t>(i);
        pile.count = 5 + static_cast<int>(test::uniform(rng, 0.0, 36.0)); // 5 to 40
        pile.integrator = integrators[static_cast<std::size_t>(i % 4)];
        pile.stepping = (i / 4) % 2 == 0 ? Stepping::world : Stepping::local;
        pile.e = restitutions[static_cast<std::size_t>((i + i / 8) % 4)];
        cases.push_back(pile);
    }
    return cases;
}

} // namespace impulse::test::piles
