#include "energy_guard.h"

#include <cmath>
#include <limits>

namespace impulse {

namespace {

struct Energy {
    double kinetic = 0.0;
    double total = 0.0;
    double magnitude = 0.0; // sum of |terms|: the scale of its rounding
};

void add_energy(const Body& body, const BodyState& state, Vec2 gravity, Energy& e) {
    const double m = 1.0 / body.inv_mass;
    double k = 0.5 * m * length_squared(state.velocity);
    if (body.rotates()) {
        k += 0.5 * (1.0 / body.inv_inertia) * state.angular_velocity * state.angular_velocity;
    }
    const double p = -m * dot(gravity, state.position);
    e.kinetic += k;
    e.total += k + p;
    e.magnitude += k + std::abs(p);
}

// True when the overlap guard moved some body of bodies[b0 .. b1).
bool moved_by_guard(const TimeSteppingScratch& s, int b0, int b1) {
    for (int k = b0; k < b1; ++k) {
        if (s.guard_moved[static_cast<std::size_t>(
                s.islands.bodies[static_cast<std::size_t>(k)])] != 0) {
            return true;
        }
    }
    return false;
}

// Checks the bodies bodies[b0 .. b1) together: if their energy rose beyond
// rounding from s.start to now, their velocities are scaled down to take the
// rise out, or, when their kinetic energy cannot pay for it, they go back to
// their poses at the step's start, at rest.
void check_bodies(World& world, TimeSteppingScratch& s, const std::vector<int>& bodies, int b0,
                  int b1) {
    constexpr double rounding = 8.0 * std::numeric_limits<double>::epsilon();
    Energy before;
    Energy after;
    for (int k = b0; k < b1; ++k) {
        const std::size_t b = static_cast<std::size_t>(bodies[static_cast<std::size_t>(k)]);
        add_energy(world.bodies[b], s.start[b], world.gravity, before);
        add_energy(world.bodies[b], world.bodies[b].state, world.gravity, after);
    }
    const double gained = after.total - before.total;
    if (!(gained > rounding * (before.magnitude + after.magnitude))) {
        return;
    }
    ++world.work.energy_guard_steps;
    world.work.energy_guard_joules += gained;
    const bool scale = after.kinetic > gained;
    ++(scale ? world.work.energy_guard_rescaled : world.work.energy_guard_returned);
    const double factor = scale ? std::sqrt(1.0 - gained / after.kinetic) : 0.0;
    for (int k = b0; k < b1; ++k) {
        const std::size_t b = static_cast<std::size_t>(bodies[static_cast<std::size_t>(k)]);
        BodyState& state = world.bodies[b].state;
        if (!scale) {
            // Kinetic energy cannot pay for the rise (a near-rest island
            // the overlap guard lifted): the bodies stay at x_k, whose
            // energy is at most E_k, at rest. x_k kept its overlaps within
            // the previous step's guard, and the bodies stayed inside reach
            // boxes no other body's box met.
            state.position = s.start[b].position;
            state.angle = s.start[b].angle;
        }
        state.velocity = factor * state.velocity;
        state.angular_velocity = factor * state.angular_velocity;
    }
}

} // namespace

void guard_energy(World& world, TimeSteppingScratch& s) {
    for (int i = 0; i < s.islands.count(); ++i) {
        const int b0 = s.islands.body_offsets[static_cast<std::size_t>(i)];
        const int b1 = s.islands.body_offsets[static_cast<std::size_t>(i) + 1];
        if (s.island_pushed[static_cast<std::size_t>(i)] == 0 && !moved_by_guard(s, b0, b1)) {
            continue; // free flight by the integrator: its own energy behaviour
        }
        check_bodies(world, s, s.islands.bodies, b0, b1);
    }
    // A body in no island (a candidate pair without points) that the overlap
    // guard moved is checked on its own: every position move is checked.
    for (std::size_t b = 0; b < world.bodies.size(); ++b) {
        if (s.guard_moved[b] != 0 && s.in_island[b] == 0) {
            ++world.work.energy_guard_lone_bodies;
            s.lone_body.assign(1, static_cast<int>(b));
            check_bodies(world, s, s.lone_body, 0, 1);
        }
    }
}

} // namespace impulse
