// Fuzz target: the memory budget (docs/memory.md) on the trajectory reader.
//
// Every fuzzed text that reads as a trajectory is scaled up, by repeating its
// frames, to just over a 1 MiB limit (IMPULSE_MAX_TRAJECTORY_MIB=1, set for
// the run): the reader must refuse it before parsing, and read the size just
// under the limit holding no more than the budget counted (fuzz_support.h).
#include "fuzz_support.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    // A small limit keeps each scaled input near a megabyte.
    ::setenv("IMPULSE_MAX_TRAJECTORY_MIB", "1", 1);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text = impulse::fuzz::text_of(data, size);
    const std::optional<impulse::harness::Trajectory> trajectory =
        impulse::fuzz::read_trajectory_fixing_digest(text);
    if (trajectory) {
        impulse::fuzz::check_memory_budget(*trajectory);
    }
    return 0;
}
