// The sweep's verdict against each reference engine, in words a stranger
// reads: "impulse at Box2D 2.4.1's cost: 5.3 orders of magnitude more
// accurate", and whether impulse's front dominates the reference's. A pure
// function of the measured points, so it can be tested with made-up ones.
#pragma once

#include "sweep.h"

#include <cstddef>
#include <string>
#include <vector>

namespace impulse::harness {

// Which error a verdict judges: the point's error (on a pile, the deepest
// overlap) or a pile's energy gained.
enum class SweepAxis { error, energy };

// The axis's value of a point.
double axis_value(const SweepPoint& point, SweepAxis axis);

// Pareto dominance on cost and the axis: a is no worse on both and better on one.
bool dominates(const SweepPoint& a, const SweepPoint& b, SweepAxis axis);

// The time step a reference is compared at: its point nearest 60 Hz.
inline constexpr double verdict_dt = 1.0 / 60.0;

// An error of exactly 0 says only that it is below what the measurement
// resolves: it counts as sweep_error_floor (1e-9) when orders of magnitude are
// taken, and the verdict says "at least" (as target 1 does). Other errors,
// however small, count as measured.

struct ReferenceVerdict {
    std::string family; // "box2d", "box2d-3", ...
    std::string title;  // "Box2D 2.4.1"
    // The reference point: the family's measured point at the dt nearest
    // verdict_dt, with its default settings when the grid has them (Box2D
    // 2.4.1: 1 sub-step, 8/3 iterations; a Node reference: its own or 4
    // sub-steps), then the cheapest.
    bool measured = false;
    std::size_t reference_point = 0;
    // The engine under study's most accurate measured point costing no more
    // (ties to the cheaper).
    bool found = false;
    std::size_t impulse_point = 0;
    // log10(reference error / impulse error), an error of 0 taken as
    // sweep_error_floor: > 0 more accurate, < 0 less.
    double orders = 0.0;
    bool floored = false; // either error was 0
    // The reference's Pareto front and how many of its points some point of
    // the engine under study dominates (cheaper or as cheap, and more
    // accurate or as accurate, one of them strictly).
    std::size_t front_size = 0;
    std::size_t front_dominated = 0;
    bool dominates() const { return front_size > 0 && front_dominated == front_size; }
};

// One verdict per reference in SweepResult::references, in that order.
std::vector<ReferenceVerdict> reference_verdicts(const SweepResult& result, SweepAxis axis);

// "impulse at Box2D 2.4.1's cost: 5.3 orders of magnitude more accurate",
// "... less accurate", "... as accurate (within 0.1 orders of magnitude)",
// "... no impulse point costs that little", or "... not measured".
std::string verdict_headline(const SweepResult& result, const ReferenceVerdict& verdict,
                             SweepAxis axis);

// The headline, the two points it compares and the front's dominance.
std::string verdict_sentence(const SweepResult& result, const ReferenceVerdict& verdict,
                             SweepAxis axis);

// "Box2D 1/60 sub 1, it 8/3", "impulse verlet/secant 1/120 tol 1e-12",
// "box2d-3 1/60 sub 4": a point for people.
std::string sweep_point_label(const SweepPoint& point);

// "1/60" when dt is the inverse of a whole number, otherwise its shortest form.
std::string sweep_dt_label(double dt);

} // namespace impulse::harness
