// Differences that mean something near zero (docs/gate-rules.md, "ULP and
// relative differences"). A value near zero is usually what is left of a
// cancellation between values of the channel's size (a velocity that passes
// through 0, a contact point's y on the ground), so its rounding error is of
// the size of the channel's largest values, not of its own. Counting the
// doubles between 1e-17 and 1e-17 + 2.2e-16 gives about 1.2e14, and between
// -1e-300 and 1e-300 about 9.2e18: numbers that say nothing about a change
// of a few rounding errors. Both measures here take the channel's scale.
#pragma once

#include <cstdint>

namespace impulse::harness {

// The channel's scale for a column or an event field: the largest finite
// |value| the golden has in it (0 when it has none).
//
// ULPs at a scale: |gold - value| divided by the spacing of doubles at
// max(|gold|, |value|, scale), rounded up. For two doubles of the same
// binade as that reference it is the count of doubles between them (1 ULP
// apart is 1); near zero it is how many rounding errors of the channel's
// size apart they are, so a sign change across zero is small. 0 when they
// are equal (+0.0 and -0.0 too); UINT64_MAX when either is NaN or the
// difference is infinite.
std::uint64_t ulp_at_scale(double gold, double value, double scale);

// |gold - value| / max(|gold|, scale): finite when the golden is 0 (then
// relative to the scale, or to |value| when the channel is all zeros); 0
// when they are equal; NaN for NaN input.
double relative_at_scale(double gold, double value, double scale);

} // namespace impulse::harness
