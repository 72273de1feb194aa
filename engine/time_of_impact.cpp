#include "time_of_impact.h"

namespace impulse {

TimeOfImpact time_of_impact(World& world, const Configuration& start, double h,
                            const Configuration& at_h, int pair_at_h, Configuration& at_impact) {
    switch (world.solver.toi) {
    case TimeOfImpactMethod::bisection:
        return bisect_time_of_impact(world, start, h, pair_at_h, at_impact);
    case TimeOfImpactMethod::secant:
        return secant_time_of_impact(world, start, h, at_h, pair_at_h, at_impact);
    }
    return bisect_time_of_impact(world, start, h, pair_at_h, at_impact);
}

TimeOfImpact pair_time_of_impact(World& world, const PairMotion& motion, double h, double s_h,
                                 BodyState& at_a, BodyState& at_b) {
    switch (world.solver.toi) {
    case TimeOfImpactMethod::bisection:
        return bisect_pair_time_of_impact(world, motion, h, at_a, at_b);
    case TimeOfImpactMethod::secant:
        return secant_pair_time_of_impact(world, motion, h, s_h, at_a, at_b);
    }
    return bisect_pair_time_of_impact(world, motion, h, at_a, at_b);
}

} // namespace impulse
