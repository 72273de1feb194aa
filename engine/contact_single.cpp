#include "contact_single.h"

#include "contact_resting.h"
#include "narrow_phase_query.h"
#include "restitution.h"

namespace impulse {

bool resolve_single_contact(World& world, const Pair& pair, double time,
                            std::vector<CollisionEvent>& events) {
    Body& a = world.bodies[pair.a];
    Body& b = world.bodies[pair.b];
    const Manifold m = pair_manifold(world, pair);
    int chosen = -1;
    for (int i = 0; i < m.point_count; ++i) {
        const Contact& c = m.points[i];
        if (relative_normal_velocity(a, b, c.point, c.normal) < 0.0 &&
            (chosen < 0 || c.separation < m.points[chosen].separation)) {
            chosen = i;
        }
    }
    if (chosen < 0) {
        return false;
    }
    const Contact& c = m.points[chosen];
    const Impulse impulse = resolve_collision(a, b, c, effective_restitution(world, a, b, c));
    events.push_back(
        {time, pair.a, pair.b, c.point, c.normal, impulse.j, impulse.vn_before, impulse.vn_after});
    return true;
}

} // namespace impulse
