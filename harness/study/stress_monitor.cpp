// The stress matrix's invariants (stress.h, StressMonitor): each measured at
// every frame, its worst value kept, and judged against its bound and why.
// The drop and head-on rows are docs/physics.md's exact answers
// (stress_exact_answers.cpp).
#include "overlap.h"
#include "stress.h"
#include "stress_exact_answers.h"
#include "stress_rows.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace impulse::harness {

namespace {

// The spacing of doubles at x: what one rounding of a coordinate there can be off by, twice.
double ulp_at(double x) {
    const double a = std::abs(x);
    return std::nextafter(a, infinity) - a;
}

} // namespace

// ---------------------------------------------------------------- measuring

StressMonitor::StressMonitor(const Scene& scene, StressChecks checks)
    : scene_(&scene), checks_(std::move(checks)), margins_(checks_.sides.size(), infinity),
      margins_at_(checks_.sides.size()), drift_worst_(checks_.drifts.size(), 0.0),
      drift_at_(checks_.drifts.size()), support_worst_(checks_.supports.size(), 0.0),
      support_at_(checks_.supports.size()) {}

Totals StressMonitor::totals_of(const std::vector<BodyState>& states) const {
    Totals t;
    const Vec2 g = scene_->gravity;
    for (std::size_t i = 0; i < states.size(); ++i) {
        const SceneBody& body = scene_->bodies[i];
        if (body.is_static) {
            continue;
        }
        const BodyState& s = states[i];
        const double m = body.mass;
        const double inertia = body.rotation ? body.inertia : 0.0;
        t.momentum += m * s.velocity;
        t.momentum_scale += m * length(s.velocity);
        const double orbital = m * cross(s.position, s.velocity);
        const double spin = inertia * s.angular_velocity;
        t.angular_momentum += orbital + spin;
        t.angular_momentum_scale += std::abs(orbital) + std::abs(spin);
        // Potential energy from the body's start, not from the origin: a
        // scene 1e4 m away would otherwise carry m g 1e4 in every total and
        // hide the changes in its last digits.
        const double kinetic = 0.5 * m * dot(s.velocity, s.velocity) +
                               0.5 * inertia * s.angular_velocity * s.angular_velocity;
        const double potential = -m * dot(g, s.position - start_positions_[i]);
        t.energy += kinetic + potential;
        t.energy_scale += kinetic + std::abs(potential);
    }
    return t;
}

void StressMonitor::observe(double t, const std::vector<BodyState>& states) {
    if (frames_ == 0) {
        start_positions_.clear();
        for (const BodyState& s : states) {
            start_positions_.push_back(s.position);
        }
    }
    ++frames_;
    // A frame with a NaN or an infinity says nothing about the geometry, so
    // the other checks skip it.
    if (observe_finite(t, states)) {
        observe_penetration(t, states);
        observe_sides(t, states);
        observe_totals(t, states);
        observe_drifts(t, states);
        observe_rest(t, states);
        observe_supports(t, states);
    }
    last_ = states;
    last_t_ = t;
}

// Finite: every value of every dynamic body.
bool StressMonitor::observe_finite(double t, const std::vector<BodyState>& states) {
    const std::vector<SceneBody>& bodies = scene_->bodies;
    bool finite = true;
    for (std::size_t i = 0; i < states.size(); ++i) {
        if (bodies[i].is_static) {
            continue;
        }
        const BodyState& s = states[i];
        const std::pair<const char*, double> values[] = {
            {"x", s.position.x},  {"y", s.position.y},  {"angle", s.angle},
            {"vx", s.velocity.x}, {"vy", s.velocity.y}, {"omega", s.angular_velocity}};
        for (const auto& [quantity, value] : values) {
            if (std::isfinite(value)) {
                largest_ = std::max(largest_, std::abs(value));
            } else {
                finite = false;
                if (non_finite_.empty()) {
                    non_finite_ = single_quoted(bodies[i].name) + "." + quantity + " is " +
                                  (std::isnan(value) ? "NaN"
                                   : value > 0       ? "+inf"
                                                     : "-inf") +
                                  " at " + at_time(t);
                }
            }
        }
    }
    return finite;
}

// Interpenetration: the deepest pair of the frame, found through the overlap
// grid (overlap.h) so a pile of 1000 bodies costs O(N) per frame, not O(N^2).
void StressMonitor::observe_penetration(double t, const std::vector<BodyState>& states) {
    const std::vector<SceneBody>& bodies = scene_->bodies;
    poses_.resize(states.size());
    for (std::size_t i = 0; i < states.size(); ++i) {
        poses_[i] = transform_of(states[i]);
    }
    const std::optional<Overlap> overlap = deepest_overlap(bodies, poses_);
    if (overlap && overlap->depth > deepest_) {
        deepest_ = overlap->depth;
        deepest_at_ = single_quoted(bodies[overlap->a].name) + " and " +
                      single_quoted(bodies[overlap->b].name) + " at " + at_time(t);
    }
}

void StressMonitor::observe_sides(double t, const std::vector<BodyState>& states) {
    for (std::size_t r = 0; r < checks_.sides.size(); ++r) {
        const SideRule& rule = checks_.sides[r];
        const double margin = dot(states[static_cast<std::size_t>(rule.a)].position -
                                      states[static_cast<std::size_t>(rule.b)].position,
                                  rule.axis);
        if (margin < margins_[r]) {
            margins_[r] = margin;
            margins_at_[r] = at_time(t);
        }
    }
}

void StressMonitor::observe_totals(double t, const std::vector<BodyState>& states) {
    const Totals now = totals_of(states);
    if (frames_ == 1) {
        start_ = now;
    }
    momentum_drift_ = std::max(momentum_drift_, length(now.momentum - start_.momentum));
    angular_momentum_drift_ =
        std::max(angular_momentum_drift_, std::abs(now.angular_momentum - start_.angular_momentum));
    momentum_scale_ = std::max(momentum_scale_, now.momentum_scale);
    angular_momentum_scale_ = std::max(angular_momentum_scale_, now.angular_momentum_scale);
    energy_scale_ = std::max({energy_scale_, now.energy_scale, checks_.energy_scale_floor});
    const double change = now.energy - start_.energy;
    if (change > energy_gain_) {
        energy_gain_ = change;
        energy_gain_at_ = at_time(t);
    }
    if (std::abs(change) > energy_drift_) {
        energy_drift_ = std::abs(change);
        energy_drift_at_ = at_time(t);
    }
}

// ---------------------------------------------------------------- pile rows

void StressMonitor::observe_drifts(double t, const std::vector<BodyState>& states) {
    const std::vector<SceneBody>& bodies = scene_->bodies;
    for (std::size_t c = 0; c < checks_.drifts.size(); ++c) {
        for (std::size_t i = 0; i < states.size(); ++i) {
            if (bodies[i].is_static) {
                continue;
            }
            const double drift =
                std::abs(dot(states[i].position - start_positions_[i], checks_.drifts[c].axis));
            if (drift > drift_worst_[c]) {
                drift_worst_[c] = drift;
                drift_at_[c] = single_quoted(bodies[i].name) + " at " + at_time(t);
            }
        }
    }
}

// K(t) against what the fall released, K(0) + sum m g.(x - x0): the at-rest
// expectation's measure (rest_expectations.cpp), here on the engine's states.
void StressMonitor::observe_rest(double t, const std::vector<BodyState>& states) {
    if (!checks_.at_rest) {
        return;
    }
    const std::vector<SceneBody>& bodies = scene_->bodies;
    double kinetic = 0.0;
    double fallen = 0.0; // potential energy lost since t = 0
    for (std::size_t i = 0; i < states.size(); ++i) {
        if (bodies[i].is_static) {
            continue;
        }
        const BodyState& s = states[i];
        const double inertia = bodies[i].rotation ? bodies[i].inertia : 0.0;
        kinetic += 0.5 * bodies[i].mass * dot(s.velocity, s.velocity) +
                   0.5 * inertia * s.angular_velocity * s.angular_velocity;
        fallen += bodies[i].mass * dot(scene_->gravity, s.position - start_positions_[i]);
    }
    if (frames_ == 1) {
        start_kinetic_ = kinetic;
    }
    if (t < checks_.at_rest->after) {
        return;
    }
    const double released = start_kinetic_ + fallen;
    const double ratio = released > 0.0 ? kinetic / released : (kinetic > 0.0 ? infinity : 0.0);
    if (ratio > rest_worst_ || rest_at_.empty()) {
        rest_worst_ = std::max(rest_worst_, ratio);
        rest_at_ = at_time(t);
    }
}

// The impulse through the contact under body k in the step just taken: the
// momentum bodies k and up gained along -g, less gravity's kick on them,
// sum_{j >= k} m_j (dv_j . up + |g| h). Held at rest it is |g| h sum m_j.
void StressMonitor::observe_supports(double t, const std::vector<BodyState>& states) {
    if (frames_ < 2 || checks_.supports.empty()) {
        return;
    }
    const double g = length(scene_->gravity);
    const Vec2 up = g > 0.0 ? (-1.0 / g) * scene_->gravity : Vec2{0.0, 1.0};
    const double h = t - last_t_;
    for (std::size_t c = 0; c < checks_.supports.size(); ++c) {
        const std::vector<int>& column = checks_.supports[c].column;
        double measured = 0.0;
        double weight = 0.0;
        for (std::size_t k = column.size(); k-- > 0;) {
            const auto j = static_cast<std::size_t>(column[k]);
            const double m = scene_->bodies[j].mass;
            measured += m * (dot(states[j].velocity - last_[j].velocity, up) + g * h);
            weight += m * g * h;
            const double error = std::abs(measured - weight) / weight;
            if (error > support_worst_[c] || support_at_[c].empty()) {
                support_worst_[c] = std::max(support_worst_[c], error);
                support_at_[c] =
                    "under " + single_quoted(scene_->bodies[j].name) + " at " + at_time(t);
            }
        }
    }
}

void StressMonitor::add_pile_rows(std::vector<StressRow>& rows) const {
    const std::vector<SceneBody>& bodies = scene_->bodies;
    for (std::size_t c = 0; c < checks_.drifts.size(); ++c) {
        const Vec2 axis = checks_.drifts[c].axis;
        const std::string along = axis.y == 0.0 ? "x" : axis.x == 0.0 ? "y" : "the axis";
        rows.push_back(judged("drift in " + along + " (m)", drift_worst_[c],
                              checks_.drifts[c].bound, Bound::at_most,
                              drift_at_[c].empty() ? "nothing moved" : "largest: " + drift_at_[c]));
    }
    if (checks_.at_rest) {
        // A run that ended before `after` never showed it was at rest.
        rows.push_back(judged(
            "at rest after " + at_time(checks_.at_rest->after),
            rest_at_.empty() ? infinity : rest_worst_, checks_.at_rest->rtol, Bound::at_most,
            rest_at_.empty() ? "the run ended before " + at_time(checks_.at_rest->after)
                             : "kinetic energy over the energy released, largest at " + rest_at_));
    }
    for (std::size_t c = 0; c < checks_.supports.size(); ++c) {
        const std::vector<int>& column = checks_.supports[c].column;
        const std::string top = column.empty()
                                    ? std::string("?")
                                    : bodies[static_cast<std::size_t>(column.back())].name;
        rows.push_back(judged(
            "support impulse under " + single_quoted(top) + "'s column (relative)",
            support_worst_[c], checks_.supports[c].rtol, Bound::at_most,
            support_at_[c].empty()
                ? "no step taken"
                : "impulse per step against the weight above times h, worst " + support_at_[c]));
    }
}

void StressMonitor::observe(const TrajectoryEvent& event) {
    events_.push_back(event);
}

// ---------------------------------------------------------------- judging

std::vector<StressRow> StressMonitor::rows() const {
    std::vector<StressRow> rows = geometry_rows();
    const double budget = position_budget();
    add_conservation_rows(rows, budget);
    add_pile_rows(rows);
    if (checks_.drop) {
        for (StressRow& row : drop_rows(*scene_, *checks_.drop, events_, budget)) {
            rows.push_back(std::move(row));
        }
    }
    if (checks_.head_on) {
        for (StressRow& row : head_on_rows(*scene_, *checks_.head_on, events_, last_)) {
            rows.push_back(std::move(row));
        }
    }
    return rows;
}

std::vector<StressRow> StressMonitor::geometry_rows() const {
    const Scene& scene = *scene_;
    std::vector<StressRow> rows;
    rows.push_back(
        judged("finite", non_finite_.empty() ? largest_ : std::nan(""), infinity, Bound::finite,
               non_finite_.empty() ? "largest magnitude of any state value" : non_finite_));
    rows.push_back(judged("interpenetration (m)", deepest_,
                          checks_.overlap_bound.value_or(scene.solver.contact_tolerance),
                          Bound::at_most,
                          deepest_at_.empty() ? "no pair ever overlapped" : deepest_at_));
    for (std::size_t r = 0; r < checks_.sides.size(); ++r) {
        const SideRule& rule = checks_.sides[r];
        rows.push_back(judged(
            "side: " + single_quoted(scene.bodies[static_cast<std::size_t>(rule.a)].name) + " of " +
                single_quoted(scene.bodies[static_cast<std::size_t>(rule.b)].name) + " (m)",
            margins_[r], 0.0, Bound::above,
            "closest approach of the centres along the axis, at " + margins_at_[r]));
    }
    return rows;
}

// Rounding of the positions 1e4 m out: each step's update rounds every
// coordinate to half an ULP there, and each collision's search compares
// positions rounded so (twice). Whatever is made of positions can be off by
// this much on top of what it is off by at the origin.
double StressMonitor::position_budget() const {
    const long long steps = std::max(frames_ - 1, 0LL);
    const auto collisions = static_cast<double>(events_.size());
    const double offset_ulp = ulp_at(checks_.offset);
    return checks_.offset > 0.0
               ? (0.5 * static_cast<double>(steps) + 2.0 * collisions + 2.0) * offset_ulp
               : 0.0;
}

void StressMonitor::add_conservation_rows(std::vector<StressRow>& rows,
                                          double position_budget) const {
    const Scene& scene = *scene_;
    const auto collisions = static_cast<double>(events_.size());
    double weight = 0.0; // m |g| of every dynamic body: potential energy per metre
    for (const SceneBody& body : scene.bodies) {
        weight += body.is_static ? 0.0 : body.mass * length(scene.gravity);
    }
    const double energy_offset = relative(weight * position_budget, energy_scale_);

    if (checks_.momentum) {
        rows.push_back(judged("momentum drift (relative)",
                              relative(momentum_drift_, momentum_scale_), stress_relative_slack,
                              Bound::at_most, "|P - P0| over the largest sum of |m v|"));
    }
    if (checks_.angular_momentum) {
        rows.push_back(judged("angular momentum drift (relative)",
                              relative(angular_momentum_drift_, angular_momentum_scale_),
                              stress_relative_slack, Bound::at_most,
                              "about the origin, over the largest sum of |terms|"));
    }
    if (checks_.energy_gain) {
        // e <= 1 never adds energy in exact arithmetic. What rounding adds
        // (an epsilon or so of the terms per step or collision, either way,
        // mostly cancelling) is given a stated slack of 1e-12 of the terms;
        // the largest gain in the matrix at the origin is 2.4e-14.
        rows.push_back(judged("energy gain (relative)", relative(energy_gain_, energy_scale_),
                              stress_relative_slack + energy_offset, Bound::at_most,
                              energy_gain_at_.empty() ? "never above the start"
                                                      : "largest at " + energy_gain_at_));
    }
    if (checks_.energy_drift) {
        // e = 1 conserves energy exactly in exact arithmetic; each collision's
        // rounding changes it by at most energy_ulps_per_collision epsilons of
        // the kinetic energy, and the errors of many collisions can add up.
        const double bound = stress_relative_slack +
                             energy_ulps_per_collision * epsilon * collisions + energy_offset;
        rows.push_back(judged("energy drift (relative)", relative(energy_drift_, energy_scale_),
                              bound, Bound::at_most,
                              energy_drift_at_.empty()
                                  ? "never moved"
                                  : "largest at " + energy_drift_at_ + ", " +
                                        std::to_string(events_.size()) + " collisions"));
    }
}

} // namespace impulse::harness
