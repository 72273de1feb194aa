// Contact islands (docs/engine.md, "Dense contact"): the dynamic bodies joined
// through contact points. A contact problem couples only the bodies of one
// island, so each island is solved on its own and the cost of a step grows with
// the islands, not the world. Static bodies never join an island: a floor under
// two piles does not make them one.
#pragma once

#include "body.h"

#include <vector>

namespace impulse {

// The two bodies of one contact point (world body indices).
struct IslandLink {
    int a = 0;
    int b = 0;
};

// Island i has the bodies bodies[body_offsets[i] .. body_offsets[i + 1]) and
// the links links_of[link_offsets[i] .. link_offsets[i + 1]) (indices into the
// links given). A dynamic body in no link is in no island (it flies free).
struct Islands {
    std::vector<int> body_offsets; // island count + 1 entries (or empty)
    std::vector<int> bodies;       // ascending within an island
    std::vector<int> link_offsets; // island count + 1 entries (or empty)
    std::vector<int> links_of;     // in the order given within an island
    int count() const {
        return body_offsets.empty() ? 0 : static_cast<int>(body_offsets.size()) - 1;
    }
};

// Scratch kept between steps so finding islands allocates nothing once warm.
struct IslandScratch {
    std::vector<int> parent; // union-find over bodies, all -1 between calls
    std::vector<int> touched;
    std::vector<int> island_of; // per body, -1 between calls
    std::vector<int> cursor;    // per island: the next free slot while placing
};

// Deterministic: islands are ordered by their smallest body index. Cost is
// O(links + T log T) for the T dynamic bodies in links (the log from sorting
// them), never O(world), once scratch has the world's size.
void find_islands(const std::vector<Body>& bodies, const std::vector<IslandLink>& links,
                  Islands& out, IslandScratch& scratch);

} // namespace impulse
