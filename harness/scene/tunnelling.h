// A scene precondition: without ccd, can a body pass through another between
// two steps, unseen? Every verb that simulates asks it before it runs (run,
// check, bless, box2d, render refuse; sweep warns per time step; stress
// refuses the case): docs/refusals-and-progress.md.
#pragma once

#include "scene.h"

#include <optional>
#include <string>

namespace impulse::harness {

// Without ccd a pair is tested only at the ends of a step. Over a step the
// centre of a body moves at most (|v| + |omega| R) dt relative to any point of
// another (R: its farthest vertex; 0 for a circle, whose turning moves no
// surface). Each body contains the disc of its inradius r about its centre
// (a convex shape contains the disc of its smallest centre-to-edge distance),
// so a straight path through the other body's middle stays inside the pair's
// overlap for a length of at least 2 (r_a + r_b): the two thicknesses. A step
// shorter than that cannot jump the overlap, so the end of some step sees it.
//
// The speeds are bounded over the whole run, not only at t = 0: gravity adds
// speed (tunnelling.cpp, gravity_gain, derives the bound). Speed that
// collisions pass from one dynamic body to another is not bounded (a light
// body struck by a heavy one); ccd is the cure for those.
struct TunnellingRefusal {
    std::string path;    // "bodies[1]" (or "gas", "pile") of the faster body of the pair
    std::string message; // one sentence naming both bodies, the speeds, the safe dt and the cure
};

// Empty when solver.ccd is on, when resting contact is time-stepping or "auto"
// (the engine takes time-stepping for any step where a pair could pass
// through), or when no pair can close faster than its thicknesses per step.
std::optional<TunnellingRefusal> tunnelling_refusal(const Scene& scene);

// Throws InputError (the scene file, the faster body's path, the sentence)
// when tunnelling_refusal finds a pair.
void refuse_tunnelling(const Scene& scene);

} // namespace impulse::harness
