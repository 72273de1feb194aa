// The exact answers of docs/physics.md and when they apply (see exact_answers.h).
#include "exact_answers.h"

#include "broad_phase.h"
#include "manifold.h"
#include "rotation.h"
#include "text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

namespace impulse::harness {

namespace {

// Shortest text that reads back to the same double, as the loader quotes
// values: a refusal becomes one of its messages.
std::string number_text(double value) {
    char buffer[32];
    const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string vec2_text(Vec2 v) {
    return "(" + number_text(v.x) + ", " + number_text(v.y) + ")";
}

Transform initial_transform(const SceneBody& body) {
    return {body.position, rotation_of(body.angle)};
}

Refusal refuse(Refusal::Where where, std::string message) {
    return {where, std::move(message)};
}

// Gravity (0, -g): the formulas are written for ground below and g >= 0.
std::optional<Refusal> gravity_refusal(const Scene& scene, const std::string& formula,
                                       bool allow_zero) {
    const Vec2 g = scene.gravity;
    const bool downward = g.x == 0.0 && (allow_zero ? g.y <= 0.0 : g.y < 0.0);
    if (downward) {
        return std::nullopt;
    }
    return refuse(Refusal::Where::entry, formula + " needs gravity (0, -g) with g " +
                                             (allow_zero ? ">=" : ">") +
                                             " 0, but the scene's gravity is " + vec2_text(g));
}

std::optional<Refusal> gap_refusal(const Scene& scene, const SceneBody& body,
                                   const std::string& formula) {
    const std::optional<Landing> landing = landing_below(scene, body);
    if (!landing) {
        const bool any_static = std::any_of(scene.bodies.begin(), scene.bodies.end(),
                                            [](const SceneBody& b) { return b.is_static; });
        return refuse(Refusal::Where::body,
                      formula + " needs static ground for " + single_quoted(body.name) +
                          " to fall on, but " +
                          (any_static ? "moved straight down it meets no static body"
                                      : "every body is dynamic"));
    }
    const double gap = landing->gap;
    const std::string ground =
        single_quoted(scene.bodies[static_cast<std::size_t>(landing->ground)].name);
    if (!(gap > 0.0)) {
        return refuse(Refusal::Where::body, formula + " needs a gap between " +
                                                single_quoted(body.name) +
                                                " and the static ground at t = 0, but it "
                                                "touches it");
    }
    // Within contact_tolerance the engine counts the pair as touching: it
    // never collides, so the formula's impacts never come.
    const double tolerance = scene.solver.contact_tolerance;
    if (!(gap > tolerance)) {
        return refuse(Refusal::Where::body,
                      formula + " needs a gap between " + single_quoted(body.name) +
                          " and the static ground at t = 0 wider than solver.contact_tolerance (" +
                          number_text(tolerance) +
                          " m), within which the two count as touching "
                          "and never collide, but it is " +
                          number_text(gap) + " m; raise the body or lower the tolerance");
    }
    // The formulas bounce the body straight back up: the surface it lands on
    // must be level there, and for a body free to turn the impulse must pass
    // below its centre (a ledge narrower than a flat landing, or its corner,
    // would send it off sideways or spinning).
    if (!(std::abs(landing->normal.x) <= parallel_tolerance && landing->normal.y > 0.0)) {
        return refuse(Refusal::Where::body,
                      formula + " needs " + single_quoted(body.name) +
                          " to land on a level surface, but moved straight down it meets " +
                          ground + " where the contact normal is " + vec2_text(landing->normal));
    }
    return std::nullopt;
}

// For a polygon free to turn, where the ground's impulse acts decides the
// spin: the landing's contact must be at `x` (its centre for a drop, its
// lowest corner for a corner impact), which a ledge narrower than the body,
// or one it meets on its own corner, would move.
std::optional<Refusal> landing_point_refusal(const Scene& scene, const SceneBody& body,
                                             const std::string& formula, double x,
                                             const std::string& what) {
    const std::optional<Landing> landing = landing_below(scene, body);
    if (!landing || body.shape.type != ShapeType::polygon || !body.rotation ||
        std::abs(landing->point.x - x) <= level_corners * (1.0 + std::abs(x))) {
        return std::nullopt;
    }
    const std::string ground =
        single_quoted(scene.bodies[static_cast<std::size_t>(landing->ground)].name);
    return refuse(Refusal::Where::body, formula + " needs the ground's impulse on " +
                                            single_quoted(body.name) + " at " + what +
                                            ", x = " + number_text(x) +
                                            ", but moved straight down it "
                                            "meets " +
                                            ground + " at x = " + number_text(landing->point.x) +
                                            " (a ledge narrower than the body, or its edge)");
}

} // namespace

// ---------------------------------------------------------------- the scene at t = 0

double gravity_magnitude(const Scene& scene) {
    return -scene.gravity.y;
}

namespace {

// How far `body`, moved straight down, falls before it touches `ground`, with
// the contact there; empty when it passes beside it. Conservative advancement:
// a signed gap (never more than the distance) moved at a time never passes
// the first touch, and one move is exact against a level surface below.
std::optional<Landing> fall_onto(const SceneBody& body, const SceneBody& ground) {
    const Transform xg = initial_transform(ground);
    const Aabb below = aabb_of(ground.shape, xg, 0.0);
    const Aabb falling = aabb_of(body.shape, initial_transform(body), 0.0);
    if (falling.upper.x < below.lower.x || below.upper.x < falling.lower.x ||
        falling.upper.y < below.lower.y) {
        return std::nullopt; // beside it, or wholly below it
    }
    const double size = std::max(falling.upper.x - falling.lower.x, below.upper.x - below.lower.x) +
                        std::abs(body.position.y) + std::abs(ground.position.y);
    Transform xb = initial_transform(body);
    double fallen = 0.0;
    double gap = separation(body.shape, xb, ground.shape, xg);
    for (int k = 0; k < 10000 && gap > 1e-13 * size; ++k) {
        fallen += gap;
        xb.p.y = body.position.y - fallen;
        if (falling.upper.y - fallen < below.lower.y) {
            return std::nullopt; // slid past it
        }
        gap = separation(body.shape, xb, ground.shape, xg);
    }
    if (fallen == 0.0) {
        fallen = gap; // touching or overlapping at t = 0: the signed gap
    }
    const Manifold m =
        collide(body.shape, xb, ground.shape, xg, 1e-9 * size, VertexNormal::reference_face);
    Landing landing{fallen, -1, m.normal, {}};
    for (int i = 0; i < m.point_count; ++i) {
        landing.point =
            landing.point + m.points[static_cast<std::size_t>(i)].point * (1.0 / m.point_count);
    }
    return landing;
}

} // namespace

std::optional<Landing> landing_below(const Scene& scene, const SceneBody& body) {
    std::optional<Landing> first;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneBody& ground = scene.bodies[i];
        if (!ground.is_static) {
            continue;
        }
        std::optional<Landing> landing = fall_onto(body, ground);
        if (landing && (!first || landing->gap < first->gap)) {
            landing->ground = static_cast<int>(i);
            first = landing;
        }
    }
    return first;
}

std::optional<double> gap_to_static_ground(const Scene& scene, const SceneBody& body) {
    const std::optional<Landing> landing = landing_below(scene, body);
    return landing ? std::optional<double>(landing->gap) : std::nullopt;
}

std::vector<Vec2> world_vertices(const SceneBody& body) {
    const Transform xf = initial_transform(body);
    std::vector<Vec2> out;
    for (int i = 0; i < body.shape.polygon.count; ++i) {
        out.push_back(apply(xf, body.shape.polygon.vertices[static_cast<std::size_t>(i)]));
    }
    return out;
}

bool lands_on_corner_below_centre(const SceneBody& body) {
    const std::vector<Vec2> corners = world_vertices(body);
    std::vector<Vec2> by_height = corners;
    std::sort(by_height.begin(), by_height.end(), [](Vec2 a, Vec2 b) { return a.y < b.y; });
    double size = 0.0;
    for (const Vec2 c : corners) {
        size = std::max(size, length(c - body.position));
    }
    return by_height[1].y - by_height[0].y >= level_corners &&
           std::abs(by_height[0].x - body.position.x) <= 1e-12 * size;
}

// Exactly two lowest corners, level, their midpoint straight below the centre:
// with simultaneous contacts both take equal impulses and the body bounces
// flat, as a point mass would.
bool lands_flat_below_centre(const SceneBody& body) {
    const std::vector<Vec2> corners = world_vertices(body);
    if (corners.size() < 3) {
        return false;
    }
    std::vector<Vec2> by_height = corners;
    std::sort(by_height.begin(), by_height.end(), [](Vec2 a, Vec2 b) { return a.y < b.y; });
    double size = 0.0;
    for (const Vec2 c : corners) {
        size = std::max(size, length(c - body.position));
    }
    const double middle = 0.5 * (by_height[0].x + by_height[1].x);
    return by_height[1].y - by_height[0].y < level_corners &&
           by_height[2].y - by_height[1].y >= level_corners &&
           std::abs(middle - body.position.x) <= 1e-12 * size;
}

bool has_face_along(const SceneBody& body, Vec2 u) {
    if (body.shape.type != ShapeType::polygon) {
        return false;
    }
    const Rotation q = rotation_of(body.angle);
    for (int i = 0; i < body.shape.polygon.count; ++i) {
        const Vec2 n = rotate(q, body.shape.polygon.normals[static_cast<std::size_t>(i)]);
        if (std::abs(cross(n, u)) <= parallel_tolerance) {
            return true;
        }
    }
    return false;
}

// ---------------------------------------------------------------- when a formula applies

std::optional<Refusal> drop_refusal(const Scene& scene, const SceneBody& body,
                                    const std::string& formula) {
    if (std::optional<Refusal> gravity = gravity_refusal(scene, formula, false)) {
        return gravity;
    }
    const std::string name = single_quoted(body.name);
    if (body.velocity != Vec2{}) {
        return refuse(Refusal::Where::body, formula + " needs the body at rest at t = 0, but " +
                                                name + " has velocity " + vec2_text(body.velocity));
    }
    if (body.angular_velocity != 0.0) {
        return refuse(Refusal::Where::body, formula + " needs the body at rest at t = 0, but " +
                                                name + " has angular velocity " +
                                                number_text(body.angular_velocity) + " rad/s");
    }
    // A free polygon lands on one corner first (the seed's single contact) and
    // starts to spin, unless that corner is straight below its centre; a disc
    // (impulse through its centre) and a non-rotating body bounce straight.
    const bool flat =
        scene.solver.contacts == ContactMode::simultaneous && lands_flat_below_centre(body);
    if (body.shape.type == ShapeType::polygon && body.rotation &&
        !lands_on_corner_below_centre(body) && !flat) {
        return refuse(Refusal::Where::body,
                      formula + " has no rotation, but " + name +
                          " is a polygon free to rotate that lands neither on one corner below "
                          "its centre nor (with \"contacts\": \"simultaneous\") flat and "
                          "centred; give it \"rotation\": false");
    }
    if (std::optional<Refusal> gap = gap_refusal(scene, body, formula)) {
        return gap;
    }
    return landing_point_refusal(scene, body, formula, body.position.x, "its centre");
}

std::optional<Refusal> corner_impact_refusal(const Scene& scene, const SceneBody& body,
                                             const std::string& formula) {
    const std::string name = single_quoted(body.name);
    if (body.shape.type != ShapeType::polygon) {
        return refuse(Refusal::Where::body,
                      formula + " needs a polygon, but " + name + " is a circle");
    }
    if (!body.rotation) {
        return refuse(Refusal::Where::body, formula + " needs a body free to rotate, but " + name +
                                                " has \"rotation\": false");
    }
    if (body.angular_velocity != 0.0) {
        return refuse(Refusal::Where::body, formula + " needs angular velocity 0 at t = 0, but " +
                                                name + " has " +
                                                number_text(body.angular_velocity) + " rad/s");
    }
    if (std::optional<Refusal> gravity = gravity_refusal(scene, formula, true)) {
        return gravity;
    }
    std::vector<double> heights;
    for (const Vec2 v : world_vertices(body)) {
        heights.push_back(v.y);
    }
    std::sort(heights.begin(), heights.end());
    if (!(heights[1] - heights[0] >= level_corners)) {
        return refuse(Refusal::Where::body, formula + " needs one lowest corner, but " + name +
                                                " has two corners within " +
                                                number_text(level_corners) +
                                                " m of the same height (a flat landing)");
    }
    if (std::optional<Refusal> gap = gap_refusal(scene, body, formula)) {
        return gap;
    }
    const std::vector<Vec2> corners = world_vertices(body);
    const Vec2 lowest =
        *std::min_element(corners.begin(), corners.end(), [](Vec2 a, Vec2 b) { return a.y < b.y; });
    if (std::optional<Refusal> point =
            landing_point_refusal(scene, body, formula, lowest.x, "its lowest corner")) {
        return point;
    }
    if (scene.gravity.y == 0.0 && !(body.velocity.y < 0.0)) {
        return refuse(Refusal::Where::body, formula +
                                                " without gravity needs the body moving down, "
                                                "but " +
                                                name + " has vy = " + number_text(body.velocity.y));
    }
    return std::nullopt;
}

std::optional<Refusal> head_on_refusal(const Scene& scene, const SceneBody& a, const SceneBody& b,
                                       const std::string& formula) {
    if (a.name == b.name) {
        return refuse(Refusal::Where::other, formula +
                                                 " needs two distinct bodies, but a and b are "
                                                 "both '" +
                                                 a.name + "'");
    }
    if (scene.gravity != Vec2{}) {
        return refuse(Refusal::Where::entry, formula +
                                                 " needs zero gravity, but the scene's gravity "
                                                 "is " +
                                                 vec2_text(scene.gravity));
    }
    // An impulse through both centres turns neither body; for a free polygon
    // the seed's single contact point is a corner, off the line of centres.
    for (const auto& [body, where] :
         {std::pair{&a, Refusal::Where::body}, std::pair{&b, Refusal::Where::other}}) {
        if (body->shape.type == ShapeType::polygon && body->rotation) {
            return refuse(where, formula + " has no rotation, but '" + body->name +
                                     "' is a polygon free to rotate; give it \"rotation\": "
                                     "false");
        }
    }
    const Vec2 line = b.position - a.position;
    const Vec2 u = (1.0 / length(line)) * line;
    const Vec2 relative = a.velocity - b.velocity;
    const double closing = dot(relative, u);
    const std::string pair = single_quoted(a.name) + " and " + single_quoted(b.name);
    if (!(closing > 0.0)) {
        return refuse(Refusal::Where::entry,
                      formula + " needs " + pair +
                          " approaching along the line of their centres, but their closing "
                          "speed is " +
                          number_text(closing) + " m/s");
    }
    if (std::abs(cross(u, relative)) > parallel_tolerance * length(relative)) {
        return refuse(Refusal::Where::entry,
                      formula + " needs " + pair +
                          " approaching along the line of their centres, but their relative "
                          "velocity " +
                          vec2_text(relative) + " is not along " + vec2_text(u));
    }
    const bool polygons = a.shape.type == ShapeType::polygon || b.shape.type == ShapeType::polygon;
    if (polygons && !has_face_along(a, u) && !has_face_along(b, u)) {
        return refuse(Refusal::Where::entry, formula +
                                                 " needs the contact normal along the line of "
                                                 "centres " +
                                                 vec2_text(u) + ", but no face of " + pair +
                                                 " is perpendicular to it");
    }
    return std::nullopt;
}

std::optional<std::string> conservation_refusal(const Scene& scene, const std::string& quantity) {
    if (quantity == "energy") {
        if (scene.restitution != 1.0) {
            return "energy is conserved only with restitution 1, but the scene's is " +
                   number_text(scene.restitution);
        }
        return std::nullopt;
    }
    const std::string what = quantity == "momentum" ? "momentum" : "angular momentum";
    if (scene.gravity != Vec2{}) {
        return what + " is conserved only in free space, but the scene's gravity is " +
               vec2_text(scene.gravity);
    }
    for (const SceneBody& body : scene.bodies) {
        if (body.is_static) {
            return what + " is conserved only in free space, but '" + body.name +
                   "' is static and takes up " + what + " in a collision";
        }
    }
    return std::nullopt;
}

// ---------------------------------------------------------------- the formulas

double DropLadder::v1() const {
    return std::sqrt(2.0 * g * h0);
}

double DropLadder::t1() const {
    return v1() / g;
}

double DropLadder::e_to(int n) const {
    double out = 1.0;
    for (int k = 0; k < n; ++k) {
        out *= e;
    }
    return out;
}

double DropLadder::impact_time(int n) const {
    double t = t1();
    for (int k = 1; k < n; ++k) {
        t += 2.0 * e_to(k) * v1() / g;
    }
    return t;
}

double DropLadder::rebound_speed(int n) const {
    return e_to(n) * v1();
}

double DropLadder::apex_gap(int n) const {
    return e_to(2 * n) * h0;
}

std::optional<DropLadder> drop_ladder(const Scene& scene, const SceneBody& body) {
    const std::optional<double> h0 = gap_to_static_ground(scene, body);
    if (!h0) {
        return std::nullopt;
    }
    return DropLadder{*h0, gravity_magnitude(scene), scene.restitution};
}

namespace {

// The smallest t > 0 with h + vy0 t - g t^2 / 2 = 0. Of the two forms of the
// root the one without cancellation is used: 2 h / (s - vy0) when falling
// (it also covers g = 0, t = h / -vy0), (vy0 + s) / g when thrown up.
double time_to_fall(double h, double vy0, double g, double s) {
    return vy0 < 0.0 ? 2.0 * h / (s - vy0) : (vy0 + s) / g;
}

} // namespace

CornerImpact corner_impact(const Scene& scene, const SceneBody& body, double h) {
    const Rotation q = rotation_of(body.angle);
    const Polygon& polygon = body.shape.polygon;
    Vec2 lowest = rotate(q, polygon.vertices[0]);
    for (int i = 1; i < polygon.count; ++i) {
        const Vec2 v = rotate(q, polygon.vertices[static_cast<std::size_t>(i)]);
        if (v.y < lowest.y) {
            lowest = v;
        }
    }
    const double g = gravity_magnitude(scene);
    const double e = scene.restitution;
    const double vy0 = body.velocity.y;
    CornerImpact c;
    // Falling h from vy0: v^2 = vy0^2 + 2 g h.
    c.v = std::sqrt(vy0 * vy0 + 2.0 * g * h);
    c.t_hit = time_to_fall(h, vy0, g, c.v);
    c.rx = lowest.x;
    const double drift = body.velocity.x * c.t_hit;
    c.point_x = body.position.x + drift + c.rx;
    c.point_scale = std::abs(body.position.x) + std::abs(drift) + std::abs(c.rx);
    c.j = (1.0 + e) * c.v / (1.0 / body.mass + c.rx * c.rx / body.inertia);
    c.vy_after = -c.v + c.j / body.mass;
    c.w_after = c.rx * c.j / body.inertia;
    return c;
}

HeadOn head_on(const Scene& scene, const SceneBody& a, const SceneBody& b) {
    HeadOn h;
    const Vec2 line = b.position - a.position;
    h.u = (1.0 / length(line)) * line;
    h.va = dot(a.velocity, h.u);
    h.vb = dot(b.velocity, h.u);
    h.pa = dot(a.velocity, perp(h.u));
    h.pb = dot(b.velocity, perp(h.u));
    const double ma = a.mass, mb = b.mass, e = scene.restitution;
    const double closing = h.va - h.vb;
    const double total = ma + mb;
    const double momentum = ma * std::abs(h.va) + mb * std::abs(h.vb);
    h.va_after = {(ma * h.va + mb * h.vb - mb * e * closing) / total,
                  (momentum + mb * e * std::abs(closing)) / total};
    h.vb_after = {(ma * h.va + mb * h.vb + ma * e * closing) / total,
                  (momentum + ma * e * std::abs(closing)) / total};
    h.j = plain(ma * mb * (1.0 + e) * closing / total);
    return h;
}

// ---------------------------------------------------------------- reading a trajectory

Motion motion_in(const std::vector<double>& frame, const BodyColumns& c) {
    return {{value_at(frame, c.x), value_at(frame, c.y)},
            value_at(frame, c.angle),
            {value_at(frame, c.vx), value_at(frame, c.vy)},
            value_at(frame, c.omega)};
}

std::optional<std::vector<Mass>> masses_of(const Scene& scene, const Trajectory& trajectory,
                                           std::string& missing) {
    std::vector<Mass> masses;
    for (const SceneBody& body : scene.bodies) {
        if (body.is_static) {
            continue;
        }
        const std::optional<BodyColumns> columns = body_columns(trajectory, body.name);
        if (!columns) {
            missing = body.name;
            return std::nullopt;
        }
        masses.push_back({&body, *columns, body.rotation ? body.inertia : 0.0});
    }
    return masses;
}

Totals totals_in(const std::vector<double>& frame, const std::vector<Mass>& masses, Vec2 gravity) {
    Totals t;
    for (const Mass& m : masses) {
        const Motion s = motion_in(frame, m.columns);
        const double mass = m.body->mass;
        t.momentum += mass * s.velocity;
        t.momentum_scale += mass * length(s.velocity);
        const double orbital = mass * cross(s.position, s.velocity);
        const double spin = m.inertia * s.omega;
        t.angular_momentum += orbital + spin;
        // The cross product's own two terms: a body moving along the line
        // through the origin has x cross v = 0 from terms that are not.
        t.angular_momentum_scale +=
            mass * (std::abs(s.position.x * s.velocity.y) + std::abs(s.position.y * s.velocity.x)) +
            std::abs(spin);
        const double kinetic =
            0.5 * mass * length_squared(s.velocity) + 0.5 * m.inertia * s.omega * s.omega;
        const double potential = -mass * dot(gravity, s.position);
        t.energy += kinetic + potential;
        t.energy_scale += kinetic + mass * (std::abs(gravity.x * s.position.x) +
                                            std::abs(gravity.y * s.position.y));
    }
    return t;
}

} // namespace impulse::harness
