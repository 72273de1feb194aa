// Deterministic sine and cosine: fdlibm's algorithm (Sun Microsystems, 1993, freely
// redistributable), restated with plain double arithmetic. Every operation below is an IEEE 754
// +, -, * or an exact operation (fabs, comparisons, exponent-field reads), and the build uses
// -ffp-contract=off, so no compiler or CPU can change a single bit of the result.
//
// Outline: reduce x to y = x - n * pi/2 with |y| <= ~pi/4, carried as a head and a tail
// (y = hi + lo) because the subtraction cancels leading bits; then evaluate a minimax polynomial
// for sin or cos on [-pi/4, pi/4] and pick the sign and function from n mod 4.
#include "trig.h"

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace impulse {
namespace {

// Every operation must round to double. x87 code (32-bit x86 without SSE2) keeps intermediates
// in extended precision, which would silently change the results.
static_assert(FLT_EVAL_METHOD == 0, "impulse::sine and cosine need arithmetic rounded to double");

// Below 2^-27, x^3/6 is under half an ulp of x, so sin x rounds to x and cos x to 1.
constexpr double tiny = 0x1p-27;

// The double nearest pi/4 (just below the real value); arguments up to here need no reduction.
constexpr double pi_over_4 = 7.85398163397448278999e-01; // 0x3FE921FB 54442D18

// fdlibm e_rem_pio2.c: pi/2 split into 33-bit pieces so that n * piece is exact for n < 2^20.
constexpr double inv_pio2 = 6.36619772367581382433e-01; // 0x3FE45F30 6DC9C883, 53 bits of 2/pi
constexpr double pio2_1 = 1.57079632673412561417e+00;   // 0x3FF921FB 54400000, first 33 bits
constexpr double pio2_1t = 6.07710050650619224932e-11;  // 0x3DD0B461 1A626331, pi/2 - pio2_1
constexpr double pio2_2 = 6.07710050630396597660e-11;   // 0x3DD0B461 1A600000, second 33 bits
constexpr double pio2_2t = 2.02226624879595063154e-21;  // 0x3BA3198A 2E037073, rest after pio2_2
constexpr double pio2_3 = 2.02226624871116645580e-21;   // 0x3BA3198A 2E000000, third 33 bits
constexpr double pio2_3t = 8.47842766036889956997e-32;  // 0x397B839A 252049C1, rest after pio2_3

// fdlibm's medium-range limit (~2^20 * pi/2): below it n < 2^20, so n * pio2_1 is exact. The
// accuracy trig.h states is tested only up to half of it, 2^19 * pi/2.
constexpr double medium_limit = 0x1.921fbp+20;

// Adding and subtracting 1.5 * 2^52 rounds a double below 2^51 to the nearest integer with
// plain arithmetic (the sum has no fraction bits left), unlike std::nearbyint, which is libm.
constexpr double round_to_integer = 0x1.8p52;

// 2*pi rounded to double, the modulus of the reduced-accuracy fallback for huge arguments.
constexpr double two_pi = 6.28318530717958623200e+00; // 0x401921FB 54442D18

// fdlibm k_sin.c: minimax coefficients for sin(x) = x + S1 x^3 + ... + S6 x^13 on [-pi/4, pi/4],
// error below 2^-58.
constexpr double S1 = -1.66666666666666324348e-01; // 0xBFC55555 55555549
constexpr double S2 = 8.33333333332248946124e-03;  // 0x3F811111 1110F8A6
constexpr double S3 = -1.98412698298579493134e-04; // 0xBF2A01A0 19C161D5
constexpr double S4 = 2.75573137070700676789e-06;  // 0x3EC71DE3 57B1FE7D
constexpr double S5 = -2.50507602534068634195e-08; // 0xBE5AE5E6 8A2B9CEB
constexpr double S6 = 1.58969099521155010221e-10;  // 0x3DE5D93A 5ACFD57C

// fdlibm k_cos.c: minimax coefficients for cos(x) = 1 - x^2/2 + C1 x^4 + ... + C6 x^14 on
// [-pi/4, pi/4], error below 2^-58.
constexpr double C1 = 4.16666666666666019037e-02;  // 0x3FA55555 5555554C
constexpr double C2 = -1.38888888888741095749e-03; // 0xBF56C16C 16C15177
constexpr double C3 = 2.48015872894767294178e-05;  // 0x3EFA01A0 19CB1590
constexpr double C4 = -2.75573143513906633035e-07; // 0xBE927E4F 809C52AD
constexpr double C5 = 2.08757232129817482790e-09;  // 0x3E21EE9E BDB4B1C4
constexpr double C6 = -1.13596475577881948265e-11; // 0xBDA8FAE9 BE8838D4

// A constant, not x - x: the NaN produced by arithmetic has a different sign bit on x86 and
// Arm, and we promise identical bits.
constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

// The biased exponent field of v; its difference between x and the reduced x counts the
// leading bits that cancelled.
int exponent_field(double v) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    return static_cast<int>((bits >> 52) & 0x7ff);
}

// x mod two_pi, computed exactly for any finite x >= two_pi: subtract two_pi * 2^k for falling
// k. Each subtraction has its operands within a factor of two, so it is exact (Sterbenz), and
// scaling by two is exact.
double remainder_two_pi(double x) {
    double multiple = two_pi;
    while (multiple <= 0.5 * x) {
        multiple += multiple;
    }
    while (multiple >= two_pi) {
        if (x >= multiple) {
            x -= multiple;
        }
        multiple *= 0.5;
    }
    return x;
}

// x - n * pi/2 as hi + lo, with |hi + lo| <= ~pi/4.
struct Reduced {
    int quadrant; // n mod 4
    double hi;
    double lo;
};

// fdlibm __ieee754_rem_pio2, medium path, for finite x > pi/4. Cody-Waite: subtract n * pi/2
// one 33-bit piece of pi/2 at a time; each product is exact and the subtraction's rounding
// error is carried into the tail. A second or third piece is needed only when x is so close to
// a multiple of pi/2 that more than 16 (or 49) leading bits cancel.
Reduced reduce(double x) {
    // Beyond the medium range, n * pio2_1 stops being exact and the reduction would be
    // meaningless. Exact Payne-Hanek reduction (fdlibm __kernel_rem_pio2) is a lot of code for
    // angles no simulation should reach, so instead we take x mod two_pi exactly. Since two_pi
    // is 2.4e-16 below 2*pi, the result is the sine or cosine of a number within ~0.35 ulp of
    // x rather than of x itself: deterministic and in [-1, 1], but not within 1 ulp.
    if (!(x < medium_limit)) {
        x = remainder_two_pi(x);
    }
    const double n = (x * inv_pio2 + round_to_integer) - round_to_integer;
    double r = x - n * pio2_1; // exact: n * pio2_1 has at most 53 bits and is close to x
    double w = n * pio2_1t;
    double hi = r - w;

    struct Piece {
        double head;
        double tail;
        int cancelled_bits; // use this piece only if more leading bits cancelled than this
    };
    constexpr Piece refinements[] = {{pio2_2, pio2_2t, 16}, {pio2_3, pio2_3t, 49}};
    const int x_exponent = exponent_field(x);
    for (const Piece& piece : refinements) {
        if (x_exponent - exponent_field(hi) <= piece.cancelled_bits) {
            break;
        }
        const double t = r;
        w = n * piece.head;
        r = t - w;
        w = n * piece.tail - ((t - r) - w); // (t - r) - w: rounding error of t - w
        hi = r - w;
    }
    const double lo = (r - hi) - w;
    return {static_cast<int>(n) & 3, hi, lo};
}

// fdlibm __kernel_sin: sin(x + y) for |x| <= ~pi/4, y the tail of x (|y| < ulp(x)). The tail
// enters through sin(x + y) ~ sin(x) + y * (1 - x^2/2); the additions are ordered so that the
// large term x is added last.
double kernel_sin(double x, double y) {
    if (std::fabs(x) < tiny) {
        return x;
    }
    const double z = x * x;
    const double v = z * x;
    const double r = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
    if (y == 0.0) {
        return x + v * (S1 + z * r);
    }
    return x - ((z * (0.5 * y - v * r) - y) - v * S1);
}

// fdlibm __kernel_cos as revised in FreeBSD msun (Bruce Evans): cos(x + y) for |x| <= ~pi/4.
// w = 1 - x^2/2 is rounded, and (1 - w) - x^2/2 recovers its rounding error exactly, so the small
// terms are added to 1 - x^2/2 held in more than double precision. The tail y enters as -x*y.
double kernel_cos(double x, double y) {
    const double z = x * x;
    const double z2 = z * z;
    const double r = z * (C1 + z * (C2 + z * C3)) + z2 * z2 * (C4 + z * (C5 + z * C6));
    const double half_z = 0.5 * z;
    const double w = 1.0 - half_z;
    return w + (((1.0 - w) - half_z) + (z * r - x * y));
}

// sin(x) for finite x >= tiny.
double sine_of_magnitude(double x) {
    if (x <= pi_over_4) {
        return kernel_sin(x, 0.0);
    }
    const Reduced y = reduce(x);
    switch (y.quadrant) {
    case 0:
        return kernel_sin(y.hi, y.lo);
    case 1:
        return kernel_cos(y.hi, y.lo);
    case 2:
        return -kernel_sin(y.hi, y.lo);
    default:
        return -kernel_cos(y.hi, y.lo);
    }
}

// cos(x) for finite x >= tiny.
double cosine_of_magnitude(double x) {
    if (x <= pi_over_4) {
        return kernel_cos(x, 0.0);
    }
    const Reduced y = reduce(x);
    switch (y.quadrant) {
    case 0:
        return kernel_cos(y.hi, y.lo);
    case 1:
        return -kernel_sin(y.hi, y.lo);
    case 2:
        return -kernel_cos(y.hi, y.lo);
    default:
        return kernel_sin(y.hi, y.lo);
    }
}

} // namespace

// Both work on |x| and restore the sign afterwards, so sine(-x) == -sine(x) and
// cosine(-x) == cosine(x) hold bit for bit.
double sine(double x) {
    const double magnitude = std::fabs(x);
    if (magnitude < tiny) {
        return x; // also keeps the sign of -0.0
    }
    if (!(magnitude <= std::numeric_limits<double>::max())) {
        return not_a_number; // NaN or infinity
    }
    const double s = sine_of_magnitude(magnitude);
    return x < 0.0 ? -s : s;
}

double cosine(double x) {
    const double magnitude = std::fabs(x);
    if (magnitude < tiny) {
        return 1.0;
    }
    if (!(magnitude <= std::numeric_limits<double>::max())) {
        return not_a_number; // NaN or infinity
    }
    return cosine_of_magnitude(magnitude);
}

} // namespace impulse
