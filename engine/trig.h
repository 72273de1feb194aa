// Sine and cosine that give the same bits on every platform.
//
// libm's sin and cos differ between glibc versions, musl and other platforms in
// the last bit, which would make trajectories platform-dependent (docs/design.md,
// Determinism rule 3). These use only +, -, * and an exact range reduction, so
// the result depends on IEEE 754 arithmetic alone.
//
// Accuracy, stated here once: within 1 ULP of glibc's std::sin and std::cos
// (equal to them in about 97% of cases) for |x| <= 2^19 pi/2 (about 8.2e5
// rad), the range tests/test_trig.cpp checks.
// The exact range reduction reaches further, to about 2^20 pi/2 (1.6e6 rad,
// trig.cpp's medium_limit), but nothing checks the accuracy between the two.
// Beyond 2^20 pi/2 they reduce modulo 2 pi rounded to a double: deterministic,
// less accurate.
#pragma once

namespace impulse {

// The double nearest pi, written out: no library trigonometry (Determinism
// rule 3), and M_PI is not standard C++.
inline constexpr double pi = 3.141592653589793;

double sine(double x);
double cosine(double x);

} // namespace impulse
