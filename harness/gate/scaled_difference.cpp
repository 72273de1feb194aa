// Differences measured at a channel's scale (scaled_difference.h).
#include "scaled_difference.h"

#include <cmath>
#include <limits>

namespace impulse::harness {

namespace {

// The gap from `reference` (finite, > 0) to the next double away from zero;
// at the largest double, the gap below it.
double spacing_at(double reference) {
    const double up = std::nextafter(reference, std::numeric_limits<double>::infinity());
    if (std::isinf(up)) {
        return reference - std::nextafter(reference, 0.0);
    }
    return up - reference;
}

} // namespace

std::uint64_t ulp_at_scale(double gold, double value, double scale) {
    constexpr std::uint64_t most = std::numeric_limits<std::uint64_t>::max();
    if (std::isnan(gold) || std::isnan(value)) {
        return most;
    }
    if (gold == value) {
        return 0; // also -0.0 against +0.0
    }
    const double difference = std::fabs(gold - value);
    const double reference =
        std::fmax(std::fmax(std::fabs(gold), std::fabs(value)), std::isfinite(scale) ? scale : 0.0);
    if (!std::isfinite(difference) || !std::isfinite(reference)) {
        return most;
    }
    const double ulps = std::ceil(difference / spacing_at(reference));
    // 2^64 as a double; anything at or past it does not fit.
    return ulps >= 18446744073709551616.0 ? most : static_cast<std::uint64_t>(ulps);
}

double relative_at_scale(double gold, double value, double scale) {
    if (gold == value) {
        return 0.0;
    }
    const double difference = std::fabs(gold - value);
    double reference = std::fmax(std::fabs(gold), std::isfinite(scale) ? scale : 0.0);
    if (reference == 0.0) {
        reference = std::fabs(value); // a channel of zeros: relative to the new value
    }
    return difference / reference;
}

} // namespace impulse::harness
