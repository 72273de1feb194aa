// The "gas" block's generator: a frictionless gas of equal bodies on a square
// lattice in a closed square room, for the many-body scale scenes
// (docs/formats.md, "The gas block", states the rule exactly).
//
// The same block gives the same bodies, bit for bit, on every platform: the
// random numbers come from splitmix64 written out here and mapped to doubles
// by a stated formula, never from std:: engines or distributions (whose
// outputs the C++ standard leaves to each library), and no library
// trigonometry is used.
#pragma once

#include "scene.h"

#include <cstdint>
#include <vector>

namespace impulse::harness {

// splitmix64 (Steele, Lea and Flood, 2014): a 64-bit state advanced by a fixed
// odd constant, each output a bijective mix of the state.
class SplitMix64 {
  public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

    std::uint64_t next();
    // (next() >> 11) * 2^-53: the 53 high bits as a double in [0, 1), exactly.
    double unit();

  private:
    std::uint64_t state_;
};

// The lattice's side k: the smallest whole number with k * k >= count, in
// integers (std::sqrt of a large count may round either way).
int gas_lattice_side(int count);

// The bodies the block stands for: wall-bottom, wall-top, wall-left,
// wall-right, then gas-0 ... gas-(count - 1). The caller has validated the
// spec (count >= 1, spacing > 2 circumradius, finite sizes).
std::vector<SceneBody> generate_gas(const GasSpec& gas);

} // namespace impulse::harness
