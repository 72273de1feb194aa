#include "continuous_collision.h"

namespace impulse {

SweptContact first_swept_contact(World& world, const Configuration& start, double h) {
    // Placeholder until the conservative advancement lands: the seed's end-of-step test.
    Configuration at_h;
    advance_all(world, start, h, at_h);
    SweptContact swept;
    swept.pair = first_interpenetrating_pair(world, at_h);
    swept.time = h;
    return swept;
}

} // namespace impulse
