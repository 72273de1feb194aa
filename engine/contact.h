// A contact between two bodies and the record of a resolved collision.
#pragma once

#include "vec2.h"

namespace impulse {

// Convention, stated once: the normal n is a unit vector pointing toward body A
// (Hecker; docs/physics.md, Notation). separation is the signed gap along n at the
// contact point: negative when the bodies interpenetrate.
struct Contact {
    Vec2 point;
    Vec2 normal;
    double separation = 0.0;
};

// One collision resolved by the engine, as the trajectory records it.
struct CollisionEvent {
    double time = 0.0;
    int body_a = -1;
    int body_b = -1;
    Vec2 point;
    Vec2 normal;            // toward body_a
    double impulse = 0.0;   // j, Eq. 6 or Eq. 9
    double vn_before = 0.0; // v1_AB . n, negative (Eq. 2)
    double vn_after = 0.0;  // v2_AB . n
};

} // namespace impulse
