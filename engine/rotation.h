// A rotation stored as its cosine and sine, and the rigid transform of a body.
#pragma once

#include "vec2.h"

namespace impulse {

struct Rotation {
    double c = 1.0;
    double s = 0.0;
};

// Built with the engine's own sine and cosine (trig.h), never libm's, so the
// same angle gives the same bits on every platform (docs/design.md, Determinism rule 3).
Rotation rotation_of(double angle);

constexpr Vec2 rotate(Rotation q, Vec2 v) {
    return {q.c * v.x - q.s * v.y, q.s * v.x + q.c * v.y};
}
constexpr Vec2 inverse_rotate(Rotation q, Vec2 v) {
    return {q.c * v.x + q.s * v.y, -q.s * v.x + q.c * v.y};
}

struct Transform {
    Vec2 p;
    Rotation q;
};

constexpr Vec2 apply(const Transform& xf, Vec2 local) {
    return rotate(xf.q, local) + xf.p;
}

} // namespace impulse
