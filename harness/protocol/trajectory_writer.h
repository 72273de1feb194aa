// The C++ side of the engine protocol (docs/engine-protocol.md) for an engine
// author: the trajectory an engine writes to standard output, built one frame
// and one event at a time, written in the harness's own canonical form.
#pragma once

#include "scene.h"
#include "trajectory.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace impulse::protocol {

// One dynamic body's state: centre of mass (m), angle (rad), velocity (m/s),
// angular velocity (rad/s): the six columns of the trajectory.
struct BodyState {
    double x = 0.0;
    double y = 0.0;
    double angle = 0.0;
    double vx = 0.0;
    double vy = 0.0;
    double omega = 0.0;
};

class TrajectoryWriter {
  public:
    // Columns from the scene's dynamic bodies, in scene order; `engine` names
    // the engine and its version ("my-engine 1.4.2").
    TrajectoryWriter(const harness::Scene& scene, const std::string& engine);

    // A setting that decides the engine's physics, for the trajectory's
    // solver block (check says when a golden was recorded with others).
    void setting(const std::string& key, const std::string& value);
    void setting(const std::string& key, const char* value);
    void setting(const std::string& key, double value);

    // The next frame: one state per dynamic body, in scene order. Its time is
    // k * dt, computed here, so it always meets the protocol's frame times.
    // Throws std::logic_error for a wrong count of states or a frame past the
    // last (steps + 1 frames), std::domain_error naming the frame and column
    // for a value that is NaN or infinite (JSON has no such number).
    void frame(const std::vector<BodyState>& dynamic_bodies);
    // A resolved collision; events come in time order. Throws
    // std::domain_error for a value that is NaN or infinite.
    void event(const harness::TrajectoryEvent& event);
    // The engine's own measure of its work (simulation only, no start-up or I/O).
    void cost(double seconds, std::optional<long long> steps = std::nullopt);

    std::size_t frames_written() const { return trajectory_.frames.size(); }
    std::size_t frames_expected() const { return frames_expected_; }
    // The trajectory's text; throws std::logic_error unless every frame was written.
    std::string text() const;

  private:
    harness::Trajectory trajectory_;
    std::size_t dynamic_bodies_ = 0;
    std::size_t frames_expected_ = 0;
    double dt_ = 0.0;
    std::optional<double> cost_seconds_;
    std::optional<long long> cost_steps_;
};

} // namespace impulse::protocol
