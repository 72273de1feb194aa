#include "energy_guard.h"

#include "contact_candidates.h"
#include "manifold.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

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

// True when the overlap guard marked some body of bodies[b0 .. b1) stuck.
bool stuck(const TimeSteppingScratch& s, const std::vector<int>& bodies, int b0, int b1) {
    if (s.guard_stuck.size() != s.start.size()) { // guard_overlaps did not run (a unit test)
        return false;
    }
    for (int k = b0; k < b1; ++k) {
        if (s.guard_stuck[static_cast<std::size_t>(bodies[static_cast<std::size_t>(k)])] != 0) {
            return true;
        }
    }
    return false;
}

// Body b back at its pose at the step's start, at rest, marked in s.returned.
void return_to_start(World& world, TimeSteppingScratch& s, std::size_t b) {
    world.bodies[b].state = {s.start[b].position, s.start[b].angle, {}, 0.0};
    s.returned[b] = 1;
}

// Checks the bodies bodies[b0 .. b1) together: if their energy rose beyond
// rounding from s.start to now, their velocities are scaled down to take the
// rise out, or, when their kinetic energy cannot pay for it, they go back to
// their poses at the step's start, at rest.
void check_bodies(World& world, TimeSteppingScratch& s, const std::vector<int>& bodies, int b0,
                  int b1) {
    if (stuck(s, bodies, b0, b1)) {
        // The overlap guard left one of these bodies deeper than d (overlap_guard.cpp,
        // mark_stuck): the unit goes back to x_k, at rest, whatever its energy.
        ++world.work.overlap_guard_returned;
        for (int k = b0; k < b1; ++k) {
            return_to_start(world, s,
                            static_cast<std::size_t>(bodies[static_cast<std::size_t>(k)]));
        }
        return;
    }
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
            // the previous step's guard; a body that has since moved there
            // is sent back too (return_units_met). The velocities are
            // scaled by 0 below, so their zeros keep their signs.
            state.position = s.start[b].position;
            state.angle = s.start[b].angle;
            s.returned[b] = 1;
        }
        state.velocity = factor * state.velocity;
        state.angular_velocity = factor * state.angular_velocity;
    }
}

// A unit sent back to x_k is clear of every body that stayed within the
// reach its step's pairs were found for: their boxes at the step's start did
// not meet, or the pair's points were farther apart than both reaches. A body
// that outran them (a stale step's, or one the overlap guard carried past
// them) may since stand where the unit was, and the unit, sent back, would
// overlap it unseen. So in a step whose overlap guard found its pairs again
// (s.pairs_refound: only then can a body have outrun them), when a unit went
// back, the pairs of the poses as they now are are found, and every unit met
// deeper than d by one that went back goes back as well, at rest (its energy
// P(x_k) <= E_k), until none is: at most once per unit, and x_k is the
// previous step's end, within d everywhere.
void return_units_met(World& world, TimeSteppingScratch& s) {
    const std::vector<int>& unit = s.guard_joined; // every entry its root
    const std::size_t n = world.bodies.size();
    const double d = world.solver.contact_tolerance;
    std::vector<int>& goes_back = s.energy_check; // per unit's root (reused)
    bool met =
        s.pairs_refound && std::find(s.returned.begin(), s.returned.end(), 1) != s.returned.end();
    while (met) {
        met = false;
        goes_back.assign(n, 0);
        find_pairs_around(world, 0.0, s);
        for (const CandidatePair& pair : s.pairs) {
            const std::size_t a = static_cast<std::size_t>(pair.a);
            const std::size_t b = static_cast<std::size_t>(pair.b);
            const std::size_t other = s.returned[a] != 0 ? b : a;
            if (s.returned[a] != s.returned[b] && !world.bodies[other].is_static() &&
                separation(world.bodies[a].shape, s.poses[a], world.bodies[b].shape, s.poses[b]) <
                    -d) {
                goes_back[static_cast<std::size_t>(unit[other])] = 1;
                met = true;
            }
        }
        world.work.returned_units_met += std::count(goes_back.begin(), goes_back.end(), 1);
        for (std::size_t k = 0; k < n; ++k) {
            if (goes_back[static_cast<std::size_t>(unit[k])] != 0 && !world.bodies[k].is_static()) {
                return_to_start(world, s, k);
            }
        }
    }
}

} // namespace

// The bodies checked together: an island, joined with every island a group
// of the overlap guard moved bodies of. A group can span islands (its pairs
// are the candidate pairs, an island's the candidate points); checked apart,
// one island could go back to x_k while its neighbour kept the move that
// separated them, and overlap it again (a random pile of 5 triangles: 6.1e-5
// m, where the guard had left 1e-9).
void guard_energy(World& world, TimeSteppingScratch& s) {
    const std::size_t n = world.bodies.size();
    std::vector<int>& parent = s.guard_joined;
    if (parent.size() != n) { // guard_overlaps did not run (a unit test)
        parent.resize(n);
        std::iota(parent.begin(), parent.end(), 0);
    }
    s.energy_check.assign(n, 0); // per body: to be checked
    s.returned.assign(n, 0);
    for (int i = 0; i < s.islands.count(); ++i) {
        const int b0 = s.islands.body_offsets[static_cast<std::size_t>(i)];
        const int b1 = s.islands.body_offsets[static_cast<std::size_t>(i) + 1];
        const bool check =
            s.island_pushed[static_cast<std::size_t>(i)] != 0 || moved_by_guard(s, b0, b1);
        for (int k = b0; k < b1; ++k) {
            const int b = s.islands.bodies[static_cast<std::size_t>(k)];
            join_bodies(parent, s.islands.bodies[static_cast<std::size_t>(b0)], b);
            s.energy_check[static_cast<std::size_t>(b)] = check ? 1 : 0;
        }
    }
    for (std::size_t b = 0; b < n; ++b) { // every parent now its root
        parent[b] = joined_root(parent, static_cast<int>(b));
    }
    for (std::size_t b = 0; b < n; ++b) { // a unit with one body to check is checked
        if (s.guard_moved[b] != 0 || s.energy_check[b] != 0 ||
            (s.guard_stuck.size() == n && s.guard_stuck[b] != 0)) {
            s.energy_check[static_cast<std::size_t>(parent[b])] = 1;
        }
    }
    s.energy_units.clear();
    for (std::size_t b = 0; b < n; ++b) {
        if (!world.bodies[b].is_static() &&
            s.energy_check[static_cast<std::size_t>(parent[b])] != 0) {
            s.energy_units.push_back(static_cast<int>(b));
        }
    }
    std::stable_sort(s.energy_units.begin(), s.energy_units.end(), [&parent](int x, int y) {
        return parent[static_cast<std::size_t>(x)] < parent[static_cast<std::size_t>(y)];
    });
    for (std::size_t u = 0; u < s.energy_units.size();) {
        const int root = parent[static_cast<std::size_t>(s.energy_units[u])];
        std::size_t end = u + 1;
        while (end < s.energy_units.size() &&
               parent[static_cast<std::size_t>(s.energy_units[end])] == root) {
            ++end;
        }
        const std::size_t b = static_cast<std::size_t>(s.energy_units[u]);
        if (end == u + 1 && s.in_island[b] == 0) {
            ++world.work.energy_guard_lone_bodies;
        }
        check_bodies(world, s, s.energy_units, static_cast<int>(u), static_cast<int>(end));
        u = end;
    }
    return_units_met(world, s);
}

} // namespace impulse
