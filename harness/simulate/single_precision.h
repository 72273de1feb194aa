// What a single-precision reference engine can represent (Box2D 2.4.1 today;
// Chipmunk or Box2D v3 would reuse it). Such an engine converts every number
// of a scene to float and forms products of them (mass times velocity,
// inverse mass, inertia m r^2, gravity times mass times dt, positions plus
// displacements); a value outside float's normal range becomes inf, 0 or a
// denormal, and Box2D then asserts (b2Body::SetMassData's m_I > 0, the broad
// phase's valid AABBs) or silently computes nonsense. So the scene is refused
// up front, with a sentence naming the file, the JSON path and the reason.
#pragma once

#include "scene.h"

#include <string>

namespace impulse::harness {

// Headroom kept at both ends of float's normal range (1.2e-38 to 3.4e38): a
// quantity of the scene must lie within [1.2e-38 * headroom, 3.4e38 /
// headroom] so that the sums and products the engine forms from a few of them
// (not each enumerated below) stay normal too.
inline constexpr double single_precision_headroom = 1e6;

// Throws InputError naming the scene file, the JSON path (bodies[1].mass,
// gravity, dt, ...) and the reason for the first quantity `engine` ("Box2D")
// cannot represent in single precision: each body's position, angle,
// velocity, angular velocity, shape size and vertices, mass, inverse mass,
// inertia and inverse inertia (rotating bodies), momentum, angular momentum,
// the gravity impulse per step, the farthest point it can reach; the
// gravity; the step `dt` (the engine's own step, e.g. dt / substeps).
// Zero passes where it means "none" (a velocity, a coordinate), never where
// it would be a divisor (a mass, a size, dt).
void require_single_precision(const Scene& scene, const std::string& engine, double dt);

} // namespace impulse::harness
