// What the gas and pile blocks share about the bodies they make: their static
// walls, and the names they give, which a listed body may not take.
#pragma once

#include "scene.h"

#include <initializer_list>
#include <string>

namespace impulse::harness {

// A static box wall of half extents (hx, hy) centred at `position`.
SceneBody static_wall(const std::string& name, Vec2 position, double hx, double hy);

// Whether a block of `count` bodies named PREFIX0 .. PREFIX{count-1} (no
// leading zeros) and the given walls gives a body this name.
bool is_generated_name(const std::string& name, std::initializer_list<const char*> walls,
                       const std::string& prefix, int count);

} // namespace impulse::harness
