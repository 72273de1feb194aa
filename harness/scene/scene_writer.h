// The scene an external engine receives (docs/engine-protocol.md, "The scene
// the engine receives"): impulse/scene@1 with every default written out, the
// gas block expanded into its bodies and every number the exact double the
// harness uses, so an engine needs to know no default and no generator.
#pragma once

#include "scene.h"

#include <string>

namespace impulse::harness {

// The normalized text of `scene` as loaded (overrides already applied by the
// caller): parse_scene of it gives the same bodies, gravity, restitution, dt,
// duration and solver settings, bit for bit. description, expectations,
// tolerance and box2d are left out: they are the harness's business.
std::string write_normalized_scene(const Scene& scene);

} // namespace impulse::harness
