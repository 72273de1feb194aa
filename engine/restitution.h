// Collision response by Newton's law of restitution, instantaneous and
// frictionless (Hecker; docs/physics.md). Symbols follow the derivation.
#pragma once

#include "body.h"
#include "contact.h"

namespace impulse {

// Velocity of the point at offset r from a body's centre of mass. Eq. 7
constexpr Vec2 point_velocity(const BodyState& s, Vec2 r) {
    return s.velocity + s.angular_velocity * perp(r);
}

// v_AB . n for the point P: negative when A and B approach there. Eqs. 1, 2
double relative_normal_velocity(const Body& a, const Body& b, Vec2 P, Vec2 n);

// The impulse magnitude j that makes v2_AB . n = -e v1_AB . n (Eq. 3): Eq. 6
// (Eq. 5, Eq. 3 with Eqs. 4a and 4b put in, solved for j) when neither body
// rotates, Eq. 9 otherwise.
double impulse_magnitude(const Body& a, const Body& b, Vec2 P, Vec2 n, double e, double vn);

// The impulse applied at one contact: its magnitude along n (toward A) and the
// relative normal velocity on either side of it.
struct Impulse {
    double j = 0.0;
    double vn_before = 0.0;
    double vn_after = 0.0;
};

// Applies +j n to A and -j n to B at P: Eqs. 4a and 4b, and for a rotating
// body Eqs. 8a and 8b (negated for B).
void apply_impulse(Body& a, Body& b, Vec2 P, Vec2 n, double j);

// Resolves one approaching contact: computes j, applies it, and reports it.
Impulse resolve_collision(Body& a, Body& b, const Contact& contact, double e);

} // namespace impulse
