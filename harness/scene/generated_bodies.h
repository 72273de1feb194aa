// What the gas and pile blocks share about the bodies they make: their static
// walls, and the names they give, which a listed body may not take.
#pragma once

#include "scene.h"

#include <cstddef>
#include <initializer_list>
#include <string>

namespace impulse::harness {

// A static box wall of half extents (hx, hy) centred at `position`.
SceneBody static_wall(const std::string& name, Vec2 position, double hx, double hy);

// Whether a block of `count` bodies named PREFIX0 .. PREFIX{count-1} (no
// leading zeros) and the given walls gives a body this name.
bool is_generated_name(const std::string& name, std::initializer_list<const char*> walls,
                       const std::string& prefix, int count);

// The JSON path a problem with scene body `index` is reported at: its entry in
// "bodies", or the block that made it ("gas" or "pile"), which the file holds
// instead of the body.
std::string body_path(const Scene& scene, std::size_t index);
// How a message names that body: "bodies[3] 'ball'", or "'pile-7' of the pile
// block".
std::string body_reference(const Scene& scene, std::size_t index);

} // namespace impulse::harness
