// The deepest interpenetration of a scene's bodies in given poses: what the
// `max-overlap` expectation judges in every frame of a run, and what a pile's
// "settled" means geometrically (docs/formats.md, "max-overlap").
//
// The depth is the engine's own narrow phase (manifold.h, separation()), so
// the harness measures overlap exactly as the engine defines it. Pairs are
// found with a uniform grid over the dynamic bodies' bounding boxes, so a pile
// of 10,000 bodies costs O(N) per frame, not O(N^2).
#pragma once

#include "rotation.h"
#include "scene.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace impulse::harness {

// The pair that interpenetrates most: depth = -separation >= 0 (0: touching),
// a < b their indices in Scene::bodies.
struct Overlap {
    double depth = 0.0;
    std::size_t a = 0;
    std::size_t b = 0;
};

// Every body's pose: poses[i] belongs to bodies[i] (static ones where the
// scene puts them). Every pair with at least one dynamic body whose
// separation is <= 0 is a candidate; the deepest wins, ties to the least
// (a, b), so the answer does not depend on the grid's order. Empty when no
// pair touches. Poses must be finite (the caller checks).
std::optional<Overlap> deepest_overlap(const std::vector<SceneBody>& bodies,
                                       const std::vector<Transform>& poses);

// The scene's own poses at t = 0 (position and angle of every body).
std::vector<Transform> initial_poses(const std::vector<SceneBody>& bodies);

} // namespace impulse::harness
