// The sweep as text: the table `impulse sweep` prints, and the sentences its
// JSON repeats (sweep.h, sweep_verdict.h).
#pragma once

#include "sweep.h"
#include "sweep_verdict.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace impulse::harness {

// Why no target was measured, or empty when they were.
std::string sweep_targets_not_measured(const SweepResult& result, const SweepTargets& targets);

// Target 1 (the error at Box2D 2.4.1's 60 Hz cost) in one sentence.
std::string sweep_error_target_text(const SweepResult& result, const SweepTargets& targets);

// Target 2 (impulse's front against Box2D 2.4.1's) in one sentence.
std::string sweep_front_target_text(const SweepResult& result, const SweepTargets& targets);

// The axes a verdict is given on: a pile's two, otherwise the error.
std::vector<SweepAxis> sweep_verdict_axes(const SweepResult& result);

// The table: a header saying what error and cost are, a row per point (* on
// its family's front), the counts, each reference's verdict, the targets.
void write_sweep_table(const SweepResult& result, std::ostream& out);

} // namespace impulse::harness
