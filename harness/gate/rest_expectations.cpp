// The dense-contact expectations: what "settled" means for a pile
// (docs/formats.md, "max-overlap" and "at-rest"). Both read the trajectory
// only, like every kind, so they hold any engine to the same rule.
#include "body.h"
#include "expectation_checks.h"
#include "overlap.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

namespace {

// Every body's pose in one frame: dynamic bodies from their columns, static
// ones where the scene puts them (already in `poses`). The name of the first
// body whose pose is not finite, when one is not.
std::optional<std::string> pose_frame(const std::vector<double>& frame,
                                      const std::vector<Mass>& masses, const Scene& scene,
                                      std::vector<Transform>& poses) {
    for (const Mass& m : masses) {
        const Motion s = motion_in(frame, m.columns);
        if (!std::isfinite(s.position.x) || !std::isfinite(s.position.y) ||
            !std::isfinite(s.angle)) {
            return m.body->name;
        }
        impulse::BodyState state;
        state.position = s.position;
        state.angle = s.angle;
        poses[static_cast<std::size_t>(m.body - scene.bodies.data())] =
            impulse::transform_of(state);
    }
    return std::nullopt;
}

// Kinetic and potential energy of every dynamic body in one frame
// (docs/physics.md: K = sum m v^2/2 + I w^2/2, P = -sum m g . x).
struct Energies {
    double kinetic = 0.0;
    double potential = 0.0;
};

Energies energies_in(const std::vector<double>& frame, const std::vector<Mass>& masses,
                     Vec2 gravity) {
    Energies e;
    for (const Mass& m : masses) {
        const Motion s = motion_in(frame, m.columns);
        const double mass = m.body->mass;
        e.kinetic += 0.5 * mass * length_squared(s.velocity) + 0.5 * m.inertia * s.omega * s.omega;
        e.potential += -mass * dot(gravity, s.position);
    }
    return e;
}

} // namespace

// The deepest interpenetration over every frame and every pair (overlap.h),
// 0 expected: the row names the frame time and the pair where it is deepest.
void check_max_overlap(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const std::optional<std::vector<Mass>> masses = masses_of(scene, trajectory, checks);
    if (!masses) {
        return;
    }
    const double atol = checks.expectation().atol;
    std::vector<Transform> poses = initial_poses(scene.bodies);
    std::optional<Overlap> worst;
    double worst_t = 0.0;
    for (const std::vector<double>& frame : trajectory.frames) {
        const double t = frame_time(frame);
        if (const std::optional<std::string> body = pose_frame(frame, *masses, scene, poses)) {
            checks.failure("deepest overlap", "the pose of " + single_quoted(*body) +
                                                  " at t = " + sentence_number(t) +
                                                  " s is not finite, so its overlaps cannot be "
                                                  "measured");
            return;
        }
        const std::optional<Overlap> found = deepest_overlap(scene.bodies, poses);
        if (found && (!worst || found->depth > worst->depth)) {
            worst = found;
            worst_t = t;
        }
    }
    if (!worst) {
        checks.judged("deepest overlap: no pair touches in any frame", true, 0.0, 0.0, "", atol);
        return;
    }
    const std::string pair = single_quoted(scene.bodies[worst->a].name) + " and " +
                             single_quoted(scene.bodies[worst->b].name);
    checks.judged("deepest overlap, " + pair + " at t = " + sentence_number(worst_t) + " s",
                  worst->depth <= atol, 0.0, worst->depth,
                  pair + " interpenetrate by " + sentence_number(worst->depth) +
                      " m at t = " + sentence_number(worst_t) + " s, more than the atol " +
                      sentence_number(atol) + " m allowed",
                  atol);
}

// For every frame with t >= after: K(t) <= rtol * released(t) + atol, where
// released(t) = E(0) - P(t), the energy gravity and the initial motion have
// given up so far. One row: the frame with the largest excess.
void check_at_rest(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const std::optional<std::vector<Mass>> masses = masses_of(scene, trajectory, checks);
    if (!masses) {
        return;
    }
    const Expectation& x = checks.expectation();
    const double after = x.t;
    const std::string what = "at rest from t = " + sentence_number(after) + " s";
    const Energies first = energies_in(trajectory.frames.front(), *masses, scene.gravity);
    const double initial = first.kinetic + first.potential;
    std::optional<std::size_t> worst;
    double worst_excess = -std::numeric_limits<double>::infinity();
    Energies worst_energies;
    for (std::size_t k = 0; k < trajectory.frames.size(); ++k) {
        if (!(frame_time(trajectory.frames[k]) >= after)) {
            continue;
        }
        const Energies e = energies_in(trajectory.frames[k], *masses, scene.gravity);
        const double allowed = x.rtol * (initial - e.potential) + x.atol;
        const double excess = e.kinetic - allowed;
        if (!worst || excess > worst_excess || std::isnan(excess)) {
            worst = k;
            worst_excess = std::isnan(excess) ? std::numeric_limits<double>::infinity() : excess;
            worst_energies = e;
        }
        if (std::isnan(excess)) {
            break; // nothing is worse than a blown-up frame
        }
    }
    if (!worst) {
        checks.failure(what, "the run has no frame at or after t = " + sentence_number(after) +
                                 " s; it ends at t = " +
                                 sentence_number(frame_time(trajectory.frames.back())) + " s");
        return;
    }
    const double t = frame_time(trajectory.frames[*worst]);
    const double released = initial - worst_energies.potential;
    const double allowed = x.rtol * released + x.atol;
    checks.judged(
        what + ", most kinetic energy for what was released at t = " + sentence_number(t) + " s",
        worst_energies.kinetic <= allowed, 0.0, worst_energies.kinetic,
        "not at rest at t = " + sentence_number(t) + " s: the kinetic energy " +
            sentence_number(worst_energies.kinetic) + " J is more than the " +
            sentence_number(allowed) + " J allowed (rtol " + sentence_number(x.rtol) +
            " x released " + sentence_number(released) + " J + atol " + sentence_number(x.atol) +
            ")",
        allowed);
}

} // namespace impulse::harness
