// Recording a run: the frames and events any Simulator produces over a scene.
#pragma once

#include "scene.h"
#include "simulator.h"
#include "trajectory.h"

namespace impulse::harness {

// Runs a simulator over the whole scene and records frames at t = 0 and after
// every step, t = k dt.
Trajectory record(Simulator& simulator, const Scene& scene);

} // namespace impulse::harness
