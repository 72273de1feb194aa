// What the three fuzz targets share: reading fuzzed text as a trajectory
// (with its digest made to match, so mutated numbers get past the digest
// check), checking the writer/reader round trip, and reporting a finding.
//
// The rule of every target: InputError (and, for tolerance options,
// std::invalid_argument) is the documented answer to bad input and is normal;
// any other exception escapes LLVMFuzzerTestOneInput and aborts the process
// with the throw site on the stack, which libFuzzer saves as a crash. A broken
// invariant calls finding(), which aborts the same way.
#pragma once

#include "trajectory.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace impulse::fuzz {

// The fuzzer's bytes as a string (they may hold NUL and any other byte).
std::string text_of(const std::uint8_t* data, std::size_t size);

// Prints "fuzz finding: WHAT" and aborts.
[[noreturn]] void finding(const std::string& what);

// read_trajectory(text, "fuzz.json"), or nullopt on InputError. When the only
// problem is a stored digest that does not match the data, the digest is
// replaced by the one the reader computed and the text read once more: almost
// every mutation of a number would otherwise stop at the digest check, and
// the code behind it (compare, the writer) would never see fuzzed values.
std::optional<harness::Trajectory> read_trajectory_fixing_digest(const std::string& text);

// Every field equal, doubles bit for bit (-0.0 and +0.0 told apart).
bool same_trajectory(const harness::Trajectory& a, const harness::Trajectory& b);

// The format's promise (docs/formats.md): a trajectory written and read back
// is the same trajectory, bit for bit, and writing it again gives the same
// bytes. Anything else is a finding.
void check_round_trip(const harness::Trajectory& trajectory);

// The memory budget's promise (docs/memory.md), under the limit the run has
// set (IMPULSE_MAX_TRAJECTORY_MIB): the trajectory's frames repeated k times,
// k the smallest count the limit refuses, are refused by the reader before it
// parses them ("is too large to read"); repeated k - 1 times they read back,
// the same trajectory, and the reader holds no more bytes than the budget's
// model counted for their text (plus the strings' characters). Anything else
// is a finding.
void check_memory_budget(const harness::Trajectory& trajectory);

} // namespace impulse::fuzz
