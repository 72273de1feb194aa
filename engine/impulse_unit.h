// Units of impulse for the island solvers (docs/engine.md, "Units of
// impulse"): powers of two chosen from a problem's largest Delassus diagonal
// A_ii. Multiplying by a power of two is exact, so a solve in such a unit
// has the bits of the solve in SI units wherever nothing overflows or is
// subnormal, while its products and squared norms stay within range: found
// by an outside review, a pile of density 1e200 (A_ii near 1e-200, impulses
// near 1e201) was declared to have no solution.
#pragma once

namespace impulse {

// The power of two u with u * largest_diagonal in [1, 2): the pivoting
// solver's scale of A. 1 when the diagonal is 0 or not finite, or below
// 2^-1023, where no finite power of two brings it up (a body near the
// largest double's mass, with no gravity to refuse its weight).
double delassus_unit(double largest_diagonal);

// The power of two s = 2^-floor(e / 2), with largest_diagonal in [2^e,
// 2^(e+1)): MPRGP's common row scale for an unscaled island, so that
// mu = lambda / s is an impulse in units of about the island's heaviest
// effective mass. 1 when the diagonal is 0 or not finite.
double row_unit(double largest_diagonal);

} // namespace impulse
