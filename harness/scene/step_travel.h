// Scene preconditions of the impulse engine's time-stepping contact: what one
// step moves a body, the fall gravity gives it (|g| dt^2) and its initial
// speed (|v| dt plus its turning), must lie where positions resolve the
// contact tolerance (docs/refusals-and-progress.md, "Scales the
// engine cannot resolve"). Time-stepping is exempt from the tunnelling
// refusal (tunnelling.h), so this is what bounds its gravity.
#pragma once

#include "scene.h"

namespace impulse::harness {

// Throws InputError at `gravity` when a scene that can hold contact by
// time-stepping ("resting": true with a resting_method other than "events")
// has |g| dt^2 beyond 2^48 solver.contact_tolerance.
void refuse_unresolvable_step_fall(const Scene& scene);

// Throws InputError at a listed body's `velocity` (or `angular_velocity`),
// or the gas block's `max_speed` (or `max_angular_speed`), when such a scene
// moves a body (|v| + R |omega|) dt beyond the same 2^48 tolerances in its
// first step (R its farthest point from its centre).
void refuse_unresolvable_step_speed(const Scene& scene);

} // namespace impulse::harness
