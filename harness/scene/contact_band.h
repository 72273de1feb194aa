// A scene precondition of the impulse engine: its contact band, the
// solver.contact_tolerance d within which two bodies count as touching, must
// be thinner than every body (docs/refusals-and-progress.md, "Scales the
// engine cannot resolve"). Checked where tunnelling is (run_scene), before
// the engine runs: d is this engine's setting, and a reference engine, which
// ignores it, refuses a scene for its own reasons first.
#pragma once

#include "scene.h"

namespace impulse::harness {

// Throws InputError when d is not below the smallest inradius of the scene's
// bodies: at solver.contact_tolerance, or at the block's wall_thickness when
// only a gas or pile block's walls are that thin.
void refuse_contact_band_beyond_bodies(const Scene& scene);

} // namespace impulse::harness
