// What the sweep measures a run's error by: the scene's exact answers, a
// reference run, or on a pile (a scene without exact answers whose
// expectations are those of dense contact) the two invariants a pile must
// keep, measured on the run, since there is no answer to be near.
#pragma once

#include "scene.h"
#include "trajectory.h"

namespace impulse::harness {

// The scene declares no exact answer (drop, corner-impact, head-on) and at
// least one of max-overlap, at-rest, energy-non-increasing.
bool is_pile_scene(const Scene& scene);

// The deepest interpenetration of any pair in any frame, in metres
// (overlap.h, as the max-overlap expectation measures it); 0 when nothing
// touches, infinity when a pose is not finite.
double deepest_overlap_over_run(const Scene& scene, const Trajectory& trajectory);

// The largest energy gained over the run: max over frames k of
// E(k) - min over j <= k of E(j), so a rise is counted from the lowest
// energy before it; relative to the energy's scale at t = 0 (the sum of
// its terms' magnitudes, as energy-non-increasing judges it). 0 when energy
// never rises; infinity when it is not finite.
double energy_gain_over_run(const Scene& scene, const Trajectory& trajectory);

// The scene with only its exact-answer expectations (drop, corner-impact,
// head-on): what the error is measured against when it declares any.
Scene with_exact_expectations_only(const Scene& scene);

// The largest |actual - expected| / max(|expected|, sweep_error_floor) over
// the exact-answer expectations of `exact_only`; infinity when a check has no
// numbers (a missing impact: the run did not produce the answer at all).
double error_against_exact(const Scene& exact_only, const Trajectory& trajectory);

// The largest relative difference of the final frame's positions, angles and
// velocities (every column but t); infinity when either has no frame.
double error_against_reference(const Trajectory& reference, const Trajectory& trajectory);

} // namespace impulse::harness
