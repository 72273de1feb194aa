// The stress matrix's rows: how a worst value is judged against its bound,
// and the short numbers and times its messages are written with. Shared by
// the monitor (stress_monitor.cpp), the exact answers
// (stress_exact_answers.cpp) and the cases (stress_cases.cpp).
#pragma once

#include "stress.h"

#include <limits>
#include <string>

namespace impulse::harness {

// The rows' two special numbers: the spacing of doubles at 1 (2^-52), which
// rounding bounds are counted in, and the worst value of a row with nothing
// to measure.
inline constexpr double epsilon = std::numeric_limits<double>::epsilon();
inline constexpr double infinity = std::numeric_limits<double>::infinity();

// A row whose `passed` says whether `worst` keeps to `bound` as `kind` reads it.
StressRow judged(std::string invariant, double worst, double bound, Bound kind, std::string detail);

// A drift relative to the size of the terms it is made of (0 when nothing moved).
double relative(double drift, double scale);

// Four significant digits: a message is read, not parsed.
std::string short_number(double value);

// "t = 1.5 s": where in a run a worst value happened.
std::string at_time(double t);

} // namespace impulse::harness
