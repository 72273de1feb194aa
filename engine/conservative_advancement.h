// Conservative advancement (docs/physics.md and docs/engine.md,
// "Tunnelling"): how long after a sample of a pair's free motion over a step
// the pair certainly stays clear of its interpenetration test, from bounds on
// how fast its points can close: in any direction, along the separating axis,
// along that axis point by point to second and to third order, in the frame
// of a turning face, and between the discs that hold turning bodies at every
// angle, whichever allows longest.
#pragma once

#include "configuration.h"

namespace impulse {

// One pair's motion from the start of the sweep, in the terms of the rates
// the integrators give (conservative_advancement.cpp): u seconds in, a's
// centre moves relative to b's at w(u) = w0 + c u a_rel (under gravity alone
// a_rel = 0 for two dynamic bodies, which fall together, and g against a
// static one), and each body turns at omega0 + c u alpha, moving its surface
// by up to R per radian.
struct SweepMotion {
    Vec2 w0;
    Vec2 a_rel;
    double c = 0.0;
    double radius_a = 0.0;
    double radius_b = 0.0;
    double omega_a = 0.0;
    double omega_b = 0.0;
    double alpha_a = 0.0;
    double alpha_b = 0.0;
};

SweepMotion sweep_motion_of(const World& world, const Configuration& start, const Pair& pair);

// How long after a free sample at u (separation s, the bodies at at_a and
// at_b) the pair certainly stays above `floor` less contact_tolerance;
// samples need go no further than `end`.
double safe_advance(const World& world, const Pair& pair, const SweepMotion& m, double u, double s,
                    double floor, const BodyState& at_a, const BodyState& at_b, double end);

} // namespace impulse
