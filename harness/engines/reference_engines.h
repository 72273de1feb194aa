// The reference engines by name (docs/references.md): the engines physics
// programmers use today, each run as fairly as it allows, that `impulse
// compare`, `impulse conform` and scripts/gate put beside the engine under
// study. Two are built in (Box2D 2.4.1, Chipmunk2D 7.0.3) and two are Node
// programs speaking the engine protocol (Box2D v3 and Rapier2D, from npm):
// whether each is on this machine is found out here, and when it is not, the
// command that installs it.
#pragma once

#include "engine.h"

#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

struct ReferenceEngine {
    std::string name;  // "box2d-3": what --with takes and what columns and files are called
    std::string title; // "Box2D v3 (npm box2d3-wasm 5.2.0)", for people
    EngineSpec spec;   // how to run it; spec.name == name
    bool available = false;
    std::string missing; // when not available: why, one clause ("node is not on PATH")
    std::string install; // when not available: the command that installs it
};

// The Node references' folder (references/ of the npm project: box2d-v3/,
// rapier/, node_modules/), the first of: IMPULSE_REFERENCES_DIR when set and
// not empty (it must be a folder: an error otherwise, never silently passed
// over); PREFIX/share/impulse/references beside an installed PREFIX/bin/impulse;
// the source tree's references/.
std::string references_dir();

// Every reference engine, in this order: box2d-2.4, box2d-3, chipmunk, rapier.
// Throws InputError when IMPULSE_REFERENCES_DIR is set to what is not a folder.
std::vector<ReferenceEngine> reference_engines();

// The names, in that order ("box2d-2.4, box2d-3, chipmunk, rapier").
std::vector<std::string> reference_names();

// One sentence for a reference that is not available: "reference 'rapier' is
// not available (node is not on PATH); install it with: scripts/setup".
std::string unavailable_sentence(const ReferenceEngine& reference);

} // namespace impulse::harness
