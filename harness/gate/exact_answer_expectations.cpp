// The expectations docs/physics.md answers exactly: a drop's ladder, a corner
// impact, a head-on collision. The exact answers are computed from the
// scene's own parameters ("Exact answers for checking"); the loader has
// already refused scenes that break their preconditions.
#include "expectation_checks.h"

#include <algorithm>
#include <optional>

namespace impulse::harness {

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
    // Two boxes meeting face to face under simultaneous contacts are recorded
    // as one event per contact point at the same instant: one collision,
    // whose impulse is their sum (an outside review saw half of it judged).
    double impulse = 0.0;
    std::size_t last = *first;
    for (std::size_t i = *first; i < trajectory.events.size(); ++i) {
        const TrajectoryEvent& e = trajectory.events[i];
        if (e.t != trajectory.events[*first].t) {
            break;
        }
        if ((e.a == a->name && e.b == b->name) || (e.a == b->name && e.b == a->name)) {
            impulse += e.impulse;
            last = i;
        }
    }
    checks.value("impulse", h.j, impulse);

    const std::optional<BodyColumns> ca = body_columns(trajectory, a->name);
    const std::optional<BodyColumns> cb = body_columns(trajectory, b->name);
    const std::vector<double>* frame = frame_after_event(trajectory, last, {a->name, b->name});
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

} // namespace impulse::harness
