// Sine and cosine that give the same bits on every platform.
//
// libm's sin and cos differ between glibc versions, musl and other platforms in
// the last bit, which would make trajectories platform-dependent (DESIGN.md,
// Determinism rule 3). These use only +, -, * and an exact range reduction, so
// the result depends on IEEE 754 arithmetic alone. They are within 1 ULP of a
// correctly rounded result for |x| <= 2^19 * pi / 2; beyond that they stay
// deterministic but lose accuracy.
#pragma once

namespace impulse {

double sine(double x);
double cosine(double x);

} // namespace impulse
