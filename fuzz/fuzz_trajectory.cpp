// Fuzz target: the trajectory/golden reader, read_trajectory(text, "fuzz.json").
//
// Bad input must end in InputError (normal here). A trajectory that reads
// (after its digest is made to match, see fuzz_support.h) must survive the
// writer: written, read back and written again, bit for bit and byte for byte.
#include "fuzz_support.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text = impulse::fuzz::text_of(data, size);
    const std::optional<impulse::harness::Trajectory> trajectory =
        impulse::fuzz::read_trajectory_fixing_digest(text);
    if (trajectory) {
        impulse::fuzz::check_round_trip(*trajectory);
    }
    return 0;
}
