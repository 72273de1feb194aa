// The "pile" block's reader (scene_pile_block.cpp), beside read_gas: private to
// the scene loader, like scene_reading.h.
#pragma once

#include "scene_reading.h"

namespace impulse::harness::scene_reading {

// "pile": reads and validates the block, then appends its walls and bodies
// (pile.h) after the listed ones. The names it gives must not be taken.
void read_pile(const Node& node, Scene& scene);

} // namespace impulse::harness::scene_reading
