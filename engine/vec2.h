// Plain 2D vector algebra. Everything is constexpr and free of library calls
// except sqrt, which IEEE 754 rounds exactly on every platform.
#pragma once

#include <cmath>

namespace impulse {

struct Vec2 {
    double x = 0.0;
    double y = 0.0;
};

constexpr Vec2 operator+(Vec2 a, Vec2 b) {
    return {a.x + b.x, a.y + b.y};
}
constexpr Vec2 operator-(Vec2 a, Vec2 b) {
    return {a.x - b.x, a.y - b.y};
}
constexpr Vec2 operator-(Vec2 a) {
    return {-a.x, -a.y};
}
constexpr Vec2 operator*(double s, Vec2 a) {
    return {s * a.x, s * a.y};
}
constexpr Vec2 operator*(Vec2 a, double s) {
    return {a.x * s, a.y * s};
}
constexpr Vec2& operator+=(Vec2& a, Vec2 b) {
    return a = a + b;
}
constexpr Vec2& operator-=(Vec2& a, Vec2 b) {
    return a = a - b;
}
constexpr bool operator==(Vec2 a, Vec2 b) {
    return a.x == b.x && a.y == b.y;
}
constexpr bool operator!=(Vec2 a, Vec2 b) {
    return !(a == b);
}

constexpr double dot(Vec2 a, Vec2 b) {
    return a.x * b.x + a.y * b.y;
}
// z component of the 3D cross product of (a, 0) and (b, 0).
constexpr double cross(Vec2 a, Vec2 b) {
    return a.x * b.y - a.y * b.x;
}
// perp(r) = (-r.y, r.x): r turned a quarter counter-clockwise (docs/physics.md, Notation).
constexpr Vec2 perp(Vec2 r) {
    return {-r.y, r.x};
}
constexpr double length_squared(Vec2 a) {
    return dot(a, a);
}
inline double length(Vec2 a) {
    return std::sqrt(length_squared(a));
}

} // namespace impulse
