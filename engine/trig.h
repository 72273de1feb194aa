// Sine and cosine that give the same bits on every platform.
//
// libm's sin and cos differ between glibc versions, musl and other platforms in
// the last bit, which would make trajectories platform-dependent (DESIGN.md,
// Determinism rule 3). These use only +, -, * and an exact range reduction, so
// the result depends on IEEE 754 arithmetic alone. They are within 1 ULP of a
// correctly rounded result for |x| <= 2^20 * pi / 2 (about 1.6e6 rad); beyond
// that they reduce modulo 2 pi rounded to a double, deterministic but less accurate.
#pragma once

namespace impulse {

double sine(double x);
double cosine(double x);

} // namespace impulse
