// The stress matrix's rows (stress_rows.h).
#include "stress_rows.h"

#include <cmath>
#include <cstdio>
#include <utility>

namespace impulse::harness {

StressRow judged(std::string invariant, double worst, double bound, Bound kind,
                 std::string detail) {
    StressRow row{std::move(invariant), worst, bound, kind, false, std::move(detail)};
    switch (kind) {
    case Bound::at_most:
        row.passed = worst <= bound;
        break;
    case Bound::above:
        row.passed = worst > bound;
        break;
    case Bound::finite:
        row.passed = std::isfinite(worst);
        break;
    }
    return row;
}

double relative(double drift, double scale) {
    return scale > 0.0 ? drift / scale : drift;
}

std::string short_number(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.4g", value);
    return buffer;
}

std::string at_time(double t) {
    return "t = " + short_number(t) + " s";
}

} // namespace impulse::harness
