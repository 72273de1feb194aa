// The stress matrix (stress.h): the invariant checkers with the bound of each and why, and the
// cases.
#include "stress.h"

#include "exact_answers.h"
#include "input_error.h"
#include "manifold.h"
#include "progress.h"
#include "simulator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <utility>

namespace impulse::harness {

namespace {

constexpr double epsilon = std::numeric_limits<double>::epsilon(); // 2^-52
constexpr double infinity = std::numeric_limits<double>::infinity();

// Four significant digits: a message is read, not parsed.
std::string short_number(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.4g", value);
    return buffer;
}

std::string quoted(const std::string& name) {
    return "'" + name + "'";
}

std::string at_time(double t) {
    return "t = " + short_number(t) + " s";
}

// The spacing of doubles at x: what one rounding of a coordinate there can be off by, twice.
double ulp_at(double x) {
    const double a = std::abs(x);
    return std::nextafter(a, infinity) - a;
}

} // namespace

// ---------------------------------------------------------------- invariants

StressMonitor::StressMonitor(const Scene& scene, StressChecks checks)
    : scene_(&scene), checks_(std::move(checks)), margins_(checks_.sides.size(), infinity),
      margins_at_(checks_.sides.size()) {}

StressMonitor::Totals StressMonitor::totals_of(const std::vector<BodyState>& states) const {
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
    const std::vector<SceneBody>& bodies = scene_->bodies;
    if (frames_ == 0) {
        start_positions_.clear();
        for (const BodyState& s : states) {
            start_positions_.push_back(s.position);
        }
    }
    ++frames_;
    last_ = states;

    // Finite: every value of every dynamic body; a frame with a NaN or an
    // infinity says nothing about the geometry, so the other checks skip it.
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
                    non_finite_ = quoted(bodies[i].name) + "." + quantity + " is " +
                                  (std::isnan(value) ? "NaN"
                                   : value > 0       ? "+inf"
                                                     : "-inf") +
                                  " at " + at_time(t);
                }
            }
        }
    }
    if (!finite) {
        return;
    }

    // Interpenetration: the signed separation of every pair that can collide.
    for (std::size_t i = 0; i < states.size(); ++i) {
        for (std::size_t k = i + 1; k < states.size(); ++k) {
            if (bodies[i].is_static && bodies[k].is_static) {
                continue;
            }
            const double depth = -separation(bodies[i].shape, transform_of(states[i]),
                                             bodies[k].shape, transform_of(states[k]));
            if (depth > deepest_) {
                deepest_ = depth;
                deepest_at_ =
                    quoted(bodies[i].name) + " and " + quoted(bodies[k].name) + " at " + at_time(t);
            }
        }
    }

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

    const Totals now = totals_of(states);
    if (frames_ == 1) {
        start_ = now;
    }
    momentum_drift_ = std::max(momentum_drift_, length(now.momentum - start_.momentum));
    angular_momentum_drift_ =
        std::max(angular_momentum_drift_, std::abs(now.angular_momentum - start_.angular_momentum));
    momentum_scale_ = std::max(momentum_scale_, now.momentum_scale);
    angular_momentum_scale_ = std::max(angular_momentum_scale_, now.angular_momentum_scale);
    energy_scale_ = std::max(energy_scale_, now.energy_scale);
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

void StressMonitor::observe(const TrajectoryEvent& event) {
    events_.push_back(event);
}

namespace {

StressRow judged(std::string invariant, double worst, double bound, Bound kind,
                 std::string detail) {
    StressRow row{std::move(invariant), worst, bound, kind, false, std::move(detail)};
    switch (kind) {
    case Bound::at_most:
        row.passed = worst <= bound;
        break;
    case Bound::above:
        row.passed = worst > bound;
        break;
    case Bound::finite:
        row.passed = std::isfinite(worst);
        break;
    }
    return row;
}

// A drift relative to the size of the terms it is made of (0 when nothing moved).
double relative(double drift, double scale) {
    return scale > 0.0 ? drift / scale : drift;
}

} // namespace

std::vector<StressRow> StressMonitor::rows() const {
    const Scene& scene = *scene_;
    const SolverSettings& solver = scene.solver;
    const long long steps = std::max(frames_ - 1, 0LL);
    const auto collisions = static_cast<double>(events_.size());
    std::vector<StressRow> rows;

    rows.push_back(
        judged("finite", non_finite_.empty() ? largest_ : std::nan(""), infinity, Bound::finite,
               non_finite_.empty() ? "largest magnitude of any state value" : non_finite_));
    rows.push_back(judged("interpenetration (m)", deepest_, solver.contact_tolerance,
                          Bound::at_most,
                          deepest_at_.empty() ? "no pair ever overlapped" : deepest_at_));
    for (std::size_t r = 0; r < checks_.sides.size(); ++r) {
        const SideRule& rule = checks_.sides[r];
        rows.push_back(
            judged("side: " + quoted(scene.bodies[static_cast<std::size_t>(rule.a)].name) + " of " +
                       quoted(scene.bodies[static_cast<std::size_t>(rule.b)].name) + " (m)",
                   margins_[r], 0.0, Bound::above,
                   "closest approach of the centres along the axis, at " + margins_at_[r]));
    }

    // Rounding of the positions 1e4 m out: each step's update rounds every
    // coordinate to half an ULP there, and each collision's search compares
    // positions rounded so (twice). Whatever is made of positions can be off
    // by this much on top of what it is off by at the origin.
    const double offset_ulp = ulp_at(checks_.offset);
    const double position_budget =
        checks_.offset > 0.0
            ? (0.5 * static_cast<double>(steps) + 2.0 * collisions + 2.0) * offset_ulp
            : 0.0;
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

    if (checks_.drop) {
        const SceneBody& body = scene.bodies[static_cast<std::size_t>(checks_.drop->body)];
        const int n = checks_.drop->impacts;
        std::vector<const TrajectoryEvent*> impacts;
        for (const TrajectoryEvent& e : events_) {
            if (involves(e, body.name)) {
                impacts.push_back(&e);
            }
        }
        const std::optional<DropLadder> ladder = drop_ladder(scene, body);
        const std::string title = "drop ladder of " + quoted(body.name);
        if (!ladder || static_cast<int>(impacts.size()) != n) {
            const std::string why = !ladder ? "no static ground below"
                                            : std::to_string(impacts.size()) +
                                                  " impacts, expected " + std::to_string(n);
            rows.push_back(
                judged(title + ": impact times (s)", infinity, 0.0, Bound::at_most, why));
            rows.push_back(
                judged(title + ": rebound speeds (m/s)", infinity, 0.0, Bound::at_most, why));
        } else {
            // Each impact is resolved at the search's lo, up to toi_tolerance
            // (T) before the touch: from up to v T above the ground and g T
            // slower. To first order that moves the next impact by
            // T (1/e - 1 - 2e) and leaves the next landing speed g T (1/e - e)
            // off, which later flights carry on (2 e / g of a speed error in
            // time, e of it per bounce in speed). Summed over n impacts, e <= 1:
            //   time  <= T (1 + (n - 1)(1/e + 1 + 4e) + e n (n - 1)(1/e + e))
            //   speed <= g T ((n - 1)(1 + e^2) + e)
            // Away from the origin a position off by the budget dy at an
            // impact of speed v acts as an impact dy / v early or late, so T
            // becomes T + dy / v at the slowest impact. Plus 8 epsilons of the
            // values for their own rounding.
            const double e = ladder->e;
            const double g = ladder->g;
            const double slowest = ladder->v1() * ladder->e_to(n - 1);
            const double shift = solver.toi_tolerance + position_budget / slowest;
            const double later =
                n > 1 ? (n - 1) * (1.0 / e + 1.0 + 4.0 * e) + e * n * (n - 1) * (1.0 / e + e) : 0.0;
            const double time_bound =
                shift * (1.0 + later) + 8.0 * epsilon * ladder->impact_time(n);
            const double speed_bound =
                g * shift * ((n - 1) * (1.0 + e * e) + e) + 8.0 * epsilon * ladder->v1();
            double time_error = 0.0, speed_error = 0.0;
            int time_at = 1, speed_at = 1;
            for (int k = 1; k <= n; ++k) {
                const TrajectoryEvent& event = *impacts[static_cast<std::size_t>(k - 1)];
                const double dt = std::abs(event.t - ladder->impact_time(k));
                const double dv = std::abs(event.vn_after - ladder->rebound_speed(k));
                if (dt > time_error) {
                    time_error = dt;
                    time_at = k;
                }
                if (dv > speed_error) {
                    speed_error = dv;
                    speed_at = k;
                }
            }
            rows.push_back(judged(
                title + ": impact times (s)", time_error, time_bound, Bound::at_most,
                "largest at impact " + std::to_string(time_at) + " of " + std::to_string(n)));
            rows.push_back(judged(
                title + ": rebound speeds (m/s)", speed_error, speed_bound, Bound::at_most,
                "largest at impact " + std::to_string(speed_at) + " of " + std::to_string(n)));
        }
    }

    if (checks_.head_on) {
        const SceneBody& a = scene.bodies[static_cast<std::size_t>(checks_.head_on->a)];
        const SceneBody& b = scene.bodies[static_cast<std::size_t>(checks_.head_on->b)];
        const HeadOn exact = head_on(scene, a, b);
        const std::string title = "head-on velocities (relative)";
        if (events_.empty() || last_.empty()) {
            rows.push_back(judged(title, infinity, 0.0, Bound::at_most, "they never collided"));
        } else {
            // The engine's j and v + j n / m round a few times each: a few
            // epsilons of the terms, far inside the slack.
            const double va =
                dot(last_[static_cast<std::size_t>(checks_.head_on->a)].velocity, exact.u);
            const double vb =
                dot(last_[static_cast<std::size_t>(checks_.head_on->b)].velocity, exact.u);
            const double error =
                std::max(relative(std::abs(va - exact.va_after.value), exact.va_after.scale),
                         relative(std::abs(vb - exact.vb_after.value), exact.vb_after.scale));
            rows.push_back(judged(title, error, stress_relative_slack, Bound::at_most,
                                  "final velocities along the line of centres, PHYSICS.md"));
        }
    }
    return rows;
}

// ---------------------------------------------------------------- running a case

bool StressResult::passed() const {
    if (expected_refusal) {
        return refused_as_expected;
    }
    return refusal.empty() && stopped.empty() &&
           std::all_of(rows.begin(), rows.end(), [](const StressRow& r) { return r.passed; });
}

namespace {

// An InputError's text without the "FILE: " it starts with: a case is named
// by its row already.
std::string without_file(const std::string& message, const std::string& file) {
    const std::string prefix = file + ": ";
    return message.compare(0, prefix.size(), prefix) == 0 ? message.substr(prefix.size()) : message;
}

} // namespace

StressResult run_stress_case(const StressCase& stress_case) {
    const auto started = std::chrono::steady_clock::now();
    const Scene& scene = stress_case.scene;
    StressResult result;
    result.name = stress_case.name;
    result.description = stress_case.description;
    result.expected_refusal = !stress_case.expected_refusal.empty();
    const auto finish = [&] {
        result.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        return result;
    };

    const auto refuse = [&](const std::string& refusal) {
        result.refusal = refusal;
        result.refused_as_expected =
            result.expected_refusal &&
            result.refusal.find(stress_case.expected_refusal) != std::string::npos;
        return finish();
    };
    if (const std::optional<TunnellingRefusal> r = tunnelling_refusal(scene)) {
        return refuse(r->path + ": " + r->message);
    }
    std::unique_ptr<Simulator> simulator;
    try {
        simulator = make_impulse_simulator(scene);
    } catch (const InputError& error) {
        return refuse(without_file(error.what(), scene.file));
    }

    StressMonitor monitor(scene, stress_case.checks);
    std::vector<BodyState> states(scene.bodies.size());
    const auto read_states = [&] {
        for (std::size_t i = 0; i < states.size(); ++i) {
            states[i] = simulator->state(static_cast<int>(i));
        }
    };
    read_states();
    monitor.observe(0.0, states);
    const long long steps = step_count(scene);
    try {
        for (long long k = 0; k < steps; ++k) {
            simulator->step(static_cast<double>(k) * scene.dt, scene.dt);
            for (const TrajectoryEvent& event : simulator->take_events()) {
                monitor.observe(event);
                ++result.collisions;
            }
            read_states();
            monitor.observe(static_cast<double>(k + 1) * scene.dt, states);
            note_simulated_time(static_cast<double>(k + 1) * scene.dt, scene.duration);
            ++result.steps;
        }
    } catch (const InputError& error) {
        result.stopped = without_file(error.what(), scene.file);
    }
    result.rows = monitor.rows();
    return finish();
}

// ---------------------------------------------------------------- the cases

namespace {

using Json = nlohmann::json;

Json pair_of(Vec2 v) {
    return Json::array({v.x, v.y});
}

Json disc(const std::string& name, double radius, double mass, Vec2 position, Vec2 velocity = {}) {
    return {{"name", name},
            {"shape", {{"circle", radius}}},
            {"mass", mass},
            {"position", pair_of(position)},
            {"velocity", pair_of(velocity)}};
}

Json box(const std::string& name, Vec2 half, double mass, Vec2 position, double angle,
         Vec2 velocity = {}) {
    return {{"name", name},   {"shape", {{"box", pair_of(half)}}},
            {"mass", mass},   {"position", pair_of(position)},
            {"angle", angle}, {"velocity", pair_of(velocity)}};
}

Json wall(const std::string& name, Vec2 half, Vec2 position) {
    return {{"name", name},
            {"static", true},
            {"shape", {{"box", pair_of(half)}}},
            {"position", pair_of(position)}};
}

struct Setting {
    double e = 1.0;
    Vec2 gravity{0.0, -9.81};
    double dt = 1.0 / 60.0;
    double duration = 1.0;
    bool ccd = false;
    bool resting = false;
    std::string contacts = "single";
    std::string vertex_normal = "reference-face";
};

// Through the scene format and its loader, so every case is a valid scene
// (no overlap at t = 0, every default filled in) like any file.
Scene scene_of(const std::string& name, const std::string& description, const Setting& s,
               Json bodies) {
    Json solver = {{"integrator", "verlet"}, {"toi", "secant"}};
    solver["ccd"] = s.ccd;
    solver["resting"] = s.resting;
    solver["contacts"] = s.contacts;
    solver["vertex_normal"] = s.vertex_normal;
    const Json document = {
        {"schema", scene_schema},        {"name", name},       {"description", description},
        {"gravity", pair_of(s.gravity)}, {"restitution", s.e}, {"dt", s.dt},
        {"duration", s.duration},        {"solver", solver},   {"bodies", std::move(bodies)}};
    return parse_scene(document.dump(), "stress/" + name);
}

StressCase make_case(const std::string& name, const std::string& description, const Setting& s,
                     Json bodies, StressChecks checks, std::string expected_refusal = "") {
    return {name, description, scene_of(name, description, s, std::move(bodies)), std::move(checks),
            std::move(expected_refusal)};
}

// Halfway between impacts n and n + 1 of a drop from h0: a run that long sees exactly n.
double drop_duration(double h0, double e, int n) {
    const DropLadder ladder{h0, 9.81, e};
    return ladder.impact_time(n) + 0.5 * (ladder.impact_time(n + 1) - ladder.impact_time(n));
}

// A disc of radius r dropped from 1 m above static ground (its top at y = 0),
// everything shifted by `offset`: the drop PHYSICS.md's ladder answers.
StressCase drop_case(const std::string& name, const std::string& description, double r, double e,
                     double dt, Vec2 offset, int impacts, double duration = 0.0) {
    Setting s;
    s.e = e;
    s.dt = dt;
    s.resting = e == 0.0; // e = 0 ends in contact, which the seed's model refuses
    s.duration = duration > 0.0 ? duration : drop_duration(1.0, e, impacts);
    StressChecks checks;
    checks.sides = {{1, 0, {0.0, 1.0}}};
    checks.energy_drift = e == 1.0;
    checks.drop = DropCheck{1, impacts};
    checks.offset = std::max(std::abs(offset.x), std::abs(offset.y));
    return make_case(
        name, description, s,
        Json::array({wall("ground", {std::max(5.0, 2.0 * r), 0.5}, offset + Vec2{0.0, -0.5}),
                     disc("ball", r, 1.0, offset + Vec2{0.0, r + 1.0})}),
        checks);
}

// Two discs of radius 0.5 closing head-on at 2 m/s in free space, masses
// `ratio` kg and 1 kg.
StressCase mass_case(double ratio, const std::string& ratio_text, double e) {
    Setting s;
    s.e = e;
    s.gravity = {0.0, 0.0};
    s.duration = 3.0;
    s.resting = e == 0.0; // they leave touching at the same speed: contact, not a collision
    StressChecks checks;
    checks.sides = {{1, 0, {1.0, 0.0}}};
    checks.momentum = true;
    checks.energy_drift = e == 1.0;
    checks.head_on = HeadOnCheck{0, 1};
    const std::string e_text = e == 0.0 ? "0" : "1";
    return make_case("mass-" + ratio_text + "-e" + e_text,
                     "mass ratio " + ratio_text + ": a " + ratio_text +
                         " kg disc meets a 1 kg disc head-on at 2 m/s, no gravity, e = " + e_text,
                     s,
                     Json::array({disc("heavy", 0.5, ratio, {-2.0, 0.0}, {1.0, 0.0}),
                                  disc("light", 0.5, 1.0, {2.0, 0.0}, {-1.0, 0.0})}),
                     checks);
}

// A 0.05 m disc of 10 g at speed v against a static wall 0.02 m thick, no
// gravity, e = 1; it hits at t = 0.4 s and the run ends at 1 s.
StressCase speed_case(const std::string& name, double v, double dt, bool ccd,
                      std::string expected_refusal = "") {
    Setting s;
    s.gravity = {0.0, 0.0};
    s.dt = dt;
    s.ccd = ccd;
    s.duration = 1.0;
    StressChecks checks;
    checks.sides = {{1, 0, {-1.0, 0.0}}};
    checks.energy_drift = true;
    const double start = -(0.06 + 0.4 * v);
    std::string description = "a 0.05 m disc at " + short_number(v) +
                              " m/s into a 0.02 m static wall, dt = " + short_number(dt) + " s" +
                              (ccd ? ", ccd" : "");
    if (!expected_refusal.empty()) {
        description += ": would tunnel without ccd, so it must be refused up front";
    }
    return make_case(name, description, s,
                     Json::array({wall("wall", {0.01, 1.0}, {0.0, 0.0}),
                                  disc("disc", 0.05, 0.01, {start, 0.0}, {v, 0.0})}),
                     checks, std::move(expected_refusal));
}

// A 2 x 0.5 m box tilted by 1e-9 rad dropped 1 m onto the ground, e = 0.5:
// its bottom face meets the ground's top face all but parallel, the corners
// 2e-9 m apart in height (twice the contact tolerance), so it lands on three
// collisions within 1e-9 s and rocks from corner to corner. The run ends at
// 0.9 s, after the second landing's rocking and before its bounces die out,
// where the seed's model stops as resting contact (as drop-flat ends early).
StressCase tilt_case(const std::string& name, const std::string& contacts) {
    Setting s;
    s.e = 0.5;
    s.contacts = contacts;
    s.duration = 0.9;
    StressChecks checks;
    checks.sides = {{1, 0, {0.0, 1.0}}};
    return make_case(name,
                     "near-parallel edges: a 2 x 0.5 m box at 1e-9 rad dropped 1 m lands and "
                     "rocks on the ground for 0.9 s, e = 0.5, contacts " +
                         contacts,
                     s,
                     Json::array({wall("ground", {5.0, 0.5}, {0.0, -0.5}),
                                  box("box", {1.0, 0.25}, 1.0, {0.0, 1.25 + 1e-9}, 1e-9)}),
                     checks);
}

// Two unit squares at 45 degrees meet corner to corner on the x axis, no
// gravity, e = 1.
StressCase corner_case(const std::string& vertex_normal) {
    Setting s;
    s.gravity = {0.0, 0.0};
    s.vertex_normal = vertex_normal;
    s.duration = 1.5;
    StressChecks checks;
    checks.sides = {{1, 0, {1.0, 0.0}}};
    checks.momentum = true;
    checks.angular_momentum = true;
    checks.energy_drift = true;
    const double quarter = 0.7853981633974483;
    return make_case("corner-" + vertex_normal,
                     "vertex/vertex: two unit squares at 45 degrees meet corner to corner at 2 "
                     "m/s, no gravity, e = 1, vertex_normal " +
                         vertex_normal,
                     s,
                     Json::array({box("left", {0.5, 0.5}, 1.0, {-1.5, 0.0}, quarter, {1.0, 0.0}),
                                  box("right", {0.5, 0.5}, 1.0, {1.5, 0.0}, quarter, {-1.0, 0.0})}),
                     checks);
}

// A 0.7 kg disc bouncing around a closed 10 x 6 m room for 1e4 s at dt 1/30
// (300,000 steps), no gravity, e = 1: thousands of collisions, each rounding
// the velocity (0.7 kg is not a power of two).
StressCase room_case() {
    Setting s;
    s.gravity = {0.0, 0.0};
    s.dt = 1.0 / 30.0;
    s.duration = 1e4;
    StressChecks checks;
    checks.sides = {
        {0, 1, {1.0, 0.0}}, {0, 2, {-1.0, 0.0}}, {0, 3, {0.0, 1.0}}, {0, 4, {0.0, -1.0}}};
    checks.energy_drift = true;
    return make_case(
        "long-room",
        "1e4 s: a 0.25 m disc of 0.7 kg bounces around a closed 10 x 6 m room at "
        "3.2 m/s for 1e4 s, dt = 1/30 s (300,000 steps), no gravity, e = 1",
        s,
        Json::array({disc("ball", 0.25, 0.7, {0.0, 0.0}, {2.9, 1.3}),
                     wall("left", {0.5, 3.5}, {-5.5, 0.0}), wall("right", {0.5, 3.5}, {5.5, 0.0}),
                     wall("floor", {6.0, 0.5}, {0.0, -3.5}),
                     wall("ceiling", {6.0, 0.5}, {0.0, 3.5})}),
        checks);
}

// The same room with a spinning 0.6 x 0.4 m box instead: every collision is
// a corner's, through Eq. 9 with its rotational terms, and rounds more.
StressCase box_room_case() {
    Setting s;
    s.gravity = {0.0, 0.0};
    s.dt = 1.0 / 30.0;
    s.duration = 1e4;
    StressChecks checks;
    checks.sides = {
        {0, 1, {1.0, 0.0}}, {0, 2, {-1.0, 0.0}}, {0, 3, {0.0, 1.0}}, {0, 4, {0.0, -1.0}}};
    checks.energy_drift = true;
    Json spinning = box("box", {0.3, 0.2}, 0.7, {0.0, 0.0}, 0.3, {2.9, 1.3});
    spinning["angular_velocity"] = 1.1;
    return make_case(
        "long-room-box",
        "1e4 s: the room of long-room with a spinning 0.6 x 0.4 m box of 0.7 kg "
        "(1.1 rad/s) instead of the disc",
        s,
        Json::array({spinning, wall("left", {0.5, 3.5}, {-5.5, 0.0}),
                     wall("right", {0.5, 3.5}, {5.5, 0.0}), wall("floor", {6.0, 0.5}, {0.0, -3.5}),
                     wall("ceiling", {6.0, 0.5}, {0.0, 3.5})}),
        checks);
}

// A disc dropped 1 m with e = 0.5 and resting on: its cascade ends, and it
// then rests for the rest of 1e4 s at dt 1/30.
StressCase rest_case() {
    Setting s;
    s.e = 0.5;
    s.dt = 1.0 / 30.0;
    s.duration = 1e4;
    s.resting = true;
    StressChecks checks;
    checks.sides = {{1, 0, {0.0, 1.0}}};
    return make_case(
        "long-rest",
        "1e4 s: a disc dropped 1 m, e = 0.5, resting: its bounces end at t_inf and "
        "it rests for 1e4 s at dt = 1/30 s (300,000 steps)",
        s,
        Json::array({wall("ground", {5.0, 0.5}, {0.0, -0.5}), disc("ball", 0.5, 1.0, {0.0, 1.5})}),
        checks);
}

} // namespace

std::vector<StressCase> stress_cases() {
    std::vector<StressCase> cases;
    for (const double e : {1.0, 0.0}) {
        cases.push_back(mass_case(1.0, "1", e));
        cases.push_back(mass_case(1e3, "1e3", e));
        cases.push_back(mass_case(1e6, "1e6", e));
    }
    cases.push_back(speed_case("speed-0.01", 0.01, 1.0 / 60.0, false));
    cases.push_back(speed_case("speed-1", 1.0, 1.0 / 60.0, false));
    cases.push_back(speed_case("speed-100", 100.0, 1e-3, false));
    cases.push_back(speed_case("speed-1000-ccd", 1000.0, 1.0 / 30.0, true));
    cases.push_back(speed_case("speed-1000", 1000.0, 1.0 / 30.0, false, "tunnelling"));
    const Vec2 origin{};
    cases.push_back(drop_case("size-0.05", "size: a 0.05 m disc dropped 1 m, e = 0.8, dt = 1/60 s",
                              0.05, 0.8, 1.0 / 60.0, origin, 4));
    cases.push_back(drop_case("size-1", "size: a 1 m disc dropped 1 m, e = 0.8, dt = 1/60 s", 1.0,
                              0.8, 1.0 / 60.0, origin, 4));
    cases.push_back(drop_case("size-50", "size: a 50 m disc dropped 1 m, e = 0.8, dt = 1/60 s",
                              50.0, 0.8, 1.0 / 60.0, origin, 4));
    cases.push_back(drop_case("offset-1e4",
                              "position: size-1 with everything 1e4 m from the origin in x and y",
                              1.0, 0.8, 1.0 / 60.0, {1e4, 1e4}, 4));
    cases.push_back(drop_case("dt-1e-4", "dt: size-1 at dt = 1e-4 s (24,000 steps)", 1.0, 0.8, 1e-4,
                              origin, 4));
    cases.push_back(
        drop_case("dt-1_30", "dt: size-1 at dt = 1/30 s", 1.0, 0.8, 1.0 / 30.0, origin, 4));
    cases.push_back(drop_case("e-0",
                              "e = 0: a 1 m disc dropped 1 m stops dead and rests (resting: true)",
                              1.0, 0.0, 1.0 / 60.0, origin, 1, 3.0));
    cases.push_back(drop_case("e-1", "e = 1: a 1 m disc dropped 1 m bounces back to 1 m every time",
                              1.0, 1.0, 1.0 / 60.0, origin, 4));
    cases.push_back(room_case());
    cases.push_back(box_room_case());
    cases.push_back(rest_case());
    cases.push_back(tilt_case("tilt-single", "single"));
    cases.push_back(tilt_case("tilt-simultaneous", "simultaneous"));
    cases.push_back(corner_case("reference-face"));
    cases.push_back(corner_case("bisector"));
    return cases;
}

} // namespace impulse::harness
