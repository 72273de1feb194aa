// The exact answers of docs/physics.md ("Exact answers for checking"), computed
// from a scene's own parameters, the conditions under which each applies, and
// the quantities a trajectory is read for to compare with them.
//
// Shared by the loader (which refuses an expectation or a Box2D observable
// whose formula cannot apply), the expectations (expectations.cpp) and the
// Box2D observables (observables.cpp), so the three never disagree on a
// formula or on when it holds.
#pragma once

#include "scene.h"
#include "trajectory.h"
#include "trajectory_columns.h"

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

// ---------------------------------------------------------------- the scene at t = 0

// Below this height difference two corners count as level: a landing would
// touch both (docs/physics.md's corner formula is for a single corner).
inline constexpr double level_corners = 1e-9;
// Parallel within rounding: |cross| <= 1e-9 for unit vectors.
inline constexpr double parallel_tolerance = 1e-9;

// g of gravity (0, -g).
double gravity_magnitude(const Scene& scene);

// Where a body moved straight down from its pose at t = 0 first touches a
// static body: how far it falls (h0; the signed gap when it touches or
// overlaps one at t = 0), which static body (index into scene.bodies), and
// the contact's normal and mean point there. Empty when nothing static lies
// below it. A roof above or a wall beside is never the ground.
struct Landing {
    double gap = 0.0;
    int ground = -1;
    Vec2 normal;
    Vec2 point;
};
std::optional<Landing> landing_below(const Scene& scene, const SceneBody& body);

// The gap h0 of landing_below. Empty when nothing static lies below the body.
std::optional<double> gap_to_static_ground(const Scene& scene, const SceneBody& body);

// A polygon body's vertices in the world at t = 0.
std::vector<Vec2> world_vertices(const SceneBody& body);

// Whether a polygon's lowest corner is alone (the next is at least
// level_corners higher) and straight below its centre, to rounding of the
// turn: then the ground's impulse passes through the centre of mass and a
// body free to rotate still bounces without spin.
bool lands_on_corner_below_centre(const SceneBody& body);

// Whether some face of a polygon body faces along the unit vector u (either
// way) at t = 0: a polygon pair's contact normal is always a face normal.
bool has_face_along(const SceneBody& body, Vec2 u);

// ---------------------------------------------------------------- when a formula applies

// Why a formula does not apply, and what the declaring entry should be told
// about: the entry itself, the body it names (drop, corner impact, head-on's
// a) or its other body (head-on's b).
struct Refusal {
    enum class Where { entry, body, other };
    Where where = Where::entry;
    std::string message; // one sentence, starting with `formula`
};

// docs/physics.md, drop: released at rest above static ground under gravity
// (0, -g), g > 0, bouncing without rotation.
std::optional<Refusal> drop_refusal(const Scene& scene, const SceneBody& body,
                                    const std::string& formula);
// docs/physics.md, single-corner impact: a polygon free to rotate, not spinning,
// falling onto static ground on exactly one corner.
std::optional<Refusal> corner_impact_refusal(const Scene& scene, const SceneBody& body,
                                             const std::string& formula);
// docs/physics.md, head-on: two distinct bodies, 1D, no rotation, free space.
std::optional<Refusal> head_on_refusal(const Scene& scene, const SceneBody& a, const SceneBody& b,
                                       const std::string& formula);
// docs/physics.md: frictionless contact in free space conserves momentum and
// angular momentum; with e = 1, energy. `quantity`: "momentum",
// "angular_momentum" or "energy". Empty when the scene conserves it.
std::optional<std::string> conservation_refusal(const Scene& scene, const std::string& quantity);

// ---------------------------------------------------------------- the formulas

// An exact answer and the size of the terms it is made of. A relative
// tolerance applies to the scale, not to the value: a post-impact velocity
// that cancels to zero (equal masses, e = 1) comes out of a simulation as a
// difference of numbers of the size of the terms, rounded.
struct Exact {
    double value = 0.0;
    double scale = 0.0;
};

// A value whose terms do not cancel: its own size is the scale.
inline Exact plain(double value) {
    return {value, std::abs(value)};
}

// docs/physics.md, drop: released at rest a gap h0 above the ground, first impact
// at t1 = sqrt(2 h0 / g) with speed v1 = g t1 = sqrt(2 g h0); each bounce
// leaves at e times the speed it came in with, so impact n + 1 comes a flight
// of 2 e^n v1 / g after impact n, and rises to e^(2n) h0.
struct DropLadder {
    double h0 = 0.0;
    double g = 0.0;
    double e = 0.0;

    double v1() const;
    double t1() const;
    // e^n by multiplication, as the bounces compound it.
    double e_to(int n) const;
    // t_n = t1 + sum_{k=1..n-1} 2 e^k v1 / g, n = 1, 2, ...
    double impact_time(int n) const;
    // e^n v1: the speed impact n sends the body up with.
    double rebound_speed(int n) const;
    // e^(2n) h0 (h0 for n = 0).
    double apex_gap(int n) const;
};

// The drop of `body` (drop_refusal must be empty); empty without static ground.
std::optional<DropLadder> drop_ladder(const Scene& scene, const SceneBody& body);

// docs/physics.md, single-corner impact on static ground (n = (0, 1)), for a body
// not spinning: the lowest corner falls the gap h, meets the ground at speed v,
// and the impulse j = (1 + e) v / (1/M + rx^2 / I) at horizontal offset rx sets
// vy' = -v + j / M and w' = rx j / I; vx is untouched.
struct CornerImpact {
    double t_hit = 0.0;
    double v = 0.0;       // speed at impact
    double rx = 0.0;      // corner's horizontal offset from the centre of mass
    double point_x = 0.0; // where the corner touches
    double point_scale = 0.0;
    double j = 0.0;
    double vy_after = 0.0;
    double w_after = 0.0;
};

// `h`: the gap to the ground at t = 0.
CornerImpact corner_impact(const Scene& scene, const SceneBody& body, double h);

// docs/physics.md, head-on (1D, no rotation): along the unit vector u from A's
// centre to B's, momentum is exact and restitution sets the closing speed:
//   vA' = (MA vA + MB vB - MB e (vA - vB)) / (MA + MB)
//   vB' = (MA vA + MB vB + MA e (vA - vB)) / (MA + MB)
//   j   = MA MB (1 + e) (vA - vB) / (MA + MB)
// The components across u are untouched: the impulse acts along u only.
struct HeadOn {
    Vec2 u;
    double va = 0.0, vb = 0.0; // along u, before
    double pa = 0.0, pb = 0.0; // across u, before and after
    Exact va_after, vb_after, j;
};

HeadOn head_on(const Scene& scene, const SceneBody& a, const SceneBody& b);

// ---------------------------------------------------------------- reading a trajectory

struct Motion {
    Vec2 position;
    double angle = 0.0;
    Vec2 velocity;
    double omega = 0.0;
};

Motion motion_in(const std::vector<double>& frame, const BodyColumns& columns);

// A dynamic body as the totals need it: mass, inertia (0 when it does not
// rotate: its spin stays 0 and carries nothing) and where its columns are.
struct Mass {
    const SceneBody* body = nullptr;
    BodyColumns columns;
    double inertia = 0.0;
};

// Every dynamic body of the scene with its columns; empty when the trajectory
// lacks a body's columns (`missing` then names it).
std::optional<std::vector<Mass>> masses_of(const Scene& scene, const Trajectory& trajectory,
                                           std::string& missing);

// Momentum, angular momentum about the origin and energy (kinetic + potential)
// of every dynamic body in one frame, each with the sum of its terms'
// magnitudes (each product's own terms: m x_x v_y and m x_y v_x, m g_x x and
// m g_y y): conserved totals may be zero (two equal bodies meeting), so a
// relative tolerance is taken of the terms, the size of the numbers rounded.
// A frame's scale may be 0 (a body at rest at the origin): a comparison of
// frames takes the larger scale of the frames it spans.
struct Totals {
    Vec2 momentum;
    double angular_momentum = 0.0;
    double energy = 0.0;
    double momentum_scale = 0.0;
    double angular_momentum_scale = 0.0;
    double energy_scale = 0.0;
};

// P = sum m v; L = sum (m x cross v + I w); E = sum (m v^2 / 2 + I w^2 / 2 - m g . x).
Totals totals_in(const std::vector<double>& frame, const std::vector<Mass>& masses, Vec2 gravity);

} // namespace impulse::harness
