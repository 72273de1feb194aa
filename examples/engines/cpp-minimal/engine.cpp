// cpp-minimal: a small 2D engine that speaks impulse's engine protocol
// (docs/engine-protocol.md) through impulse::protocol. Circles move; circles
// and convex polygons (boxes) may be static. The seed's loop: move every body
// over the step; if any pair interpenetrates, bisect the time of collision,
// apply the impulse of Eq. 9 (docs/physics.md) and go on from there.
// Frictionless circles never turn: the normal passes through their centres.
#include "protocol.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace {

using impulse::Integrator;
using impulse::Shape;
using impulse::ShapeType;
using impulse::Vec2;
using impulse::harness::Scene;
using impulse::protocol::Unsupported;

const char* const engine_name = "cpp-minimal 0.1";
// More collisions than this in one step is a body coming to rest (a Zeno
// cascade), which this engine does not model.
const int max_collisions_per_step = 1000;

struct Body {
    std::string name;
    const Shape* shape = nullptr;
    bool is_static = false;
    Vec2 position;
    double angle = 0.0;
    Vec2 velocity;
    double omega = 0.0;
    double inverse_mass = 0.0;    // 0: static
    double inverse_inertia = 0.0; // 0: static, or "rotation": false
};

// A contact of circle `a` with body `b`: gap < 0 is interpenetration; the
// normal points from b toward a, as in docs/physics.md.
struct Contact {
    std::size_t a = 0;
    std::size_t b = 0;
    double gap = 0.0;
    Vec2 normal;
    Vec2 point;
};

Vec2 rotated(Vec2 v, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

Vec2 closest_on_segment(Vec2 p, Vec2 a, Vec2 b) {
    const Vec2 ab = b - a;
    const double t = std::fmax(0.0, std::fmin(1.0, dot(p - a, ab) / dot(ab, ab)));
    return a + t * ab;
}

// Circle a against body b, a circle or a convex polygon.
Contact contact(const std::vector<Body>& bodies, std::size_t a, std::size_t b) {
    const Body& A = bodies[a];
    const Body& B = bodies[b];
    const double r = A.shape->radius;
    Contact c{a, b, 0.0, {}, {}};
    if (B.shape->type == ShapeType::circle) {
        const Vec2 d = A.position - B.position;
        const double distance = std::sqrt(dot(d, d));
        c.normal = distance > 0.0 ? (1.0 / distance) * d : Vec2{0.0, 1.0};
        c.gap = distance - r - B.shape->radius;
    } else {
        // In B's frame: the deepest edge when the centre is inside, else the
        // closest point of the boundary.
        const impulse::Polygon& poly = B.shape->polygon;
        const Vec2 centre = rotated(A.position - B.position, -B.angle);
        double separation = -std::numeric_limits<double>::infinity();
        Vec2 normal, closest;
        double closest_distance = std::numeric_limits<double>::infinity();
        for (int i = 0; i < poly.count; ++i) {
            const Vec2 v0 = poly.vertices[static_cast<std::size_t>(i)];
            const Vec2 v1 = poly.vertices[static_cast<std::size_t>((i + 1) % poly.count)];
            const double s = dot(poly.normals[static_cast<std::size_t>(i)], centre - v0);
            if (s > separation) {
                separation = s;
                normal = poly.normals[static_cast<std::size_t>(i)];
            }
            const Vec2 q = closest_on_segment(centre, v0, v1);
            const Vec2 d = centre - q;
            if (dot(d, d) < closest_distance) {
                closest_distance = dot(d, d);
                closest = q;
            }
        }
        if (separation > 0.0) { // outside: the closest boundary point decides
            const double distance = std::sqrt(closest_distance);
            normal = (1.0 / distance) * (centre - closest);
            separation = distance;
        }
        c.normal = rotated(normal, B.angle);
        c.gap = separation - r;
    }
    c.point = A.position - r * c.normal;
    return c;
}

// Every pair with a moving body; a is always a circle (the moving one, or the
// earlier of two moving ones).
std::vector<Contact> contacts(const std::vector<Body>& bodies) {
    std::vector<Contact> out;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        for (std::size_t j = i + 1; j < bodies.size(); ++j) {
            if (!bodies[i].is_static) {
                out.push_back(contact(bodies, i, j));
            } else if (!bodies[j].is_static) {
                out.push_back(contact(bodies, j, i));
            }
        }
    }
    return out;
}

// The deepest interpenetrating pair, if any.
std::optional<Contact> deepest(const std::vector<Body>& bodies) {
    std::optional<Contact> worst;
    for (const Contact& c : contacts(bodies)) {
        if (c.gap < 0.0 && (!worst || c.gap < worst->gap)) {
            worst = c;
        }
    }
    return worst;
}

// Moves every body by tau under constant gravity g. Verlet and rk4 are exact
// for a constant force, so both are the parabola.
std::vector<Body> moved(std::vector<Body> bodies, double tau, Vec2 g, Integrator integrator) {
    for (Body& b : bodies) {
        if (b.is_static) {
            continue;
        }
        const Vec2 v0 = b.velocity;
        b.velocity += tau * g;
        if (integrator == Integrator::euler) {
            b.position += tau * v0;
        } else if (integrator == Integrator::symplectic_euler) {
            b.position += tau * b.velocity;
        } else {
            b.position += tau * v0 + (0.5 * tau * tau) * g;
        }
        b.angle += tau * b.omega;
    }
    return bodies;
}

double normal_velocity(const std::vector<Body>& bodies, const Contact& c) {
    const Body& A = bodies[c.a];
    const Body& B = bodies[c.b];
    const Vec2 vA = A.velocity + A.omega * perp(c.point - A.position); // Eq. 7
    const Vec2 vB = B.velocity + B.omega * perp(c.point - B.position);
    return dot(vA - vB, c.normal);
}

// Eq. 9, then Eqs. 8a and 8b for A and, with -j, for B. Returns the event.
impulse::harness::TrajectoryEvent resolve(std::vector<Body>& bodies, const Contact& c, double e,
                                          double t) {
    Body& A = bodies[c.a];
    Body& B = bodies[c.b];
    const Vec2 n = c.normal;
    const double rnA = dot(perp(c.point - A.position), n);
    const double rnB = dot(perp(c.point - B.position), n);
    const double vn = normal_velocity(bodies, c);
    const double k = dot(n, n) * (A.inverse_mass + B.inverse_mass) + rnA * rnA * A.inverse_inertia +
                     rnB * rnB * B.inverse_inertia;
    const double j = -(1.0 + e) * vn / k; // Eq. 9
    A.velocity += (j * A.inverse_mass) * n;
    A.omega += rnA * j * A.inverse_inertia;
    B.velocity -= (j * B.inverse_mass) * n;
    B.omega -= rnB * j * B.inverse_inertia;
    return {t,          A.name, B.name, {c.point.x, c.point.y},
            {n.x, n.y}, j,      vn,     normal_velocity(bodies, c)};
}

// The first solver setting this engine cannot honour, or nullptr. "toi":
// "secant" is honoured: bisection finds the same time of collision within the
// same toi_tolerance, so the physics asked for is the same.
const char* unmodelled_setting(const impulse::SolverSettings& s) {
    if (s.contacts != impulse::ContactMode::single) {
        return "\"contacts\": \"simultaneous\"";
    }
    if (s.stepping != impulse::Stepping::world) {
        return "\"stepping\": \"local\"";
    }
    if (s.ccd) {
        return "\"ccd\": true";
    }
    return s.resting ? "\"resting\": true" : nullptr;
}

// What this engine does not model, refused before it starts.
void refuse_what_is_not_modelled(const Scene& scene) {
    for (const impulse::harness::SceneBody& b : scene.bodies) {
        if (!b.is_static && b.shape.type != ShapeType::circle) {
            throw Unsupported("cpp-minimal moves circles only; the dynamic body '" + b.name +
                              "' is a polygon");
        }
    }
    if (const char* setting = unmodelled_setting(scene.solver)) {
        throw Unsupported(std::string("cpp-minimal does not model the solver setting ") + setting +
                          " (one contact at a time, the whole world stepped, no tunnelling "
                          "check, no resting contact)");
    }
}

// One step of the seed's loop from `t`: returns the bodies at t + dt.
std::vector<Body> step(std::vector<Body> bodies, const Scene& scene, double t,
                       impulse::protocol::TrajectoryWriter& out) {
    const Integrator integrator = scene.solver.integrator;
    double left = scene.dt;
    for (int collisions = 0;; ++collisions) {
        std::vector<Body> end = moved(bodies, left, scene.gravity, integrator);
        if (!deepest(end)) {
            return end;
        }
        if (collisions == max_collisions_per_step) {
            throw Unsupported("cpp-minimal does not model resting contact: more than " +
                              std::to_string(max_collisions_per_step) +
                              " collisions in the step from t = " + std::to_string(t));
        }
        // Bisection: `lo` never interpenetrates, `hi` does.
        double lo = 0.0, hi = left;
        while (hi - lo > scene.solver.toi_tolerance) {
            const double mid = 0.5 * (lo + hi);
            (deepest(moved(bodies, mid, scene.gravity, integrator)) ? hi : lo) = mid;
        }
        bodies = moved(bodies, lo, scene.gravity, integrator);
        const Contact c = *deepest(moved(bodies, hi - lo, scene.gravity, integrator));
        const Contact at_lo = contact(bodies, c.a, c.b);
        t += lo;
        left -= lo;
        if (normal_velocity(bodies, at_lo) < 0.0) { // approaching
            out.event(resolve(bodies, at_lo, scene.restitution, t));
        }
    }
}

std::vector<impulse::protocol::BodyState> states(const std::vector<Body>& bodies) {
    std::vector<impulse::protocol::BodyState> out;
    for (const Body& b : bodies) {
        if (!b.is_static) {
            out.push_back(
                {b.position.x, b.position.y, b.angle, b.velocity.x, b.velocity.y, b.omega});
        }
    }
    return out;
}

void simulate(const Scene& scene, impulse::protocol::TrajectoryWriter& out) {
    refuse_what_is_not_modelled(scene);
    out.setting("integrator", impulse::harness::integrator_name(scene.solver.integrator));
    out.setting("toi", "bisection");
    out.setting("toi_tolerance", scene.solver.toi_tolerance);
    std::vector<Body> bodies;
    for (const impulse::harness::SceneBody& b : scene.bodies) {
        const bool turns = !b.is_static && b.rotation && b.inertia > 0.0;
        bodies.push_back({b.name, &b.shape, b.is_static, b.position, b.angle, b.velocity,
                          b.angular_velocity, b.is_static ? 0.0 : 1.0 / b.mass,
                          turns ? 1.0 / b.inertia : 0.0});
    }
    const auto start = std::chrono::steady_clock::now();
    const long long steps = static_cast<long long>(out.frames_expected()) - 1;
    out.frame(states(bodies));
    for (long long k = 0; k < steps; ++k) {
        bodies = step(bodies, scene, static_cast<double>(k) * scene.dt, out);
        out.frame(states(bodies));
    }
    const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - start;
    out.cost(spent.count(), steps);
}

} // namespace

int main(int argc, char** argv) {
    return impulse::protocol::engine_main(argc, argv, engine_name, simulate);
}
