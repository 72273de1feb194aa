// Recording a run: any Simulator over a whole scene, frame by frame, within
// the trajectory size limit (docs/memory.md).
#include "record.h"

#include "memory_budget.h"
#include "number_format.h"
#include "progress.h"
#include "trajectory_columns.h"

#include <cmath>
#include <cstdint>
#include <utility>

namespace impulse::harness {

StoppedRun::StoppedRun(const std::string& file, const InputError& cause, Trajectory partial)
    : InputError(file, cause.json_path(), cause.message()),
      trajectory_(std::make_shared<const Trajectory>(std::move(partial))) {}

namespace {

bool finite_event(const TrajectoryEvent& e) {
    for (const double value : {e.t, e.point[0], e.point[1], e.normal[0], e.normal[1], e.impulse,
                               e.vn_before, e.vn_after}) {
        if (!std::isfinite(value)) {
            return false;
        }
    }
    return true;
}

// What a stopped run hands back: the frames so far (the last at t, the end
// of the last full step), the finite events of the step that failed too
// (a Zeno cascade's collisions are what the user needs to see), and why.
[[noreturn]] void stop(Simulator& simulator, const Scene& scene, Trajectory& trajectory,
                       const InputError& cause) {
    for (TrajectoryEvent& e : simulator.take_events()) {
        if (finite_event(e)) {
            trajectory.events.push_back(std::move(e));
        }
    }
    const double t = trajectory.frames.back().front();
    trajectory.partial = TrajectoryPartial{cause.message(), t};
    throw StoppedRun(scene.file, cause, std::move(trajectory));
}

// The run stops, with a sentence, at the first event that could take the
// trajectory past the limit: the events so far fit, the step's others are
// dropped.
void stop_past_limit(const Scene& scene, Trajectory& trajectory, const TrajectorySize& size,
                     const TrajectoryEvent& e) {
    try {
        require_within_trajectory_limit(
            size, scene.file, "",
            "the run stopped at t = " + format_double(e.t) + " s: its frames and " +
                std::to_string(trajectory.events.size() + 1) + " collision events so far",
            true);
    } catch (const InputError& error) {
        trajectory.partial = TrajectoryPartial{error.message(), trajectory.frames.back().front()};
        throw StoppedRun(scene.file, error, std::move(trajectory));
    }
}

} // namespace

Trajectory record(Simulator& simulator, const Scene& scene) {
    Trajectory trajectory;
    trajectory.scene = scene.name;
    trajectory.scene_sha256 = scene.sha256;
    trajectory.engine = simulator.engine();
    trajectory.solver = simulator.settings();

    std::vector<int> dynamic;
    trajectory.columns.push_back("t");
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        if (scene.bodies[i].is_static) {
            continue;
        }
        dynamic.push_back(static_cast<int>(i));
        for (const char* channel : body_channel_suffixes) {
            trajectory.columns.push_back(scene.bodies[i].name + channel);
        }
    }

    auto frame_at = [&](double t) {
        std::vector<double> frame;
        frame.reserve(trajectory.columns.size());
        frame.push_back(t);
        for (int index : dynamic) {
            const BodyState s = simulator.state(index);
            frame.insert(frame.end(), {s.position.x, s.position.y, s.angle, s.velocity.x,
                                       s.velocity.y, s.angular_velocity});
        }
        return frame;
    };

    const long long steps = step_count(scene);
    // The frames are known before the run: a trajectory that could exceed
    // the limit is refused before anything is simulated (docs/memory.md).
    TrajectorySize size =
        header_size_bound(trajectory.columns) +
        frames_size_bound(static_cast<std::uint64_t>(steps) + 1, trajectory.columns.size());
    require_within_trajectory_limit(size, scene.file, "duration",
                                    "the run would record " + std::to_string(steps + 1) +
                                        " frames of " + std::to_string(trajectory.columns.size()) +
                                        " numbers (" + std::to_string(steps) + " steps)",
                                    true);
    // Read once: each event below only compares, and a sentence is built only
    // for the event that passes the limit.
    const std::uint64_t limit = trajectory_limit_bytes();
    trajectory.frames.reserve(static_cast<std::size_t>(steps) + 1);
    trajectory.frames.push_back(frame_at(0.0));
    for (long long k = 0; k < steps; ++k) {
        try {
            // Time as k dt, never accumulated, so it does not drift.
            simulator.step(static_cast<double>(k) * scene.dt, scene.dt);
        } catch (const InputError& e) {
            stop(simulator, scene, trajectory, e);
        }
        for (TrajectoryEvent& e : simulator.take_events()) {
            // Events are not known up front.
            size = size + event_size_bound(e.a.size() + e.b.size());
            if (!size.within(limit)) {
                stop_past_limit(scene, trajectory, size, e);
            }
            trajectory.events.push_back(std::move(e));
        }
        trajectory.frames.push_back(frame_at(static_cast<double>(k + 1) * scene.dt));
        note_simulated_time(static_cast<double>(k + 1) * scene.dt, scene.duration);
    }
    return trajectory;
}

} // namespace impulse::harness
