// The sweep's plot, kept with the other pictures rather than in the verb.
#pragma once

#include "sweep.h"

#include <string>

namespace impulse::harness {

// The sweep's plot: log10 cost against log10 error, every point faint, each
// family's Pareto front as a line (Box2D's thick and dashed), a legend.
std::string sweep_svg(const SweepResult& result);

} // namespace impulse::harness
