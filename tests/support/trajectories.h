// Trajectories written by hand, for the tests of what reads them
// (expectations, observables, the trajectory format).
#pragma once

#include "trajectory.h"

#include <string>
#include <utility>
#include <vector>

namespace impulse::test {

// A frame: t, then per body x, y, angle, vx, vy, omega.
using Frame = std::vector<double>;

inline impulse::harness::Trajectory
trajectory_of(const std::vector<std::string>& bodies, std::vector<Frame> frames,
              std::vector<impulse::harness::TrajectoryEvent> events) {
    impulse::harness::Trajectory t;
    t.columns.push_back("t");
    for (const std::string& body : bodies) {
        for (const char* channel : {".x", ".y", ".angle", ".vx", ".vy", ".omega"}) {
            t.columns.push_back(body + channel);
        }
    }
    t.frames = std::move(frames);
    t.events = std::move(events);
    return t;
}

inline impulse::harness::TrajectoryEvent make_event(double t, const std::string& a,
                                                    const std::string& b, double px, double py,
                                                    double nx, double ny, double impulse,
                                                    double vn_before, double vn_after) {
    impulse::harness::TrajectoryEvent event;
    event.t = t;
    event.a = a;
    event.b = b;
    event.point[0] = px;
    event.point[1] = py;
    event.normal[0] = nx;
    event.normal[1] = ny;
    event.impulse = impulse;
    event.vn_before = vn_before;
    event.vn_after = vn_after;
    return event;
}

} // namespace impulse::test
