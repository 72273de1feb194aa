// Checking a run against the answers its scene declares (DESIGN.md: "A scene
// may declare expectations that every run checks").
//
// Everything here reads the trajectory only (its NAME.x ... NAME.omega columns
// and its events), never the engine, so the same checks hold any simulator to
// the same physics. The exact answers are computed from the scene's own
// parameters by the formulas of PHYSICS.md, "Exact answers for checking"; the
// loader (scene.cpp) has already refused scenes that break their preconditions.
#include "expectations.h"

#include "exact_answers.h"
#include "number_format.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness {

namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------- text

// ---------------------------------------------------------------- judging one value

// The checks of one expectation, with the prefix every line of it shares.
class Checks {
  public:
    Checks(const Expectation& expectation, std::string subject, std::vector<ExpectationResult>& out)
        : expectation_(expectation), subject_(std::move(subject)), out_(out) {}

    // Passes when |actual - expected| <= atol + rtol * scale.
    void value(const std::string& what, Exact expected, double actual) {
        ExpectationResult r = start(what);
        const double allowed = expectation_.atol + expectation_.rtol * expected.scale;
        const double off = std::abs(actual - expected.value);
        r.passed = off <= allowed; // false for NaN
        r.expected = finite_or_zero(expected.value);
        r.actual = finite_or_zero(actual);
        if (!std::isfinite(expected.value)) {
            r.passed = false;
            r.detail = "the exact formula gives " + sentence_number(expected.value) +
                       " for this scene, so it cannot be checked";
        } else if (!std::isfinite(actual)) {
            r.passed = false;
            r.detail = "the run gave " + sentence_number(actual) + ", which is not finite";
        } else if (!std::isfinite(off) || !std::isfinite(allowed)) {
            // An overflowed difference or tolerance (a scale of inf) would let
            // anything pass: what cannot be computed fails.
            r.passed = false;
            r.detail = "not finite: off by " + sentence_number(off) + ", allowed " +
                       sentence_number(allowed) + " (atol " + sentence_number(expectation_.atol) +
                       " + rtol " + sentence_number(expectation_.rtol) + " x " +
                       sentence_number(expected.scale) + ")";
        } else if (!r.passed) {
            r.detail =
                "off by " + sentence_number(off) + ", more than the " + sentence_number(allowed) +
                " allowed (atol " + sentence_number(expectation_.atol) + " + rtol " +
                sentence_number(expectation_.rtol) + " x " + sentence_number(expected.scale) + ")";
        }
        out_.push_back(std::move(r));
    }

    // A check judged by its caller; `detail` is kept only when it failed.
    // `allowed` is the tolerance the caller judged with. A non-finite
    // expected, actual or allowed value fails whatever the caller found:
    // inf <= inf + inf is true, and must not pass.
    void judged(const std::string& what, bool passed, double expected, double actual,
                const std::string& detail, double allowed = 0.0) {
        ExpectationResult r = start(what);
        const bool finite =
            std::isfinite(expected) && std::isfinite(actual) && std::isfinite(allowed);
        r.passed = passed && finite;
        r.expected = finite_or_zero(expected);
        r.actual = finite_or_zero(actual);
        if (!finite) {
            r.detail = "not finite: expected " + sentence_number(expected) + ", got " +
                       sentence_number(actual) + ", allowed " + sentence_number(allowed) + "; " +
                       detail;
        } else if (!passed) {
            r.detail = detail;
        }
        out_.push_back(std::move(r));
    }

    // A check that failed without a number to compare (a missing event or
    // frame); expected and actual say what was wanted and found when they can.
    void failure(const std::string& what, const std::string& detail, double expected = 0.0,
                 double actual = 0.0) {
        judged(what, false, expected, actual, detail);
    }

    // Names compared as strings: no tolerance applies.
    void name(const std::string& what, const std::string& expected, const std::string& actual) {
        ExpectationResult r = start(what);
        r.passed = expected == actual;
        if (!r.passed) {
            r.detail = "expected " + single_quoted(expected) + ", got " + single_quoted(actual);
        }
        out_.push_back(std::move(r));
    }

    const Expectation& expectation() const { return expectation_; }

  private:
    static double finite_or_zero(double value) { return std::isfinite(value) ? value : 0.0; }

    ExpectationResult start(const std::string& what) const {
        ExpectationResult r;
        r.path = expectation_.path;
        r.what = subject_.empty() ? what : what.empty() ? subject_ : subject_ + ": " + what;
        return r;
    }

    const Expectation& expectation_;
    std::string subject_;
    std::vector<ExpectationResult>& out_;
};

// ---------------------------------------------------------------- reading the trajectory

double field_of(const Motion& m, const std::string& field) {
    if (field == "x") {
        return m.position.x;
    }
    if (field == "y") {
        return m.position.y;
    }
    if (field == "angle") {
        return m.angle;
    }
    if (field == "vx") {
        return m.velocity.x;
    }
    if (field == "vy") {
        return m.velocity.y;
    }
    return field == "omega" ? m.omega : not_a_number;
}

double field_of(const TrajectoryEvent& e, const std::string& field) {
    if (field == "t") {
        return e.t;
    }
    if (field == "impulse") {
        return e.impulse;
    }
    if (field == "vn_before") {
        return e.vn_before;
    }
    if (field == "vn_after") {
        return e.vn_after;
    }
    if (field == "point.x" || field == "point.y") {
        return e.point[field == "point.x" ? 0 : 1];
    }
    if (field == "normal.x" || field == "normal.y") {
        return e.normal[field == "normal.x" ? 0 : 1];
    }
    return not_a_number;
}

// The first frame recorded after event `index`, when no later event touching
// any of `bodies` happens up to it: only then does the frame show the state
// this collision left (plus the free motion since). Empty otherwise.
const std::vector<double>* frame_after_event(const Trajectory& trajectory, std::size_t index,
                                             const std::vector<std::string>& bodies) {
    const double t = trajectory.events[index].t;
    const auto frame =
        std::find_if(trajectory.frames.begin(), trajectory.frames.end(),
                     [t](const std::vector<double>& f) { return frame_time(f) > t; });
    if (frame == trajectory.frames.end()) {
        return nullptr;
    }
    for (std::size_t k = index + 1; k < trajectory.events.size(); ++k) {
        const TrajectoryEvent& later = trajectory.events[k];
        if (later.t > frame_time(*frame)) {
            break;
        }
        for (const std::string& body : bodies) {
            if (involves(later, body)) {
                return nullptr;
            }
        }
    }
    return &*frame;
}

const SceneBody* scene_body(const Scene& scene, const std::string& name) {
    for (const SceneBody& body : scene.bodies) {
        if (body.name == name) {
            return &body;
        }
    }
    return nullptr;
}

// ---------------------------------------------------------------- drop

void check_drop(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const Expectation& x = checks.expectation();
    const SceneBody* body = scene_body(scene, x.body);
    const std::optional<double> h0 = body ? gap_to_static_ground(scene, *body) : std::nullopt;
    if (!h0) {
        checks.failure("", "the scene has no body " + single_quoted(x.body) +
                               " above static ground, so the drop formula has no gap h0");
        return;
    }
    const DropLadder drop{*h0, gravity_magnitude(scene), scene.restitution};
    // A flat landing under simultaneous contacts records one event per
    // corner at the same instant: one impact.
    std::vector<std::size_t> impacts;
    for (const std::size_t i : events_of(trajectory, x.body)) {
        if (impacts.empty() || trajectory.events[i].t != trajectory.events[impacts.back()].t) {
            impacts.push_back(i);
        }
    }
    const int seen = static_cast<int>(std::min<std::size_t>(impacts.size(), 1u << 30));
    for (int n = 1; n <= std::min(x.impacts, seen); ++n) {
        const TrajectoryEvent& ev = trajectory.events[impacts[static_cast<std::size_t>(n - 1)]];
        const std::string impact = "impact " + std::to_string(n) + " ";
        checks.value(impact + "time", plain(drop.impact_time(n)), ev.t);
        checks.value(impact + "rebound speed", plain(drop.rebound_speed(n)), ev.vn_after);
        // The rebound speed's apex: a body leaving at speed v rises v^2 / (2 g).
        checks.value(impact + "apex gap", plain(drop.apex_gap(n)),
                     ev.vn_after * ev.vn_after / (2.0 * drop.g));
    }
    if (seen < x.impacts) {
        checks.failure("impacts",
                       "the run has " + std::to_string(seen) + " collision" +
                           (seen == 1 ? "" : "s") + " of " + single_quoted(x.body) +
                           ", fewer than the " + std::to_string(x.impacts) + " impacts expected",
                       x.impacts, seen);
    }
}

// ---------------------------------------------------------------- corner impact

void check_corner_impact(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const Expectation& x = checks.expectation();
    const SceneBody* body = scene_body(scene, x.body);
    const std::optional<double> h = body ? gap_to_static_ground(scene, *body) : std::nullopt;
    if (!h || body->shape.type != ShapeType::polygon || !(body->inertia > 0.0)) {
        checks.failure("", "the scene has no rotating polygon " + single_quoted(x.body) +
                               " above static ground, so the corner-impact formula does not apply");
        return;
    }
    const CornerImpact c = corner_impact(scene, *body, *h);
    const std::vector<std::size_t> hits = events_of(trajectory, x.body);
    if (hits.empty()) {
        checks.failure("", "the run has no collision of " + single_quoted(x.body) +
                               "; the exact answer has it hit the ground at t = " +
                               sentence_number(c.t_hit) + " s");
        return;
    }
    const TrajectoryEvent& hit = trajectory.events[hits.front()];
    checks.value("time", plain(c.t_hit), hit.t);
    checks.value("impulse", plain(c.j), hit.impulse);
    checks.value("vn_before", plain(-c.v), hit.vn_before);
    checks.value("point.x", {c.point_x, c.point_scale}, hit.point[0]);

    const std::optional<BodyColumns> columns = body_columns(trajectory, x.body);
    const std::vector<double>* frame = frame_after_event(trajectory, hits.front(), {x.body});
    if (!columns || !frame) {
        return; // nothing shows the state this impact alone left
    }
    const Motion after = motion_in(*frame, *columns);
    const double flight = frame_time(*frame) - c.t_hit;
    const double g = gravity_magnitude(scene);
    // rx is a difference of world positions in the engine, so w' inherits
    // their rounding: its scale is the point's.
    checks.value("omega after", {c.w_after, c.point_scale * c.j / body->inertia}, after.omega);
    checks.value("vx after", plain(body->velocity.x), after.velocity.x);
    // After the impact only gravity acts: vy = vy' - g (t - t_hit).
    checks.value("vy after",
                 {c.vy_after - g * flight, c.v + c.j / body->mass + std::abs(g * flight)},
                 after.velocity.y);
}

// ---------------------------------------------------------------- head-on

void check_head_on(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const Expectation& x = checks.expectation();
    const SceneBody* a = scene_body(scene, x.body);
    const SceneBody* b = scene_body(scene, x.other);
    if (!a || !b || a == b || !(a->mass > 0.0) || !(b->mass > 0.0)) {
        checks.failure("", "the scene has no two dynamic bodies " + single_quoted(x.body) +
                               " and " + single_quoted(x.other) +
                               ", so the head-on formula does not apply");
        return;
    }
    const HeadOn h = head_on(scene, *a, *b);
    std::optional<std::size_t> first;
    for (std::size_t i = 0; i < trajectory.events.size() && !first; ++i) {
        const TrajectoryEvent& e = trajectory.events[i];
        if ((e.a == a->name && e.b == b->name) || (e.a == b->name && e.b == a->name)) {
            first = i;
        }
    }
    if (!first) {
        checks.failure("", "the run has no collision between " + single_quoted(a->name) + " and " +
                               single_quoted(b->name));
        return;
    }
    checks.value("impulse", h.j, trajectory.events[*first].impulse);

    const std::optional<BodyColumns> ca = body_columns(trajectory, a->name);
    const std::optional<BodyColumns> cb = body_columns(trajectory, b->name);
    const std::vector<double>* frame = frame_after_event(trajectory, *first, {a->name, b->name});
    if (!ca || !cb || !frame) {
        return; // nothing shows the state this collision alone left
    }
    const Vec2 va = motion_in(*frame, *ca).velocity;
    const Vec2 vb = motion_in(*frame, *cb).velocity;
    const Vec2 across = perp(h.u);
    // A velocity read along u carries the rounding of its component across u,
    // and the other way round; the impulse's j / M is what rounding of the
    // normal leaks across.
    checks.value(single_quoted(a->name) + " velocity along the line of centres",
                 {h.va_after.value, h.va_after.scale + std::abs(h.pa)}, dot(va, h.u));
    checks.value(single_quoted(b->name) + " velocity along the line of centres",
                 {h.vb_after.value, h.vb_after.scale + std::abs(h.pb)}, dot(vb, h.u));
    checks.value(single_quoted(a->name) + " velocity across the line of centres",
                 {h.pa, std::abs(h.pa) + h.va_after.scale + h.j.value / a->mass}, dot(va, across));
    checks.value(single_quoted(b->name) + " velocity across the line of centres",
                 {h.pb, std::abs(h.pb) + h.vb_after.scale + h.j.value / b->mass}, dot(vb, across));
}

// ---------------------------------------------------------------- totals

// Every dynamic body with its columns; empty (after a failure) when the
// trajectory lacks a body's columns. The same as exact_answers.h's masses_of,
// with the columns found through an index: a gas of 10,000 bodies has 60,001
// columns, and searching them once per body takes over a second.
std::optional<std::vector<Mass>> masses_of(const Scene& scene, const Trajectory& trajectory,
                                           Checks& checks) {
    std::map<std::string, std::size_t> index;
    for (std::size_t c = 0; c < trajectory.columns.size(); ++c) {
        index.emplace(trajectory.columns[c], c); // the first of a repeated name, as std::find
    }
    std::vector<Mass> masses;
    for (const SceneBody& body : scene.bodies) {
        if (body.is_static) {
            continue;
        }
        std::size_t found[6] = {};
        const char* suffixes[6] = {".x", ".y", ".angle", ".vx", ".vy", ".omega"};
        for (std::size_t i = 0; i < 6; ++i) {
            const auto it = index.find(body.name + suffixes[i]);
            if (it == index.end()) {
                checks.failure("", "the trajectory has no columns for " + single_quoted(body.name));
                return std::nullopt;
            }
            found[i] = it->second;
        }
        const BodyColumns columns{found[0], found[1], found[2], found[3], found[4], found[5]};
        masses.push_back({&body, columns, body.rotation ? body.inertia : 0.0});
    }
    if (trajectory.frames.empty()) {
        checks.failure("", "the trajectory has no frames");
        return std::nullopt;
    }
    return masses;
}

// A conserved quantity as scalar components (momentum has two) and the scale
// of its terms.
std::vector<double> components_of(const Totals& t, const std::string& quantity) {
    if (quantity == "momentum") {
        return {t.momentum.x, t.momentum.y};
    }
    return {quantity == "angular_momentum" ? t.angular_momentum : t.energy};
}

double scale_of(const Totals& t, const std::string& quantity) {
    if (quantity == "momentum") {
        return t.momentum_scale;
    }
    return quantity == "angular_momentum" ? t.angular_momentum_scale : t.energy_scale;
}

// PHYSICS.md: frictionless contact in free space conserves momentum and
// angular momentum; with e = 1, energy. Every frame is compared with frame 0
// and the frame where the quantity strays furthest is reported.
void check_conserved(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const std::optional<std::vector<Mass>> masses = masses_of(scene, trajectory, checks);
    if (!masses) {
        return;
    }
    std::vector<Totals> totals;
    totals.reserve(trajectory.frames.size());
    for (const std::vector<double>& frame : trajectory.frames) {
        totals.push_back(totals_in(frame, *masses, scene.gravity));
    }
    for (const std::string& quantity : checks.expectation().quantities) {
        const std::vector<double> initial = components_of(totals.front(), quantity);
        std::size_t worst_frame = 0;
        std::size_t worst_component = 0;
        double largest = 0.0;
        for (std::size_t k = 0; k < totals.size(); ++k) {
            const std::vector<double> now = components_of(totals[k], quantity);
            for (std::size_t c = 0; c < now.size(); ++c) {
                const double off = std::abs(now[c] - initial[c]);
                // NaN is the worst of all: it is what a blown-up run leaves.
                if (off > largest || (std::isnan(off) && !std::isnan(largest))) {
                    largest = off;
                    worst_frame = k;
                    worst_component = c;
                }
            }
        }
        std::string name = quantity == "angular_momentum" ? "angular momentum" : quantity;
        if (initial.size() == 2) {
            name += worst_component == 0 ? " (x)" : " (y)";
        }
        const double t = frame_time(trajectory.frames[worst_frame]);
        checks.value("conserved " + name + ", furthest from t = 0 at t = " + sentence_number(t) +
                         " s",
                     {initial[worst_component], scale_of(totals.front(), quantity)},
                     components_of(totals[worst_frame], quantity)[worst_component]);
    }
}

// An impulse a static body gave a dynamic one.
struct Kick {
    double t = 0.0;
    Vec2 impulse; // on the dynamic body
    double size = 0.0;
};

// The impulses from static bodies, in time order. In an event the impulse on
// a is j n (the normal points toward a) and on b is -j n; the dynamic body is
// a in the impulse engine's events, but either is read right. Events between
// two dynamic bodies give equal and opposite impulses and leave the total
// alone. Empty (after a failure) when an event names a body the scene lacks.
std::optional<std::vector<Kick>>
kicks_from_static_bodies(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    std::map<std::string, bool> is_static;
    for (const SceneBody& body : scene.bodies) {
        is_static.emplace(body.name, body.is_static);
    }
    std::vector<Kick> kicks;
    for (std::size_t k = 0; k < trajectory.events.size(); ++k) {
        const TrajectoryEvent& e = trajectory.events[k];
        const auto a = is_static.find(e.a);
        const auto b = is_static.find(e.b);
        if (a == is_static.end() || b == is_static.end()) {
            checks.failure("", "event " + std::to_string(k) + " names " +
                                   single_quoted(a == is_static.end() ? e.a : e.b) +
                                   ", which is not a body of the scene");
            return std::nullopt;
        }
        if (a->second == b->second) {
            continue;
        }
        const Vec2 on_a{e.impulse * e.normal[0], e.impulse * e.normal[1]};
        kicks.push_back({e.t, a->second ? -on_a : on_a, std::abs(e.impulse)});
    }
    // Events come in time order from a world-stepping run; a run whose bodies
    // keep their own clocks may record them otherwise. Stable: ties keep the
    // recorded order, so the sum is the same however the run is repeated.
    std::stable_sort(kicks.begin(), kicks.end(),
                     [](const Kick& x, const Kick& y) { return x.t < y.t; });
    return kicks;
}

// How far a value is off relative to what it is allowed: the scale of the
// momentum balance grows with every impulse, so the frame nearest to failing
// is not always the one furthest off. NaN (a blown-up run) is the worst.
double share_of_allowance(double off, double allowed) {
    if (std::isnan(off)) {
        return std::numeric_limits<double>::infinity();
    }
    if (allowed > 0.0) {
        return off / allowed;
    }
    return off > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

// A gas in a closed room: total momentum changes only by the walls' impulses.
// In every frame, P(t) - P(0) = sum of j n over the events with a static body
// up to t (event.t <= t), judged against the sum of |m v| at t = 0 plus the
// sum of those |j|; the frame and component nearest to failing (by share of
// its allowance) is reported. The loader has refused gravity (it would add
// m g t).
void check_momentum_balance(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const std::optional<std::vector<Mass>> masses = masses_of(scene, trajectory, checks);
    if (!masses) {
        return;
    }
    const std::optional<std::vector<Kick>> kicks =
        kicks_from_static_bodies(scene, trajectory, checks);
    if (!kicks) {
        return;
    }
    const Expectation& x = checks.expectation();
    const Totals initial = totals_in(trajectory.frames.front(), *masses, scene.gravity);
    Vec2 given;              // sum of j n up to the frame
    double given_size = 0.0; // sum of |j| up to the frame
    std::size_t next = 0;
    struct Worst {
        std::size_t frame = 0;
        std::size_t component = 0;
        double expected = 0.0;
        double actual = 0.0;
        double scale = 0.0;
        double share = -1.0;
    } worst;
    for (std::size_t k = 0; k < trajectory.frames.size(); ++k) {
        const double t = frame_time(trajectory.frames[k]);
        for (; next < kicks->size() && (*kicks)[next].t <= t; ++next) {
            given += (*kicks)[next].impulse;
            given_size += (*kicks)[next].size;
        }
        const Vec2 now = totals_in(trajectory.frames[k], *masses, scene.gravity).momentum;
        const double scale = initial.momentum_scale + given_size;
        const double expected[2] = {initial.momentum.x + given.x, initial.momentum.y + given.y};
        const double actual[2] = {now.x, now.y};
        for (std::size_t c = 0; c < 2; ++c) {
            const double share =
                share_of_allowance(std::abs(actual[c] - expected[c]), x.atol + x.rtol * scale);
            if (share > worst.share) {
                worst = {k, c, expected[c], actual[c], scale, share};
            }
        }
    }
    const double t = frame_time(trajectory.frames[worst.frame]);
    checks.value(std::string("momentum balance") + (worst.component == 0 ? " (x)" : " (y)") +
                     ", nearest to its tolerance at t = " + sentence_number(t) + " s",
                 {worst.expected, worst.scale}, worst.actual);
}

// PHYSICS.md: "with e < 1 energy never increases". One result: the largest
// rise from one frame to the next, judged against the energy's scale at t = 0.
void check_energy_non_increasing(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const std::optional<std::vector<Mass>> masses = masses_of(scene, trajectory, checks);
    if (!masses) {
        return;
    }
    const Totals initial = totals_in(trajectory.frames.front(), *masses, scene.gravity);
    std::size_t worst = 0;
    double before = initial.energy;
    double after = initial.energy;
    double largest_rise = -std::numeric_limits<double>::infinity();
    double previous = initial.energy;
    for (std::size_t k = 1; k < trajectory.frames.size(); ++k) {
        const double energy = totals_in(trajectory.frames[k], *masses, scene.gravity).energy;
        const double rise = energy - previous;
        if (rise > largest_rise || std::isnan(rise)) {
            largest_rise = std::isnan(rise) ? std::numeric_limits<double>::infinity() : rise;
            worst = k;
            before = previous;
            after = energy;
        }
        previous = energy;
    }
    const double t = frame_time(trajectory.frames[worst]);
    // E(k) <= E(k-1) + atol + rtol * scale: one-sided, a fall is always fine.
    const Expectation& x = checks.expectation();
    const double allowed = x.atol + x.rtol * initial.energy_scale;
    checks.judged("energy non-increasing, largest rise at t = " + sentence_number(t) + " s",
                  after <= before + allowed, before, after,
                  "the energy rose by " + sentence_number(after - before) +
                      " J in the step to t = " + sentence_number(t) + " s, more than the " +
                      sentence_number(allowed) + " allowed (atol " + sentence_number(x.atol) +
                      " + rtol " + sentence_number(x.rtol) + " x " +
                      sentence_number(initial.energy_scale) + ")",
                  allowed);
}

// ---------------------------------------------------------------- literal values

void check_event(const Trajectory& trajectory, Checks& checks) {
    const Expectation& x = checks.expectation();
    const std::size_t count = trajectory.events.size();
    if (x.index >= count) {
        checks.failure("",
                       "the run has " + std::to_string(count) + " collision event" +
                           (count == 1 ? "" : "s") + ", so there is no event " +
                           std::to_string(x.index),
                       static_cast<double>(x.index + 1), static_cast<double>(count));
        return;
    }
    const TrajectoryEvent& e = trajectory.events[x.index];
    if (!x.body.empty()) {
        checks.name("a", x.body, e.a);
    }
    if (!x.other.empty()) {
        checks.name("b", x.other, e.b);
    }
    for (const auto& [field, value] : x.values) {
        checks.value(field, plain(value), field_of(e, field));
    }
}

// Frames are k dt apart; the spacing of the first two is the run's dt even
// when a command-line override changed the scene's.
double frame_spacing(const Scene& scene, const Trajectory& trajectory) {
    if (trajectory.frames.size() >= 2) {
        return frame_time(trajectory.frames[1]) - frame_time(trajectory.frames[0]);
    }
    return scene.dt;
}

void check_state(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const Expectation& x = checks.expectation();
    const double dt = frame_spacing(scene, trajectory);
    const auto frame = std::find_if(
        trajectory.frames.begin(), trajectory.frames.end(),
        [&](const std::vector<double>& f) { return std::abs(frame_time(f) - x.t) <= 1e-9 * dt; });
    const std::optional<BodyColumns> columns = body_columns(trajectory, x.body);
    if (!columns) {
        checks.failure("", "the trajectory has no columns for " + single_quoted(x.body));
        return;
    }
    if (frame == trajectory.frames.end()) {
        const double end = trajectory.frames.empty() ? 0.0 : frame_time(trajectory.frames.back());
        checks.failure("", "the run has no frame at t = " + sentence_number(x.t) +
                               " s (its frames are " + sentence_number(dt) +
                               " s apart and end at " + sentence_number(end) + " s)");
        return;
    }
    const Motion m = motion_in(*frame, *columns);
    for (const auto& [field, value] : x.values) {
        checks.value(field, plain(value), field_of(m, field));
    }
}

// ---------------------------------------------------------------- dispatch

// The first words of every line an expectation reports.
std::string subject_of(const Expectation& x) {
    switch (x.kind) {
    case Expectation::Kind::drop:
        return "drop of " + single_quoted(x.body);
    case Expectation::Kind::corner_impact:
        return "corner impact of " + single_quoted(x.body);
    case Expectation::Kind::head_on:
        return "head-on of " + single_quoted(x.body) + " and " + single_quoted(x.other);
    case Expectation::Kind::conserved:
    case Expectation::Kind::energy_non_increasing:
    case Expectation::Kind::momentum_balance:
        return "";
    case Expectation::Kind::event:
        return "event " + std::to_string(x.index);
    case Expectation::Kind::state:
        return "state of " + single_quoted(x.body) + " at t = " + sentence_number(x.t) + " s";
    }
    return "";
}

} // namespace

std::vector<ExpectationResult> evaluate_expectations(const Scene& scene,
                                                     const Trajectory& trajectory) {
    std::vector<ExpectationResult> results;
    for (const Expectation& x : scene.expectations) {
        Checks checks(x, subject_of(x), results);
        switch (x.kind) {
        case Expectation::Kind::drop:
            check_drop(scene, trajectory, checks);
            break;
        case Expectation::Kind::corner_impact:
            check_corner_impact(scene, trajectory, checks);
            break;
        case Expectation::Kind::head_on:
            check_head_on(scene, trajectory, checks);
            break;
        case Expectation::Kind::conserved:
            check_conserved(scene, trajectory, checks);
            break;
        case Expectation::Kind::energy_non_increasing:
            check_energy_non_increasing(scene, trajectory, checks);
            break;
        case Expectation::Kind::momentum_balance:
            check_momentum_balance(scene, trajectory, checks);
            break;
        case Expectation::Kind::event:
            check_event(trajectory, checks);
            break;
        case Expectation::Kind::state:
            check_state(scene, trajectory, checks);
            break;
        }
    }
    return results;
}

} // namespace impulse::harness
