// The sweep's plot, kept with the other pictures rather than in the verb.
#pragma once

#include "sweep.h"

#include <string>

namespace impulse::harness {

// The sweep's plot: log10 cost against log10 error (a pile: a second panel
// for the energy gained), every point faint, each family's Pareto front as a
// line with its own colour and marker (the references' dashed) and the time
// step beside each front point, a legend saying how to read it, and a
// verdict per reference in words (sweep_verdict.h).
std::string sweep_svg(const SweepResult& result);

} // namespace impulse::harness
