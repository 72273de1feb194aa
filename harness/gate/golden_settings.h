// What a golden says besides its numbers: the engine that recorded it and the
// solver settings it ran with. Neither is in the digest (goldens stay
// byte-identical when the digest's rules are kept), so check compares them
// itself: a golden whose solver block was edited, or that another engine
// recorded, must not pass because its numbers happen to match.
#pragma once

#include "trajectory.h"

#include <string>
#include <vector>

namespace impulse::harness {

struct SettingsComparison {
    // Each a failure: "solver.KEY: golden V, new W", or the engines' names.
    std::vector<std::string> differences;
    // Reported, never a failure: the same engine at another version.
    std::vector<std::string> notes;
};

// The engine string is "NAME VERSION" ("impulse 0.1.0"): another NAME is a
// difference, another VERSION of the same engine a note (the numbers and
// the solver settings are compared anyway, so a version bump that changes
// the physics still fails). Solver keys are compared by name, whatever
// their order; a key on one side only is a difference.
SettingsComparison compare_settings(const Trajectory& gold, const Trajectory& value);

} // namespace impulse::harness
