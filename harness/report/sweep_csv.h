// The sweep as CSV (impulse sweep --csv), one row per grid point, kept apart
// from the verb as its plot is (sweep_plot.h).
#pragma once

#include "sweep.h"

#include <string>

namespace impulse::harness {

// A header row and one row per point, numbers in shortest round-trip form,
// an empty field where a point has no value. A sweep of an engine other than
// impulse has one more column, cost_source (engine, process or in-process);
// a pile's sweep one more, energy_error (its second error axis). A
// reference's row has its name as engine and its --substeps (empty: its own).
std::string sweep_csv(const SweepResult& result);

} // namespace impulse::harness
