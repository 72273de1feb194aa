// Local stepping's bookkeeping (docs/engine.md, "Local stepping"): within one
// step every body keeps its own clock, so a collision restarts only the two
// bodies in it, and the collisions found so far wait in time order.
#pragma once

#include "body.h"
#include "broad_phase.h"

namespace impulse {

struct BodyClock {
    BodyState start;    // the body's state at `since`
    double since = 0.0; // seconds after the step's start: the body's last restart
    BodyState end;      // start integrated to the end of the step
    Transform end_pose; // of end, computed once per restart
    Aabb end_box;       // of the shape at end_pose
    int version = 0;    // bumped at every restart; older pending collisions are stale
    int collisions = 0; // within this step
};

// A collision found between two bodies' current motions, waiting for its turn.
struct PendingCollision {
    double time = 0.0; // seconds after the step's start
    int a = -1;
    int b = -1;
    int version_a = 0;
    int version_b = 0;
    bool converged = false;
    // Already interpenetrating where the search began: a collision the seed's
    // end-of-step test missed (a graze within one step), seen only now.
    bool late = false;
    BodyState state_a; // at time
    BodyState state_b;
};

// The queue's order: earliest first, then by the pair, so equal times resolve
// the same way on every machine. std::priority_queue keeps the largest on top.
constexpr bool later(const PendingCollision& x, const PendingCollision& y) {
    if (x.time != y.time) {
        return x.time > y.time;
    }
    if (x.a != y.a) {
        return x.a > y.a;
    }
    return x.b > y.b;
}

} // namespace impulse
