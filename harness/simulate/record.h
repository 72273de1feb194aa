// Recording a run: the frames and events any Simulator produces over a scene.
#pragma once

#include "input_error.h"
#include "scene.h"
#include "simulator.h"
#include "trajectory.h"

#include <memory>
#include <string>

namespace impulse::harness {

// A run that stopped before the scene's duration: the engine's sentence (an
// InputError, exit 2, as before) that also hands back what was simulated up
// to the stop, marked partial, for `impulse run` to write. Every other
// caller treats it as the InputError it is, so a stopped run is never
// compared or blessed.
class StoppedRun : public InputError {
  public:
    StoppedRun(const std::string& file, const InputError& cause, Trajectory partial);
    const Trajectory& trajectory() const { return *trajectory_; }

  private:
    // Shared: an exception is copied when thrown, a trajectory can be large.
    std::shared_ptr<const Trajectory> trajectory_;
};

// Runs a simulator over the whole scene and records frames at t = 0 and after
// every step, t = k dt. When a step fails (the engine refuses a resting
// contact, a Zeno cascade, a value overflows) or the events pass the
// trajectory limit, throws StoppedRun holding the frames up to the last full
// step and the finite events so far, with "partial" set: the reason and the
// last frame's time.
Trajectory record(Simulator& simulator, const Scene& scene);

} // namespace impulse::harness
