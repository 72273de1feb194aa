// docs/physics.md's exact answers as stress rows: a case's drop against the
// ladder (impact times, rebound speeds) and its head-on collision against
// the 1D formulas, each with the bound its rounding allows and why.
#pragma once

#include "body.h"
#include "scene.h"
#include "stress.h"
#include "trajectory.h"

#include <vector>

namespace impulse::harness {

// The drop's two rows. `position_budget` is what rounding far from the origin
// can move a position by over the run (0 at the origin).
std::vector<StressRow> drop_rows(const Scene& scene, const DropCheck& check,
                                 const std::vector<TrajectoryEvent>& events,
                                 double position_budget);

// The head-on row, from the bodies' final states `last`.
std::vector<StressRow> head_on_rows(const Scene& scene, const HeadOnCheck& check,
                                    const std::vector<TrajectoryEvent>& events,
                                    const std::vector<BodyState>& last);

} // namespace impulse::harness
