#include "tunnelling.h"

#include "generated_bodies.h"
#include "input_error.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace impulse::harness {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Four significant digits: a message is read, not parsed.
std::string short_number(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.4g", value);
    return buffer;
}

// How far a body's surface can move by turning alone, per rad/s: its farthest
// vertex. A circle turning moves no surface, and the engine's circle tests
// ignore its angle.
double turning_reach(const Shape& shape) {
    if (shape.type == ShapeType::circle) {
        return 0.0;
    }
    double reach = 0.0;
    for (int i = 0; i < shape.polygon.count; ++i) {
        reach = std::max(reach, length(shape.polygon.vertices[static_cast<std::size_t>(i)]));
    }
    return reach;
}

// The lowest point of a body at its pose at t = 0 along `up` (sign = 1), or
// its highest (sign = -1).
double extreme_point(const SceneBody& body, Vec2 up, double sign) {
    if (body.shape.type == ShapeType::circle) {
        return dot(body.position, up) - sign * body.shape.radius;
    }
    const double c = std::cos(body.angle);
    const double s = std::sin(body.angle);
    double extreme = infinity;
    for (int i = 0; i < body.shape.polygon.count; ++i) {
        const Vec2 v = body.shape.polygon.vertices[static_cast<std::size_t>(i)];
        const Vec2 world{body.position.x + c * v.x - s * v.y, body.position.y + s * v.x + c * v.y};
        extreme = std::min(extreme, sign * dot(world, up));
    }
    return sign * extreme;
}

// The speed gravity can add to a body over the run, as seen by anything it
// could tunnel through.
//  - Two bodies in free fall gain the same g t: gravity changes no relative
//    speed, so it matters only against static bodies (and bodies resting on
//    them). With no static body it adds nothing.
//  - In free fall the body gains at most |g| duration.
//  - Collisions with e <= 1 never add energy, so a body has at most the
//    energy it started with plus what its fall released: |v|^2 <= |v0|^2 +
//    2 |g| h, h the drop available: from its lowest point at t = 0 down to the
//    lowest top of a static body (the floor of a room, the ground), where it
//    lands at the latest. What falls past every static body meets none below
//    to pass through. (This takes the body's own energy; speed passed on by
//    other dynamic bodies is not bounded.)
// The smaller of the two is the gain: a stack resting for 60 s gains the
// speed of its fall, not g * 60 s.
double gravity_gain(const Scene& scene, const SceneBody& body, double lowest_top) {
    const double g = length(scene.gravity);
    if (body.is_static || g == 0.0 || lowest_top == infinity) {
        return 0.0;
    }
    const Vec2 up = (-1.0 / g) * scene.gravity;
    const double v0 = length(body.velocity);
    const double drop = std::max(0.0, extreme_point(body, up, 1.0) - lowest_top);
    const double by_energy = std::sqrt(v0 * v0 + 2.0 * g * drop) - v0;
    return std::min(g * scene.duration, by_energy);
}

// How far the body's centre can travel over the run. Its speed at time t is
// at most |v0| + |g| t (nothing but gravity speeds it up, and a bounce off a
// static body with e <= 1 only slows its fall) and at most |v0| + gain, so
// the distance is the integral of the smaller of the two.
double travel(const Scene& scene, const SceneBody& body, double gain) {
    const double v0 = length(body.velocity);
    const double T = scene.duration;
    if (gain <= 0.0) {
        return v0 * T;
    }
    const double g = length(scene.gravity);
    const double t_cap = gain / g; // when |v0| + g t reaches |v0| + gain
    if (t_cap >= T) {
        return v0 * T + 0.5 * g * T * T;
    }
    return v0 * T + 0.5 * gain * t_cap + gain * (T - t_cap);
}

struct Reach {
    double radius = 0.0;  // inradius: half the body's thickness
    double extent = 0.0;  // the farthest point from the centre
    double travel = 0.0;  // how far the centre can get over the run (travel)
    double turning = 0.0; // |omega| R: how fast turning moves the surface
    double gain = 0.0;    // what gravity can add to its speed (gravity_gain)
    double speed = 0.0;   // |v0| + turning + gain: the fastest it can be
};

std::vector<Reach> reaches_of(const Scene& scene) {
    double lowest_top = infinity;
    const double g = length(scene.gravity);
    for (const SceneBody& body : scene.bodies) {
        if (body.is_static && g > 0.0) {
            lowest_top =
                std::min(lowest_top, extreme_point(body, (-1.0 / g) * scene.gravity, -1.0));
        }
    }
    std::vector<Reach> out(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneBody& body = scene.bodies[i];
        Reach& r = out[i];
        r.radius = inradius(body.shape);
        r.turning =
            body.is_static ? 0.0 : std::abs(body.angular_velocity) * turning_reach(body.shape);
        r.gain = gravity_gain(scene, body, lowest_top);
        r.extent =
            body.shape.type == ShapeType::circle ? body.shape.radius : turning_reach(body.shape);
        r.travel = body.is_static ? 0.0 : travel(scene, body, r.gain);
        r.speed = length(body.velocity) + r.turning + r.gain;
    }
    return out;
}

TunnellingRefusal refusal(const Scene& scene, std::size_t fast, std::size_t slow,
                          const std::vector<Reach>& reach, double closing, double thickness) {
    const SceneBody& a = scene.bodies[fast];
    const SceneBody& b = scene.bodies[slow];
    // A speed bound that overflows (gravity or a velocity beyond 1e154, whose
    // length squares to infinity) has no safe dt to offer: say so, rather
    // than quote "inf m/s" and "dt below 0 s".
    if (!std::isfinite(closing)) {
        return TunnellingRefusal{body_path(scene, fast),
                                 single_quoted(a.name) + " and " + single_quoted(b.name) +
                                     " could close at a speed that overflows double precision "
                                     "(the scene's gravity, velocities or angular velocities are "
                                     "too large to simulate); scale them down"};
    }
    const double safe_dt = thickness / closing;
    const double gain = reach[fast].gain + reach[slow].gain;
    const std::string gravity = gain > 0.0 ? " (" + short_number(closing - gain) +
                                                 " m/s at t = 0, and gravity adds up to " +
                                                 short_number(gain) + " m/s)"
                                           : " at t = 0";
    // A resting scene reaching here asked for events (time-stepping and "auto"
    // are exempt), and either of those is one more cure for it.
    const std::string settings =
        scene.solver.resting ? "\"ccd\": true or \"resting_method\": \"auto\" or \"time-stepping\""
                             : "\"ccd\": true";
    const std::string cure =
        scene.solver.stepping == Stepping::local
            ? "use dt below " + short_number(safe_dt) + " s (ccd needs \"stepping\": \"world\")"
            : "set " + settings + " in the solver block, or use dt below " + short_number(safe_dt) +
                  " s";
    return TunnellingRefusal{
        body_path(scene, fast),
        single_quoted(a.name) + " and " + single_quoted(b.name) + " close at up to " +
            short_number(closing) + " m/s" + gravity + ": " + short_number(closing * scene.dt) +
            " m per step of dt = " + short_number(scene.dt) +
            " s, at least their combined thickness of " + short_number(thickness) +
            " m, so one could pass through the other between two steps without either end of "
            "the step seeing them overlap (tunnelling); " +
            cure};
}

} // namespace

std::optional<TunnellingRefusal> tunnelling_refusal(const Scene& scene) {
    // Time-stepping contact does not test pairs only at the ends of a step: each
    // step takes a contact point for every pair whose boxes, grown by the
    // step's whole motion (the union of the boxes at both ends, plus the
    // turning reach), overlap, and the contact problem then forbids passing
    // through. Its candidates cover the swept motion as ccd does, so nothing
    // here applies. "auto" runs events only in steps where no pair could pass
    // through: before a step where one could, the engine takes time-stepping
    // (world.cpp, could_pass_through), so only "events" and scenes without
    // resting contact are refused here.
    const bool automatic =
        scene.solver.resting && scene.solver.resting_method == RestingMethod::automatic;
    if (scene.solver.ccd || automatic || time_stepping_from_start(scene)) {
        return std::nullopt;
    }
    const std::vector<Reach> reach = reaches_of(scene);
    double fastest = 0.0;
    double thinnest = infinity;
    for (const Reach& r : reach) {
        fastest = std::max(fastest, r.speed);
        thinnest = std::min(thinnest, r.radius);
    }
    // No pair closes faster than twice the fastest body or is thinner than
    // twice the thinnest: most scenes (a gas of 10^4 bodies among them) are
    // cleared here without looking at pairs.
    if (2.0 * fastest * scene.dt < 4.0 * thinnest) {
        return std::nullopt;
    }
    const std::size_t n = scene.bodies.size();
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = i + 1; k < n; ++k) {
            const SceneBody& a = scene.bodies[i];
            const SceneBody& b = scene.bodies[k];
            if (a.is_static && b.is_static) {
                continue;
            }
            const double closing = length(a.velocity - b.velocity) + reach[i].turning +
                                   reach[k].turning + reach[i].gain + reach[k].gain;
            const double thickness = 2.0 * (reach[i].radius + reach[k].radius);
            if (closing * scene.dt < thickness) {
                continue;
            }
            // A pair too far apart to touch within the run cannot tunnel:
            // the rods of `rod`, 8 m apart, fall 1.5 m each.
            const double gap = length(a.position - b.position) - reach[i].extent - reach[k].extent;
            if (gap > reach[i].travel + reach[k].travel) {
                continue;
            }
            const bool a_faster = reach[i].speed >= reach[k].speed;
            return a_faster ? refusal(scene, i, k, reach, closing, thickness)
                            : refusal(scene, k, i, reach, closing, thickness);
        }
    }
    return std::nullopt;
}

void refuse_tunnelling(const Scene& scene) {
    if (const std::optional<TunnellingRefusal> r = tunnelling_refusal(scene)) {
        throw InputError(scene.file, r->path, r->message);
    }
}

} // namespace impulse::harness
