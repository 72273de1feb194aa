// The one first divergence of a comparison (docs/gate-rules.md, "The first
// divergence"): the terminal, JUnit, summary.md and the HTML report all name
// the same value, and say what caused it.
#pragma once

#include "compare.h"
#include "scene_check.h"

#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

// The earliest value that differs, over frames AND events, by golden time.
// Ties at the same time: an event before a frame (the collision happens
// inside the step whose end the frame records; an event within 1e-9 of the
// golden's frame step of a frame's time is at it); among frames, the column
// order of the golden (body by body in scene order, then x, y, angle, vx,
// vy, omega); among events, the lower index, then the field order t, point,
// normal, impulse, vn_before, vn_after. A time that is not a number (a frame
// without a t column) counts as later than any time. Null when no value
// differs (equal, or different only in shape).
const Divergence* earliest_divergence(const Comparison& comparison);

// Whether a divergence is an event field ("events[3].impulse").
bool is_event_divergence(const Divergence& divergence);

struct FirstDivergence {
    Divergence divergence;
    bool is_event = false;
    // Every other divergence of the comparison is at or after this one: it
    // is where the runs parted, and the rest follows from it.
    bool the_rest_follows = true;
    // What caused it, derived from the data: "the first collision's impulse
    // differs by 1 ULP; every later difference follows from it", or, for a
    // frame value, which channel of which body differs first.
    std::string cause;
};

std::optional<FirstDivergence> first_divergence_of(const Comparison& comparison);

// The line every report prints for a failed comparison: "first divergence:
// events[0].impulse at t = 0.4515 s (golden 2.5, new 2.5000000000000004):
// the first collision's impulse differs by 1 ULP; every later difference
// follows from it", then shape_clause. When no compared value differs, the
// first shape difference alone ("event counts differ: golden 109, new 108;
// the first 108 are compared").
std::string first_divergence_line(const Comparison& comparison);

// What a first divergence adds when the shapes differ too, so that every
// report names the same value first and the shape after it: "; the
// trajectories also differ in shape: event counts differ: ... (and 1 more)";
// empty when the shapes agree.
std::string shape_clause(const Comparison& comparison);

// What makes two scenes' first divergences "the same cause": the event
// field with its index ("events[0].impulse"), or for a frame value its
// channel ("the velocity channel"). Empty when there is none.
std::string cause_key(const Comparison& comparison);

// One line per cause shared by two or more failed scenes, in the order of
// the first scene with it: "3 scenes start diverging at events[0].impulse:
// drop-box, drop-circle, stack". Scenes are named ENGINE/NAME when the check
// carries an engine.
std::vector<std::string> shared_causes(const std::vector<SceneCheck>& checks);

} // namespace impulse::harness
