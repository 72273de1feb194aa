// The one small interface through which the harness drives a simulator
// (docs/design.md, Layout): build from a scene, step, read state and collisions.
// The impulse engine is one implementation; Box2D and a user's engine can be others.
#pragma once

#include "body.h"
#include "scene.h"
#include "trajectory.h"
#include "world.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness {

class Simulator {
  public:
    virtual ~Simulator() = default;
    // "impulse 0.1.0", "box2d 2.4.1", ...
    virtual std::string engine() const = 0;
    // The settings that decide the physics, as (key, JSON value text) pairs.
    virtual std::vector<std::pair<std::string, std::string>> settings() const = 0;
    // Advances from t0 by dt; throws InputError when the simulator cannot go on.
    virtual void step(double t0, double dt) = 0;
    // State of the scene's body `index` (scene order).
    virtual BodyState state(int index) const = 0;
    // Collisions resolved since the last call, in order.
    virtual std::vector<TrajectoryEvent> take_events() = 0;
    // Machine-independent work done so far (steps, narrow-phase queries,
    // time-of-impact iterations); zeros for a simulator that does not count.
    virtual WorkCounters work() const { return {}; }
};

// A reference engine's contact event as the trajectory records it, before its
// impulse and vn_after are known (the engine's solve fills them in): the
// scene's names for bodies a and b, the contact point, the normal toward a.
inline TrajectoryEvent contact_event(double t, const std::string& a, const std::string& b,
                                     Vec2 point, Vec2 normal, double vn_before) {
    TrajectoryEvent event;
    event.t = t;
    event.a = a;
    event.b = b;
    event.point[0] = point.x;
    event.point[1] = point.y;
    event.normal[0] = normal.x;
    event.normal[1] = normal.y;
    event.vn_before = vn_before;
    return event;
}

std::unique_ptr<Simulator> make_impulse_simulator(const Scene& scene);

} // namespace impulse::harness
