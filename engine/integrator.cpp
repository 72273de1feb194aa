#include "integrator.h"

namespace impulse {

namespace {

// The seed's explicit Euler: position moves with the velocity at the start.
BodyState advance_euler(const BodyState& s, Vec2 g, double h) {
    BodyState next = s;
    next.position = s.position + h * s.velocity;
    next.velocity = s.velocity + h * g;
    return next;
}

// Box2D's integrator: velocity first, then position with the new velocity.
BodyState advance_symplectic_euler(const BodyState& s, Vec2 g, double h) {
    BodyState next = s;
    next.velocity = s.velocity + h * g;
    next.position = s.position + h * next.velocity;
    return next;
}

// Velocity Verlet; exact for constant acceleration.
BodyState advance_verlet(const BodyState& s, Vec2 g, double h) {
    BodyState next = s;
    next.position = s.position + h * s.velocity + (0.5 * h * h) * g;
    next.velocity = s.velocity + h * g;
    return next;
}

// Classical fourth-order Runge-Kutta on (x, v)' = (v, g); exact for constant
// acceleration, written out stage by stage so it stays RK4 if forces grow.
BodyState advance_rk4(const BodyState& s, Vec2 g, double h) {
    const Vec2 k1x = s.velocity;
    const Vec2 k2x = s.velocity + (0.5 * h) * g;
    const Vec2 k3x = s.velocity + (0.5 * h) * g;
    const Vec2 k4x = s.velocity + h * g;
    const Vec2 k1v = g, k2v = g, k3v = g, k4v = g;
    BodyState next = s;
    next.position = s.position + (h / 6.0) * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    next.velocity = s.velocity + (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    return next;
}

} // namespace

BodyState advance(Integrator integrator, const BodyState& state, Vec2 gravity, bool rotates,
                  double h) {
    BodyState next = state;
    if (gravity == Vec2{}) {
        // Without a force every integrator reduces to uniform motion.
        next.position = state.position + h * state.velocity;
    } else {
        switch (integrator) {
        case Integrator::euler:
            next = advance_euler(state, gravity, h);
            break;
        case Integrator::symplectic_euler:
            next = advance_symplectic_euler(state, gravity, h);
            break;
        case Integrator::verlet:
            next = advance_verlet(state, gravity, h);
            break;
        case Integrator::rk4:
            next = advance_rk4(state, gravity, h);
            break;
        }
    }
    if (rotates) {
        // No torque acts between collisions, so omega is constant for every integrator.
        next.angle = state.angle + h * state.angular_velocity;
    }
    return next;
}

namespace {

// The angular update under a constant angular acceleration alpha, each
// integrator's own rule applied to (angle, omega) as to (position, velocity).
void advance_angle(Integrator integrator, const BodyState& s, double alpha, double h,
                   BodyState& next) {
    switch (integrator) {
    case Integrator::euler:
        next.angle = s.angle + h * s.angular_velocity;
        next.angular_velocity = s.angular_velocity + h * alpha;
        return;
    case Integrator::symplectic_euler:
        next.angular_velocity = s.angular_velocity + h * alpha;
        next.angle = s.angle + h * next.angular_velocity;
        return;
    case Integrator::verlet:
    case Integrator::rk4: // RK4 on (angle, omega)' = (omega, alpha) reduces to the exact quadratic
        next.angle = s.angle + h * s.angular_velocity + (0.5 * h * h) * alpha;
        next.angular_velocity = s.angular_velocity + h * alpha;
        return;
    }
}

} // namespace

BodyState advance_under(Integrator integrator, const BodyState& state,
                        const Acceleration& acceleration, bool rotates, double h) {
    BodyState next = advance(integrator, state, acceleration.linear, rotates, h);
    if (rotates && acceleration.angular != 0.0) {
        advance_angle(integrator, state, acceleration.angular, h, next);
    }
    return next;
}

} // namespace impulse
