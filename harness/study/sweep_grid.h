// The sweep's grid (sweep.h): the points each engine runs, in the order
// they run. The engine under study's points come first, dt outermost, then
// Box2D's, then every other reference's.
#pragma once

#include "scene.h"
#include "sweep.h"

#include <vector>

namespace impulse::harness {

// solver.ccd for the impulse points: the scene's own or the configured ones.
// ccd on with "stepping": "local" is the scene's error (InputError).
std::vector<bool> ccd_settings(const Scene& scene, const SweepConfig& config);

// The impulse engine's points: dt, integrator, toi method, tolerance, then
// ccd fastest, so a point with it sits next to the same point without.
std::vector<SweepPoint> impulse_points(const SweepConfig& config, const std::vector<bool>& ccds);

// Another engine's points: dt, integrator, then tolerance fastest (what
// reaches it as a modified scene), with the scene's own toi method and ccd.
std::vector<SweepPoint> engine_points(const SweepConfig& config, const Scene& scene);

// Box2D's points (none in a build without Box2D), then every other
// reference's: its own settings, or each of its sub-step counts, at every dt.
void add_box2d_points(const SweepConfig& config, std::vector<SweepPoint>& points);
void add_reference_points(const SweepConfig& config, std::vector<SweepPoint>& points);

} // namespace impulse::harness
