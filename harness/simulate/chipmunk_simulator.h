// Chipmunk2D 7.0.3 behind the harness's Simulator interface, set up for a fair
// comparison (docs/references.md, "Chipmunk2D 7.0.3"): friction 0, every
// pair's restitution e, no damping, no sleeping, polygons with radius 0, the
// scene's own mass and inertia, and collision slop and bias chosen at the
// scene's scale instead of Chipmunk's pixel defaults.
#pragma once

#include "simulator.h"

#include <memory>
#include <string>

namespace impulse::harness {

// The Chipmunk settings that decide the physics, all of them recorded in the
// trajectory's solver block.
struct ChipmunkSettings {
    int iterations = 10;         // cpSpaceSetIterations: solver passes per step
    double collision_slop = 0.0; // m of overlap left uncorrected (cpSpaceSetCollisionSlop)
    // cpSpaceSetCollisionBias: the fraction of an overlap left uncorrected
    // after one second; Chipmunk's default (1 - 0.1)^60 corrects 10% per
    // 1/60 s step.
    double collision_bias = 0.0;
    int collision_persistence = 3; // steps a separated pair keeps its arbiter
};

// The settings this harness runs a scene with: Chipmunk's own iterations,
// bias and persistence (they hold no length), and a slop of
// chipmunk_slop_fraction of the smallest body's size (Chipmunk's 0.1 is a
// tenth of a pixel).
ChipmunkSettings chipmunk_settings_for(const Scene& scene);
inline constexpr double chipmunk_slop_fraction = 1e-3;

// "chipmunk 7.0.3", from the library's cpVersionString.
std::string chipmunk_version();

// Throws InputError naming the scene file and the JSON path for a scene
// Chipmunk cannot represent, or that would trip one of the debug checks
// Debian's build keeps on (they abort the process): a scene asking for
// continuous collision, a mass, inertia, size, speed or position outside the
// range within which Chipmunk's products stay finite and non-zero.
std::unique_ptr<Simulator> make_chipmunk_simulator(const Scene& scene,
                                                   const ChipmunkSettings& settings);
std::unique_ptr<Simulator> make_chipmunk_simulator(const Scene& scene);

} // namespace impulse::harness
