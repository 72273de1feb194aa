// The energy guard of time-stepping (docs/engine.md, "Dense contact"). The
// holding step itself never adds energy (docs/physics.md), but the overlap
// guard lifts bodies and an iterative solve stops at a residual: either can
// add a little. An island whose energy rose beyond rounding gives it back.
#pragma once

#include "time_stepping_scratch.h"
#include "world.h"

namespace impulse {

// For every island some impulse acted on this step, or with a body the
// overlap guard moved (s.guard_moved): if its energy (kinetic + potential,
// from s.start to now) rose by dE beyond 8 eps of the sum of its terms'
// magnitudes, its velocities are scaled by sqrt(1 - dE / K), or, when its
// kinetic energy K is less than dE, it goes back to its poses at the step's
// start, at rest (energy P(x_k) <= E_k). Energy then never rises beyond
// rounding, whatever moved the bodies. A body in no island that the overlap
// guard moved is checked the same way on its own. Islands that one group of
// the overlap guard moved bodies of are checked as one (s.guard_joined), so a
// return to x_k never undoes half of a separation. Counted in
// world.work.energy_guard_steps and energy_guard_joules, and by path in
// energy_guard_rescaled, energy_guard_returned and energy_guard_lone_bodies.
// A unit with a body the overlap guard could not bring within d
// (s.guard_stuck) goes back to its poses at the step's start, at rest,
// whatever its energy (world.work.overlap_guard_returned).
void guard_energy(World& world, TimeSteppingScratch& s);

} // namespace impulse
