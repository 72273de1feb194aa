#include "impulse_unit.h"

#include <cmath>

namespace impulse {

double delassus_unit(double largest_diagonal) {
    if (!(largest_diagonal > 0.0) || !std::isfinite(largest_diagonal)) {
        return 1.0;
    }
    const double unit = std::ldexp(1.0, -std::ilogb(largest_diagonal));
    return std::isfinite(unit) ? unit : 1.0;
}

double row_unit(double largest_diagonal) {
    if (!(largest_diagonal > 0.0) || !std::isfinite(largest_diagonal)) {
        return 1.0;
    }
    const int exponent = std::ilogb(largest_diagonal); // A_ii in [2^e, 2^(e+1))
    return std::ldexp(1.0, -(exponent >= 0 ? exponent / 2 : (exponent - 1) / 2));
}

} // namespace impulse
