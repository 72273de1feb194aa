#include "contact_single.h"

#include "contact_resting.h"
#include "narrow_phase_query.h"
#include "restitution.h"

#include <array>

namespace impulse {

namespace {

// The deepest approaching point of m not yet tried (ties go to the first), or -1.
int deepest_approaching(const Body& a, const Body& b, const Manifold& m,
                        const std::array<bool, 2>& tried) {
    int chosen = -1;
    for (int i = 0; i < m.point_count; ++i) {
        const Contact& c = m.points[static_cast<std::size_t>(i)];
        if (!tried[static_cast<std::size_t>(i)] &&
            relative_normal_velocity(a, b, c.point, c.normal) < 0.0 &&
            (chosen < 0 || c.separation < m.points[static_cast<std::size_t>(chosen)].separation)) {
            chosen = i;
        }
    }
    return chosen;
}

} // namespace

bool resolve_single_contact(World& world, const Pair& pair, double time,
                            std::vector<CollisionEvent>& events) {
    Body& a = world.bodies[pair.a];
    Body& b = world.bodies[pair.b];
    const Manifold m = pair_manifold(world, pair);
    const BodyState a_before = a.state;
    const BodyState b_before = b.state;
    std::array<bool, 2> tried = {false, false};
    int first_choice = -1;
    for (int chosen = deepest_approaching(a, b, m, tried); chosen >= 0;
         chosen = deepest_approaching(a, b, m, tried)) {
        const Contact& c = m.points[static_cast<std::size_t>(chosen)];
        const Impulse impulse = resolve_collision(a, b, c, effective_restitution(world, a, b, c));
        // An approach of rounding size (1e-20 m/s beside terms of 1e-3) takes
        // an impulse that leaves it exactly as it was: no progress, and the
        // same point would be chosen again and again while another point of
        // the pair still approaches (a box landing flat at e = 0: an outside
        // review's 4096 collisions). Such a point is passed over for the next.
        if (impulse.vn_after != impulse.vn_before) {
            events.push_back({time, pair.a, pair.b, c.point, c.normal, impulse.j, impulse.vn_before,
                              impulse.vn_after});
            return true;
        }
        first_choice = first_choice < 0 ? chosen : first_choice;
        a.state = a_before;
        b.state = b_before;
        tried[static_cast<std::size_t>(chosen)] = true;
    }
    if (first_choice < 0) {
        return false;
    }
    // Every approaching point was futile: the seed's choice, as it was.
    const Contact& c = m.points[static_cast<std::size_t>(first_choice)];
    const Impulse impulse = resolve_collision(a, b, c, effective_restitution(world, a, b, c));
    events.push_back(
        {time, pair.a, pair.b, c.point, c.normal, impulse.j, impulse.vn_before, impulse.vn_after});
    return true;
}

} // namespace impulse
