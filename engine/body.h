// Rigid bodies: plain data, held by the world in one array and named by index.
#pragma once

#include "rotation.h"
#include "shape.h"

namespace impulse {

struct BodyState {
    Vec2 position; // of the centre of mass, world coordinates
    double angle = 0.0;
    Vec2 velocity;
    double angular_velocity = 0.0;
};

// Static bodies have inv_mass = inv_inertia = 0 (infinite mass, docs/physics.md);
// non-rotating dynamic bodies have inv_inertia = 0 (infinite inertia).
struct Body {
    BodyState state;
    Shape shape;
    double inv_mass = 0.0;
    double inv_inertia = 0.0;

    bool is_static() const { return inv_mass == 0.0; }
    bool rotates() const { return inv_inertia != 0.0; }
};

inline Transform transform_of(const BodyState& s) {
    return {s.position, rotation_of(s.angle)};
}

} // namespace impulse
