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

// ---------------------------------------------------------------- the runs

// One run with the name its notes call it by.
struct Run {
    const Trajectory& trajectory;
    std::string name; // "impulse", "Box2D"
};
using Runs = std::vector<Run>;

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
// hence event_time_slack). The frame at t = 0 comes before every step, so it
// never shows an impact done.
const std::vector<double>* frame_after(const Trajectory& trajectory,
                                       const std::vector<double>& impacts, std::size_t n,
                                       double not_before = 0.0) {
    const std::vector<std::vector<double>>& frames = trajectory.frames;
    if (frames.size() < 2) {
        return nullptr;
    }
    const double slack = event_time_slack(trajectory);
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

ObservableReadings row(const Box2dObservable& observable, std::string name,
                       std::optional<double> exact, const std::vector<Reading>& readings) {
    ObservableReadings r;
    r.path = observable.path;
    r.name = std::move(name);
    r.exact = exact;
    r.atol = observable.atol;
    r.rtol = observable.rtol;
    for (const Reading& reading : readings) {
        r.values.push_back(reading.value);
        if (!reading.missing.empty()) {
            r.note += (r.note.empty() ? "" : " ") + reading.missing;
        }
    }
    return r;
}

// "The Box2D run has 2 impacts of 'box', fewer than 3."
std::string too_few_impacts(const Run& run, std::size_t seen, int wanted, const std::string& body) {
    return "The " + run.name + " run has " + plural(seen, "impact", "impacts") + " of " +
           single_quoted(body) + ", fewer than " + std::to_string(wanted) + ".";
}

std::string no_frame_between(const Run& run, std::size_t n, const std::string& body) {
    return "The " + run.name + " run has no frame between impact " + std::to_string(n) + " of " +
           single_quoted(body) + " and the next.";
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
void impact_times(const Scene& scene, const Box2dObservable& o, const Runs& runs,
                  std::vector<ObservableReadings>& out) {
    const SceneBody& body = body_named(scene, o.body);
    std::optional<DropLadder> drop;
    if (drop_applies(scene, body)) {
        drop = drop_ladder(scene, body);
    }
    std::optional<double> corner_time;
    if (!drop && !corner_impact_refusal(scene, body, "")) {
        corner_time = corner_impact(scene, body, *gap_to_static_ground(scene, body)).t_hit;
    }
    std::vector<std::vector<double>> impacts;
    for (const Run& run : runs) {
        impacts.push_back(impacts_of(run.trajectory, o.body));
    }
    for (int n = 1; n <= o.count; ++n) {
        const auto k = static_cast<std::size_t>(n - 1);
        std::vector<Reading> readings(runs.size());
        for (std::size_t r = 0; r < runs.size(); ++r) {
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
                exact, readings));
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
            out.push_back(
                none("The " + run.name + " run has no columns for " + single_quoted(o.body) + "."));
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

void apex_observable(const Scene& scene, const Box2dObservable& o, const Runs& runs,
                     std::vector<ObservableReadings>& out) {
    const SceneBody& body = body_named(scene, o.body);
    // The loader has held the body to the drop's preconditions: static ground below.
    const DropLadder drop = *drop_ladder(scene, body);
    std::vector<std::vector<Reading>> apex;
    for (const Run& run : runs) {
        apex.push_back(apexes(scene, o, run, drop.h0));
    }
    for (int n = 1; n <= o.count; ++n) {
        const auto k = static_cast<std::size_t>(n);
        const std::string number_n = std::to_string(n);
        if (o.kind == Kind::apex_heights) {
            std::vector<Reading> heights;
            for (const std::vector<Reading>& of_run : apex) {
                heights.push_back(of_run[k]);
            }
            out.push_back(row(o, "apex " + number_n + " of " + single_quoted(o.body) + " (m)",
                              drop.apex_gap(n), heights));
            continue;
        }
        std::vector<Reading> ratio(runs.size());
        for (std::size_t r = 0; r < runs.size(); ++r) {
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
                          drop.e * drop.e, ratio));
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

// The times of `frames` for a sentence: "0.5 s and 0.55 s", "0.5 s, 0.55 s and 0.6 s".
std::string times_of(const std::vector<const std::vector<double>*>& frames) {
    std::vector<std::string> times;
    for (const std::vector<double>* f : frames) {
        if (f) {
            times.push_back(sentence_number(frame_time(*f)) + " s");
        }
    }
    std::string text;
    for (std::size_t i = 0; i < times.size(); ++i) {
        text += (i == 0 ? "" : i + 1 == times.size() ? " and " : ", ") + times[i];
    }
    return text;
}

// Each run's first frame after impact k (0-based), or why it has none.
struct AfterImpact {
    const std::vector<double>* frame = nullptr;
    std::vector<double> impacts;
    std::optional<BodyColumns> columns;
    std::string missing;
};

AfterImpact after_impact(const Run& run, const std::string& body, std::size_t k, int impact) {
    AfterImpact a;
    a.impacts = impacts_of(run.trajectory, body);
    a.columns = body_columns(run.trajectory, body);
    if (!a.columns) {
        a.missing = "The " + run.name + " run has no columns for " + single_quoted(body) + ".";
    } else if (k >= a.impacts.size()) {
        a.missing = too_few_impacts(run, a.impacts.size(), impact, body);
    } else if (!(a.frame = frame_after(run.trajectory, a.impacts, k))) {
        a.missing = no_frame_between(run, k + 1, body);
    }
    return a;
}

// Moves every run that has a first frame after impact k to the frame of the
// latest of them, so that gravity has pulled on all for equally long (Box2D
// resolves an impact a step or two after the exact time, so its first frame
// after it is often a step later than the impulse engine's). Empty, or the
// sentence saying each run is read at its own frame when in one run the next
// impact comes before another run's first frame.
std::string common_frames(const Runs& runs, std::vector<AfterImpact>& after, std::size_t k) {
    std::vector<const std::vector<double>*> frames;
    std::optional<double> t;
    for (const AfterImpact& a : after) {
        frames.push_back(a.frame);
        if (a.frame) {
            t = std::max(t.value_or(frame_time(*a.frame)), frame_time(*a.frame));
        }
    }
    if (std::count(frames.begin(), frames.end(), nullptr) + 1 >=
        static_cast<std::ptrdiff_t>(frames.size())) {
        // Fewer than two runs to read at a common time.
        return "";
    }
    std::vector<const std::vector<double>*> common(runs.size(), nullptr);
    for (std::size_t r = 0; r < runs.size(); ++r) {
        if (frames[r] && !(common[r] = frame_after(runs[r].trajectory, after[r].impacts, k, *t))) {
            return "Read at each run's own first frame after the impact (t = " + times_of(frames) +
                   "): in one run the next impact comes before the other run's first frame.";
        }
    }
    for (std::size_t r = 0; r < runs.size(); ++r) {
        after[r].frame = common[r];
    }
    return "";
}

// vx, vy and omega in the first frame after impact n, read at the same frame
// time in every run (common_frames).
void post_impact_velocity(const Scene& scene, const Box2dObservable& o, const Runs& runs,
                          std::vector<ObservableReadings>& out) {
    const SceneBody& body = body_named(scene, o.body);
    const auto k = static_cast<std::size_t>(o.impact - 1);
    std::vector<AfterImpact> after;
    for (const Run& run : runs) {
        after.push_back(after_impact(run, o.body, k, o.impact));
    }
    const std::string shared = common_frames(runs, after, k);
    std::optional<Motion> exact;
    if (after.front().frame) {
        exact = exact_after(scene, body, o.impact, frame_time(*after.front().frame));
    }
    std::vector<Motion> motion(runs.size());
    for (std::size_t r = 0; r < runs.size(); ++r) {
        if (after[r].frame) {
            motion[r] = motion_in(*after[r].frame, *after[r].columns);
        }
    }
    const std::string text =
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
        std::vector<Reading> readings(runs.size());
        for (std::size_t r = 0; r < runs.size(); ++r) {
            readings[r] = after[r].frame ? value(c.of(motion[r])) : none(after[r].missing);
        }
        ObservableReadings built =
            row(o, std::string(c.name) + text + " (" + c.unit + ")",
                exact ? std::optional<double>(c.of(*exact)) : std::nullopt, readings);
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
        return none("The " + run.name + " run has no collision" +
                    (o.body.empty() ? "" : " of " + single_quoted(o.body)) + " to measure.");
    }
    return value(*largest);
}

void restitution_residual(const Scene& scene, const Box2dObservable& o, const Runs& runs,
                          std::vector<ObservableReadings>& out) {
    std::vector<Reading> readings;
    for (const Run& run : runs) {
        readings.push_back(largest_residual(scene, o, run));
    }
    out.push_back(row(o,
                      "largest restitution residual" +
                          (o.body.empty() ? std::string() : " of " + single_quoted(o.body)),
                      0.0, readings));
}

// ---------------------------------------------------------------- conserved quantities

// The largest |Q(t) - Q(0)| over the frames (momentum as a vector norm).
Reading largest_drift(const Scene& scene, Kind kind, const Run& run) {
    std::string missing;
    const std::optional<std::vector<Mass>> masses = masses_of(scene, run.trajectory, missing);
    if (!masses) {
        return none("The " + run.name + " run has no columns for " + single_quoted(missing) + ".");
    }
    if (run.trajectory.frames.empty()) {
        return none("The " + run.name + " run has no frames.");
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

void conserved(const Scene& scene, const Box2dObservable& o, const Runs& runs,
               std::vector<ObservableReadings>& out) {
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
    std::vector<Reading> readings;
    for (const Run& run : runs) {
        readings.push_back(largest_drift(scene, o.kind, run));
    }
    out.push_back(row(o, name, exact, readings));
}

} // namespace

double ObservableReadings::tolerance() const {
    const std::optional<double>& first = values.front();
    return atol + (first ? rtol * std::abs(*first) : 0.0);
}

bool ObservableReadings::within(std::size_t run) const {
    const std::optional<double>& first = values.front();
    const std::optional<double>& other = values.at(run);
    return first && other && std::abs(*other - *first) <= tolerance(); // false for NaN
}

std::vector<ObservableReadings> read_observables(const Scene& scene,
                                                 const std::vector<ObservedRun>& observed) {
    Runs runs;
    for (const ObservedRun& o : observed) {
        runs.push_back({*o.trajectory, o.name});
    }
    std::vector<ObservableReadings> rows;
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

std::vector<ObservableRow> compare_observables(const Scene& scene, const Trajectory& impulse,
                                               const Trajectory& box2d) {
    std::vector<ObservableRow> rows;
    for (const ObservableReadings& r :
         read_observables(scene, {{&impulse, "impulse"}, {&box2d, "Box2D"}})) {
        ObservableRow row;
        row.path = r.path;
        row.name = r.name;
        row.exact = r.exact;
        row.impulse = r.values[0];
        row.box2d = r.values[1];
        row.tolerance = r.tolerance();
        row.within = r.within(1);
        row.note = r.note;
        rows.push_back(std::move(row));
    }
    return rows;
}

} // namespace impulse::harness
