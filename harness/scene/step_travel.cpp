#include "step_travel.h"

#include "contact_candidates.h"
#include "input_error.h"
#include "scene_reading.h"
#include "text.h"

#include <cmath>
#include <string>

namespace impulse::harness {

namespace {

bool holds_by_time_stepping(const SolverSettings& solver) {
    return solver.resting && solver.resting_method != RestingMethod::events;
}

std::string travel_limit_text(const Scene& scene, double limit) {
    return sentence_number(limit) + " m (2^48 times solver.contact_tolerance " +
           sentence_number(scene.solver.contact_tolerance) + " m";
}

// A body's initial travel in one step: its speed plus its farthest point's
// turning speed, times dt.
double step_travel(Vec2 velocity, double angular_velocity, const Shape& shape, double dt) {
    return (std::hypot(velocity.x, velocity.y) +
            rotation_radius(shape) * std::fabs(angular_velocity)) *
           dt;
}

void refuse_travel(const Scene& scene, const std::string& path, const std::string& who,
                   double travel, double limit) {
    throw InputError(scene.file, path,
                     "moves " + who + " " + sentence_number(travel) +
                         " m in its first step of dt = " + sentence_number(scene.dt) +
                         " s, but time-stepping contact holds a pair to the contact tolerance "
                         "only for a step's travel within " +
                         travel_limit_text(scene, limit) +
                         ": the contact impulse that stops it leaves |v| dt 2^-52 per step); use "
                         "a smaller speed or dt, or a larger solver.contact_tolerance");
}

} // namespace

// A body resting in a time-stepping island gets gravity's kick |g| dt each
// step and a contact impulse that cancels it (docs/engine.md, "Dense
// contact"): its new velocity is the difference of two numbers of size
// |g| dt, held to within |g| dt 2^-52, so its position drifts by up to
// |g| dt^2 2^-52 per step. Within 2^48 contact tolerances (the box's limit,
// resolvable_extent.cpp) that is 1/16 of the tolerance or less; beyond it
// the contact cannot hold a body to its tolerance, and at 1e200 m/s^2 the
// first step left pairs 0.29 m deep and every energy NaN. The event model
// ("events") has no such cancellation and is bounded by the tunnelling
// refusal instead.
void refuse_unresolvable_step_fall(const Scene& scene) {
    const SolverSettings& solver = scene.solver;
    if (!holds_by_time_stepping(solver)) {
        return;
    }
    // hypot, not length: |g| beyond 1e154 would square to inf.
    const double fall = std::hypot(scene.gravity.x, scene.gravity.y) * scene.dt * scene.dt;
    const double limit = scene_reading::resolvable_extent(solver.contact_tolerance);
    if (fall <= limit) {
        return;
    }
    throw InputError(
        scene.file, "gravity",
        "gives a fall of |g| dt^2 = " + sentence_number(fall) +
            " m per step of dt = " + sentence_number(scene.dt) +
            " s, but time-stepping contact, which cancels gravity's kick at every step, holds "
            "positions to the contact tolerance only for a fall within " +
            travel_limit_text(scene, limit) +
            ": the cancellation leaves |g| dt^2 2^-52 per step); use a smaller gravity or "
            "dt, or a larger solver.contact_tolerance");
}

// The same cancellation for a body's own speed: a contact that stops a body
// moving at |v| leaves a velocity held to |v| 2^-52, so the holding problem
// cannot be solved closer than that, and beyond 2^48 contact tolerances per
// step its residual d / 32h is below rounding. Found by an outside review: a
// disc given 1e20 m/s (or 1e155) in the 20-disc pile stopped at t = 0 with
// "use a smaller dt", which could not help; measured, 1e7 m/s (1.7e5 m per
// step at dt = 1/60) runs and 3e7 m/s (5e5 m) stops. Every listed dynamic
// body is checked, and a gas's fastest draw (a pile starts at rest).
void refuse_unresolvable_step_speed(const Scene& scene) {
    if (!holds_by_time_stepping(scene.solver)) {
        return;
    }
    const double limit = scene_reading::resolvable_extent(scene.solver.contact_tolerance);
    for (std::size_t i = 0; i < scene.listed_bodies; ++i) {
        const SceneBody& body = scene.bodies[i];
        if (body.is_static) {
            continue;
        }
        const double moved = std::hypot(body.velocity.x, body.velocity.y) * scene.dt;
        const double travel =
            step_travel(body.velocity, body.angular_velocity, body.shape, scene.dt);
        if (travel <= limit) {
            continue;
        }
        // The key whose share is the larger is the one to change.
        const std::string key = moved >= travel - moved ? "velocity" : "angular_velocity";
        refuse_travel(scene, "bodies[" + std::to_string(i) + "]." + key, "'" + body.name + "'",
                      travel, limit);
    }
    if (scene.gas) {
        const GasSpec& gas = *scene.gas;
        const double travel =
            step_travel({gas.max_speed, 0.0}, gas.max_angular_speed, gas.shape, scene.dt);
        if (travel > limit) {
            const double moved = gas.max_speed * scene.dt;
            refuse_travel(scene,
                          moved >= travel - moved ? "gas.max_speed" : "gas.max_angular_speed",
                          "the gas's fastest body", travel, limit);
        }
    }
}

} // namespace impulse::harness
