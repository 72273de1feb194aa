// A scene precondition of the impulse engine's time-stepping contact: the
// fall gravity gives a body in one step, |g| dt^2, must lie where positions
// resolve the contact tolerance (docs/refusals-and-progress.md, "Scales the
// engine cannot resolve"). Time-stepping is exempt from the tunnelling
// refusal (tunnelling.h), so this is what bounds its gravity.
#pragma once

#include "scene.h"

namespace impulse::harness {

// Throws InputError at `gravity` when a scene that can hold contact by
// time-stepping ("resting": true with a resting_method other than "events")
// has |g| dt^2 beyond 2^48 solver.contact_tolerance.
void refuse_unresolvable_step_fall(const Scene& scene);

} // namespace impulse::harness
