// What the sweep measures on a pile (a scene without exact answers whose
// expectations are those of dense contact): no answer to be near, so the
// errors are the two invariants a pile must keep, measured on the run.
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

} // namespace impulse::harness
