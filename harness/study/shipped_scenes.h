// The shipped scenes: the canonical scenes that come with the impulse tool,
// wherever it runs from (a build tree, an installed prefix), so that a verb
// working for another project's engine (`impulse conform`) finds them without
// this repository as its working directory.
#pragma once

#include <string>

namespace impulse::harness {

// The folder of the shipped canonical scenes, the first of:
//  1. IMPULSE_SCENES_DIR, when set and not empty (it must be a folder: a
//     setting that points nowhere is an error, never silently passed over);
//  2. <folder of the running executable>/../share/impulse/scenes, when it is a
//     folder: the installed layout;
//  3. the source tree's harness/scenes, where this build came from.
// Throws InputError when none is there.
std::string shipped_scenes_dir();

} // namespace impulse::harness
