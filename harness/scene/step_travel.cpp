#include "step_fall.h"

#include "input_error.h"
#include "scene_reading.h"
#include "text.h"

#include <cmath>
#include <string>

namespace impulse::harness {

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
    if (!solver.resting || solver.resting_method == RestingMethod::events) {
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
            sentence_number(limit) + " m (2^48 times solver.contact_tolerance " +
            sentence_number(solver.contact_tolerance) +
            " m: the cancellation leaves |g| dt^2 2^-52 per step); use a smaller gravity or "
            "dt, or a larger solver.contact_tolerance");
}

} // namespace impulse::harness
