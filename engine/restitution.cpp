#include "restitution.h"

namespace impulse {

double relative_normal_velocity(const Body& a, const Body& b, Vec2 P, Vec2 n) {
    const Vec2 rAP = P - a.state.position;
    const Vec2 rBP = P - b.state.position;
    const Vec2 vAB = point_velocity(a.state, rAP) - point_velocity(b.state, rBP); // Eq. 1
    return dot(vAB, n);                                                           // Eq. 2
}

double impulse_magnitude(const Body& a, const Body& b, Vec2 P, Vec2 n, double e, double vn) {
    // Eq. 6 (Eq. 5 solved for j) when neither body rotates: its denominator.
    double k = dot(n, n) * (a.inv_mass + b.inv_mass);
    if (a.rotates() || b.rotates()) {
        // Eq. 9: each rotating body adds (perp(r) . n)^2 / I.
        const double rnA = dot(perp(P - a.state.position), n);
        const double rnB = dot(perp(P - b.state.position), n);
        k += rnA * rnA * a.inv_inertia + rnB * rnB * b.inv_inertia;
    }
    return -(1.0 + e) * vn / k;
}

void apply_impulse(Body& a, Body& b, Vec2 P, Vec2 n, double j) {
    const Vec2 jn = j * n;
    a.state.velocity += a.inv_mass * jn; // Eq. 4a, which Eq. 8a repeats for a rotating body
    b.state.velocity -= b.inv_mass * jn; // Eq. 4b
    if (a.rotates()) {
        a.state.angular_velocity += dot(perp(P - a.state.position), jn) * a.inv_inertia; // Eq. 8b
    }
    if (b.rotates()) {
        b.state.angular_velocity -= dot(perp(P - b.state.position), jn) * b.inv_inertia;
    }
}

Impulse resolve_collision(Body& a, Body& b, const Contact& contact, double e) {
    Impulse impulse;
    impulse.vn_before = relative_normal_velocity(a, b, contact.point, contact.normal);
    impulse.j = impulse_magnitude(a, b, contact.point, contact.normal, e, impulse.vn_before);
    apply_impulse(a, b, contact.point, contact.normal, impulse.j);
    impulse.vn_after = relative_normal_velocity(a, b, contact.point, contact.normal);
    return impulse;
}

} // namespace impulse
