// Box2D 2.4.1 behind the harness's Simulator interface, set up for a fair
// comparison (docs/physics.md, "Box2D, the second reference"): friction 0,
// restitution e, restitution threshold 0, no sleeping, no damping, polygons
// shrunk by the skin so the skin surface is the true surface, continuous
// collision only where the scene asks for it.
#pragma once

#include "simulator.h"

#include <memory>
#include <string>
#include <vector>

namespace impulse::harness {

// Box2D's own version, e.g. "box2d 2.4.1".
std::string box2d_version();

// Throws InputError naming the body for a shape Box2D cannot take (a polygon
// of more than 8 vertices, a circle under b2_linearSlop) and for any quantity
// single precision cannot hold (single_precision.h). Appends to `warnings` one sentence per body
// whose speed would hit Box2D's per-step translation or rotation clamp.
std::unique_ptr<Simulator> make_box2d_simulator(const Scene& scene,
                                                std::vector<std::string>& warnings);

} // namespace impulse::harness
