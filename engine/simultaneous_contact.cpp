#include "simultaneous_contact.h"

namespace impulse {

SimultaneousResult resolve_simultaneous_contacts(World& world, double time,
                                                 std::vector<CollisionEvent>& events) {
    (void)world;
    (void)time;
    (void)events;
    return {}; // placeholder until the LCP lands
}

} // namespace impulse
