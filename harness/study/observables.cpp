// The observables `impulse box2d` compares (docs/physics.md, "Box2D, the second
// reference"): quantities that survive Box2D's differences from the exact
// model (its skin, iteration counts, position correction, single precision,
// impacts resolved at the ends of steps), read the same way from any
// simulator's trajectory of a scene. Where docs/physics.md's formulas give an exact
// answer for the scene, it is computed from the scene's own parameters
// (exact_answers.h), so each run's error can be told apart from their
// difference.
#include "observables.h"

#include "exact_answers.h"
#include "number_format.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness {

namespace {

using Kind = Box2dObservable::Kind;

// ---------------------------------------------------------------- the two runs

// One run with the name its notes call it by.
struct Run {
    const Trajectory& trajectory;
    const char* name; // "impulse", "Box2D"
};

// The times of a body's impacts: its events, those that share one time
// counted once (Box2D may report two points of one landing as two contacts
// begun in the same step; the impulse engine may resolve two points of one
// landing at the same instant).
std::vector<double> impacts_of(const Trajectory& trajectory, const std::string& body) {
    std::vector<double> impacts;
    for (const std::size_t i : events_of(trajectory, body)) {
        const double t = trajectory.events[i].t;
        if (impacts.empty() || impacts.back() != t) {
            impacts.push_back(t);
        }
    }
    return impacts;
}

// The first frame that shows impact `n` (0-based) done, at or after `not_before`,
// when impact n + 1 comes after it: only then does the frame show the state
// impact n left (plus free flight since). Empty otherwise. An event at time t
// is resolved by the frame at t (the impulse engine resolves it inside the
// step; Box2D stamps it with the end of the step that solved it, t0 + dt,
// which may differ from the frame's (k + 1) dt in the last bit, hence the
// slack of 1e-9 of a step). The frame at t = 0 comes before every step, so it
// never shows an impact done.
const std::vector<double>* frame_after(const Trajectory& trajectory,
                                       const std::vector<double>& impacts, std::size_t n,
                                       double not_before = 0.0) {
    const std::vector<std::vector<double>>& frames = trajectory.frames;
    if (frames.size() < 2) {
        return nullptr;
    }
    const double slack = 1e-9 * (frame_time(frames[1]) - frame_time(frames[0]));
    const double t = std::max(impacts[n], not_before) - slack;
    const auto frame =
        std::find_if(frames.begin() + 1, frames.end(),
                     [t](const std::vector<double>& f) { return frame_time(f) >= t; });
    if (frame == frames.end()) {
        return nullptr;
    }
    if (n + 1 < impacts.size() && !(impacts[n + 1] > frame_time(*frame) + slack)) {
        return nullptr;
    }
    return &*frame;
}

// ---------------------------------------------------------------- rows

// What one run gave for one row: a value, or why there is none.
struct Reading {
    std::optional<double> value;
    std::string missing; // one sentence when there is no value
};

Reading value(double v) {
    return {v, ""};
}

Reading none(std::string why) {
    return {std::nullopt, std::move(why)};
}

ObservableRow row(const Box2dObservable& observable, std::string name, std::optional<double> exact,
                  const Reading& impulse, const Reading& box2d) {
    ObservableRow r;
    r.path = observable.path;
    r.name = std::move(name);
    r.exact = exact;
    r.impulse = impulse.value;
    r.box2d = box2d.value;
    r.tolerance =
        observable.atol + (impulse.value ? observable.rtol * std::abs(*impulse.value) : 0.0);
    r.within = impulse.value && box2d.value &&
               std::abs(*box2d.value - *impulse.value) <= r.tolerance; // false for NaN
    for (const std::string* why : {&impulse.missing, &box2d.missing}) {
        if (!why->empty()) {
            r.note += (r.note.empty() ? "" : " ") + *why;
        }
    }
    return r;
}

// "The Box2D run has 2 impacts of 'box', fewer than 3."
std::string too_few_impacts(const Run& run, std::size_t seen, int wanted, const std::string& body) {
    return std::string("The ") + run.name + " run has " + plural(seen, "impact", "impacts") +
           " of " + single_quoted(body) + ", fewer than " + std::to_string(wanted) + ".";
}

std::string no_frame_between(const Run& run, std::size_t n, const std::string& body) {
    return std::string("The ") + run.name + " run has no frame between impact " +
           std::to_string(n) + " of " + single_quoted(body) + " and the next.";
}

const SceneBody& body_named(const Scene& scene, const std::string& name) {
    for (const SceneBody& body : scene.bodies) {
        if (body.name == name) {
            return body;
        }
    }
    // The loader has checked every name an observable gives.
    return scene.bodies.front();
}

bool drop_applies(const Scene& scene, const SceneBody& body) {
    return !drop_refusal(scene, body, "");
}

// ---------------------------------------------------------------- impact times

// Each run's own times. Box2D finds a contact once the bodies overlap at the
// end of a step and resolves it in the next, so its times lag by one to two
// steps. The exact answer is the drop ladder, or the single-corner impact's
// first time.
void impact_times(const Scene& scene, const Box2dObservable& o, const Run (&runs)[2],
                  std::vector<ObservableRow>& out) {
    const SceneBody& body = body_named(scene, o.body);
    std::optional<DropLadder> drop;
    if (drop_applies(scene, body)) {
        drop = drop_ladder(scene, body);
    }
    std::optional<double> corner_time;
    if (!drop && !corner_impact_refusal(scene, body, "")) {
        corner_time = corner_impact(scene, body, *gap_to_static_ground(scene, body)).t_hit;
    }
    const std::vector<double> impacts[2] = {impacts_of(runs[0].trajectory, o.body),
                                            impacts_of(runs[1].trajectory, o.body)};
    for (int n = 1; n <= o.count; ++n) {
        const auto k = static_cast<std::size_t>(n - 1);
        Reading readings[2];
        for (int r = 0; r < 2; ++r) {
            readings[r] = k < impacts[r].size()
                              ? value(impacts[r][k])
                              : none(too_few_impacts(runs[r], impacts[r].size(), n, o.body));
        }
        std::optional<double> exact;
        if (drop) {
            exact = drop->impact_time(n);
        } else if (corner_time && n == 1) {
            exact = corner_time;
        }
        out.push_back(
            row(o, "impact " + std::to_string(n) + " time of " + single_quoted(o.body) + " (s)",
                exact, readings[0], readings[1]));
    }
}

// ---------------------------------------------------------------- apex heights and ratios

// Apex n of a run: from the first frame after impact n, y + vy^2 / (2 g) is
// the height the centre will reach (free flight under gravity alone), less
// its height at contact, y0 - h0. Apex 0 is h0 itself.
std::vector<Reading> apexes(const Scene& scene, const Box2dObservable& o, const Run& run,
                            double h0) {
    const SceneBody& body = body_named(scene, o.body);
    const double g = gravity_magnitude(scene);
    const double contact_height = body.position.y - h0;
    const std::vector<double> impacts = impacts_of(run.trajectory, o.body);
    const std::optional<BodyColumns> columns = body_columns(run.trajectory, o.body);
    std::vector<Reading> out{value(h0)};
    for (int n = 1; n <= o.count; ++n) {
        const auto k = static_cast<std::size_t>(n - 1);
        if (!columns) {
            out.push_back(none(std::string("The ") + run.name + " run has no columns for " +
                               single_quoted(o.body) + "."));
            continue;
        }
        if (k >= impacts.size()) {
            out.push_back(none(too_few_impacts(run, impacts.size(), n, o.body)));
            continue;
        }
        const std::vector<double>* frame = frame_after(run.trajectory, impacts, k);
        if (!frame) {
            out.push_back(none(no_frame_between(run, k + 1, o.body)));
            continue;
        }
        const Motion m = motion_in(*frame, *columns);
        out.push_back(
            value(m.position.y + m.velocity.y * m.velocity.y / (2.0 * g) - contact_height));
    }
    return out;
}

void apex_observable(const Scene& scene, const Box2dObservable& o, const Run (&runs)[2],
                     std::vector<ObservableRow>& out) {
    const SceneBody& body = body_named(scene, o.body);
    // The loader has held the body to the drop's preconditions: static ground below.
    const DropLadder drop = *drop_ladder(scene, body);
    const std::vector<Reading> apex[2] = {apexes(scene, o, runs[0], drop.h0),
                                          apexes(scene, o, runs[1], drop.h0)};
    for (int n = 1; n <= o.count; ++n) {
        const auto k = static_cast<std::size_t>(n);
        const std::string number_n = std::to_string(n);
        if (o.kind == Kind::apex_heights) {
            out.push_back(row(o, "apex " + number_n + " of " + single_quoted(o.body) + " (m)",
                              drop.apex_gap(n), apex[0][k], apex[1][k]));
            continue;
        }
        Reading ratio[2];
        for (int r = 0; r < 2; ++r) {
            const Reading& now = apex[r][k];
            const Reading& before = apex[r][k - 1];
            if (now.value && before.value) {
                ratio[r] = value(*now.value / *before.value);
            } else {
                ratio[r] = none(before.value ? now.missing : before.missing);
            }
        }
        out.push_back(row(o,
                          "apex " + number_n + " / apex " + std::to_string(n - 1) + " of " +
                              single_quoted(o.body),
                          drop.e * drop.e, ratio[0], ratio[1]));
    }
}

// ---------------------------------------------------------------- post-impact velocity

// The exact state after impact n at time t (> the impact), where a formula of
// docs/physics.md gives it: the drop (every impact), the single-corner impact and
// the head-on collision of two free bodies (the first impact).
std::optional<Motion> exact_after(const Scene& scene, const SceneBody& body, int n, double t) {
    const double g = gravity_magnitude(scene);
    if (drop_applies(scene, body)) {
        const DropLadder drop = *drop_ladder(scene, body);
        Motion m;
        m.velocity = {body.velocity.x, drop.rebound_speed(n) - g * (t - drop.impact_time(n))};
        m.omega = body.angular_velocity;
        return m;
    }
    if (n != 1) {
        return std::nullopt;
    }
    if (!corner_impact_refusal(scene, body, "")) {
        const CornerImpact c = corner_impact(scene, body, *gap_to_static_ground(scene, body));
        Motion m;
        m.velocity = {body.velocity.x, c.vy_after - g * (t - c.t_hit)};
        m.omega = c.w_after;
        return m;
    }
    // Head-on: two free bodies and nothing else in the scene to meet first.
    if (scene.bodies.size() == 2 && !scene.bodies[0].is_static && !scene.bodies[1].is_static) {
        const SceneBody& a = scene.bodies[0];
        const SceneBody& b = scene.bodies[1];
        if (!head_on_refusal(scene, a, b, "")) {
            const HeadOn h = head_on(scene, a, b);
            const bool is_a = body.name == a.name;
            Motion m;
            m.velocity = (is_a ? h.va_after.value : h.vb_after.value) * h.u +
                         (is_a ? h.pa : h.pb) * perp(h.u);
            m.omega = body.angular_velocity;
            return m;
        }
    }
    return std::nullopt;
}

// vx, vy and omega in the first frame after impact n, read at the same frame
// time in both runs (the later of their first frames after the impact) so
// that gravity has pulled on both for equally long (Box2D resolves an impact
// a step or two after the exact time, so its first frame after it is often a
// step later than the impulse engine's).
void post_impact_velocity(const Scene& scene, const Box2dObservable& o, const Run (&runs)[2],
                          std::vector<ObservableRow>& out) {
    const SceneBody& body = body_named(scene, o.body);
    const auto k = static_cast<std::size_t>(o.impact - 1);
    const std::vector<double>* frames[2] = {nullptr, nullptr};
    std::vector<double> impacts[2];
    std::optional<BodyColumns> columns[2];
    std::string missing[2];
    for (int r = 0; r < 2; ++r) {
        impacts[r] = impacts_of(runs[r].trajectory, o.body);
        columns[r] = body_columns(runs[r].trajectory, o.body);
        if (!columns[r]) {
            missing[r] = std::string("The ") + runs[r].name + " run has no columns for " +
                         single_quoted(o.body) + ".";
        } else if (k >= impacts[r].size()) {
            missing[r] = too_few_impacts(runs[r], impacts[r].size(), o.impact, o.body);
        } else if (!(frames[r] = frame_after(runs[r].trajectory, impacts[r], k))) {
            missing[r] = no_frame_between(runs[r], k + 1, o.body);
        }
    }
    std::string shared;
    if (frames[0] && frames[1]) {
        // Both runs record frames at k dt.
        const double t = std::max(frame_time(*frames[0]), frame_time(*frames[1]));
        const std::vector<double>* common[2];
        for (int r = 0; r < 2; ++r) {
            common[r] = frame_after(runs[r].trajectory, impacts[r], k, t);
        }
        if (common[0] && common[1]) {
            frames[0] = common[0];
            frames[1] = common[1];
        } else {
            shared = "Read at each run's own first frame after the impact (t = " +
                     sentence_number(frame_time(*frames[0])) + " s and " +
                     sentence_number(frame_time(*frames[1])) +
                     " s): in one run the next impact comes before the other run's first frame.";
        }
    }
    std::optional<Motion> exact;
    if (frames[0]) {
        exact = exact_after(scene, body, o.impact, frame_time(*frames[0]));
    }
    Motion motion[2];
    for (int r = 0; r < 2; ++r) {
        if (frames[r]) {
            motion[r] = motion_in(*frames[r], *columns[r]);
        }
    }
    const std::string after =
        " after impact " + std::to_string(o.impact) + " of " + single_quoted(o.body);
    struct Component {
        const char* name;
        const char* unit;
        double (*of)(const Motion&);
    };
    const Component components[3] = {
        {"vx", "m/s", [](const Motion& m) { return m.velocity.x; }},
        {"vy", "m/s", [](const Motion& m) { return m.velocity.y; }},
        {"omega", "rad/s", [](const Motion& m) { return m.omega; }},
    };
    for (const Component& c : components) {
        Reading readings[2];
        for (int r = 0; r < 2; ++r) {
            readings[r] = frames[r] ? value(c.of(motion[r])) : none(missing[r]);
        }
        ObservableRow built = row(o, std::string(c.name) + after + " (" + c.unit + ")",
                                  exact ? std::optional<double>(c.of(*exact)) : std::nullopt,
                                  readings[0], readings[1]);
        if (!shared.empty()) {
            built.note += (built.note.empty() ? "" : " ") + shared;
        }
        out.push_back(std::move(built));
    }
}

// ---------------------------------------------------------------- restitution residual

// Newton's law of restitution (docs/physics.md, Eq. 3) per event: vn_after =
// -e vn_before, so (vn_after + e vn_before) / |vn_before| is 0 in the exact
// model. The event with the largest magnitude is reported, sign kept.
Reading largest_residual(const Scene& scene, const Box2dObservable& o, const Run& run) {
    std::optional<double> largest;
    for (const TrajectoryEvent& e : run.trajectory.events) {
        if ((!o.body.empty() && !involves(e, o.body)) || e.vn_before == 0.0) {
            continue;
        }
        const double residual =
            (e.vn_after + scene.restitution * e.vn_before) / std::abs(e.vn_before);
        if (!largest || std::abs(residual) > std::abs(*largest) || std::isnan(residual)) {
            largest = residual;
        }
    }
    if (!largest) {
        return none(std::string("The ") + run.name + " run has no collision" +
                    (o.body.empty() ? "" : " of " + single_quoted(o.body)) + " to measure.");
    }
    return value(*largest);
}

void restitution_residual(const Scene& scene, const Box2dObservable& o, const Run (&runs)[2],
                          std::vector<ObservableRow>& out) {
    out.push_back(row(o,
                      "largest restitution residual" +
                          (o.body.empty() ? std::string() : " of " + single_quoted(o.body)),
                      0.0, largest_residual(scene, o, runs[0]),
                      largest_residual(scene, o, runs[1])));
}

// ---------------------------------------------------------------- conserved quantities

// The largest |Q(t) - Q(0)| over the frames (momentum as a vector norm).
Reading largest_drift(const Scene& scene, Kind kind, const Run& run) {
    std::string missing;
    const std::optional<std::vector<Mass>> masses = masses_of(scene, run.trajectory, missing);
    if (!masses) {
        return none(std::string("The ") + run.name + " run has no columns for " +
                    single_quoted(missing) + ".");
    }
    if (run.trajectory.frames.empty()) {
        return none(std::string("The ") + run.name + " run has no frames.");
    }
    const Totals initial = totals_in(run.trajectory.frames.front(), *masses, scene.gravity);
    double largest = 0.0;
    for (const std::vector<double>& frame : run.trajectory.frames) {
        const Totals now = totals_in(frame, *masses, scene.gravity);
        double drift = 0.0;
        switch (kind) {
        case Kind::momentum:
            drift = length(now.momentum - initial.momentum);
            break;
        case Kind::angular_momentum:
            drift = std::abs(now.angular_momentum - initial.angular_momentum);
            break;
        default:
            drift = std::abs(now.energy - initial.energy);
            break;
        }
        // NaN is the worst of all: it is what a blown-up run leaves.
        if (drift > largest || std::isnan(drift)) {
            largest = drift;
            if (std::isnan(drift)) {
                break;
            }
        }
    }
    return value(largest);
}

void conserved(const Scene& scene, const Box2dObservable& o, const Run (&runs)[2],
               std::vector<ObservableRow>& out) {
    const char* quantity = o.kind == Kind::momentum           ? "momentum"
                           : o.kind == Kind::angular_momentum ? "angular_momentum"
                                                              : "energy";
    const char* name = o.kind == Kind::momentum ? "momentum drift |P(t) - P(0)| (kg m/s)"
                       : o.kind == Kind::angular_momentum
                           ? "angular momentum drift |L(t) - L(0)| (kg m^2/s)"
                           : "energy drift |E(t) - E(0)| (J)";
    std::optional<double> exact;
    if (!conservation_refusal(scene, quantity)) {
        exact = 0.0;
    }
    out.push_back(row(o, name, exact, largest_drift(scene, o.kind, runs[0]),
                      largest_drift(scene, o.kind, runs[1])));
}

} // namespace

std::vector<ObservableRow> compare_observables(const Scene& scene, const Trajectory& impulse,
                                               const Trajectory& box2d) {
    const Run runs[2] = {{impulse, "impulse"}, {box2d, "Box2D"}};
    std::vector<ObservableRow> rows;
    for (const Box2dObservable& o : scene.box2d.observables) {
        switch (o.kind) {
        case Kind::impact_times:
            impact_times(scene, o, runs, rows);
            break;
        case Kind::apex_heights:
        case Kind::apex_ratios:
            apex_observable(scene, o, runs, rows);
            break;
        case Kind::post_impact_velocity:
            post_impact_velocity(scene, o, runs, rows);
            break;
        case Kind::restitution_residual:
            restitution_residual(scene, o, runs, rows);
            break;
        case Kind::momentum:
        case Kind::angular_momentum:
        case Kind::energy:
            conserved(scene, o, runs, rows);
            break;
        }
    }
    return rows;
}

} // namespace impulse::harness
