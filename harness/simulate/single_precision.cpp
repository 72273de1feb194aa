#include "single_precision.h"

#include "input_error.h"
#include "shape.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace impulse::harness {

namespace {

constexpr double float_max = static_cast<double>(std::numeric_limits<float>::max()); // 3.4e38
constexpr double float_min = static_cast<double>(std::numeric_limits<float>::min()); // 1.2e-38
constexpr double highest = float_max / single_precision_headroom;
constexpr double lowest = float_min * single_precision_headroom;

// "1e39", "3.4e38", "0.5": three digits, no '+' or leading zeros in the exponent.
std::string short_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    std::string s = text;
    const std::size_t e = s.find('e');
    if (e != std::string::npos) {
        std::string exponent = s.substr(e + 1);
        const bool negative = exponent.front() == '-';
        exponent.erase(0, exponent.find_first_not_of("+-0"));
        s = s.substr(0, e + 1) + (negative ? "-" : "") + (exponent.empty() ? "0" : exponent);
    }
    return s;
}

// One scene, one engine: judges each quantity and throws on the first it cannot hold.
struct Judge {
    const Scene& scene;
    const std::string& engine;

    // `zero_allowed`: 0 means "none" here (a velocity), not a divisor (a mass).
    void operator()(const std::string& path, const std::string& what, double value,
                    const std::string& unit, bool zero_allowed) const {
        const double size = std::fabs(value);
        if (!std::isfinite(value) || size > highest) {
            fail(path, what + " " + short_number(value) + unit + " is beyond " + engine +
                           "'s single precision (max " + short_number(float_max) +
                           ", and it forms products of it, so at most " + short_number(highest) +
                           ")");
        }
        if (size == 0.0 && !zero_allowed) {
            fail(path, what + " is 0, which " + engine + " cannot represent (it divides by it)");
        }
        if (size != 0.0 && size < lowest) {
            fail(path, what + " " + short_number(value) + unit + " is below " + engine +
                           "'s single precision (smallest normal float " + short_number(float_min) +
                           ", and it forms products of it, so at least " + short_number(lowest) +
                           ")");
        }
    }

    [[noreturn]] void fail(const std::string& path, const std::string& reason) const {
        throw InputError(scene.file, path, reason + "; " + engine + " cannot run this scene");
    }
};

// The farthest point of the shape from its centre.
void judge_shape(const Judge& judge, const Shape& shape, const std::string& path) {
    if (shape.type == ShapeType::circle) {
        judge(path, "its radius", shape.radius, " m", false);
        return;
    }
    for (int i = 0; i < shape.polygon.count; ++i) {
        const Vec2 v = shape.polygon.vertices[static_cast<std::size_t>(i)];
        judge(path, "its vertex " + std::to_string(i) + " x", v.x, " m", true);
        judge(path, "its vertex " + std::to_string(i) + " y", v.y, " m", true);
    }
    judge(path, "its size", circumradius(shape), " m", false);
}

// The mass properties and the products of them the engine forms. Speeds are
// bounded by |v0| + |g| duration (collisions with e <= 1 add none in the
// engine's model, and the clamp of b2_maxTranslation only lowers them).
void judge_dynamics(const Judge& judge, const Scene& scene, const SceneBody& body,
                    const std::string& path, double dt) {
    const double g = length(scene.gravity);
    const double speed = length(body.velocity) + g * scene.duration;
    judge(path + ".mass", "its mass", body.mass, " kg", false);
    judge(path + ".mass", "its inverse mass", 1.0 / body.mass, " 1/kg", false);
    judge(path + ".velocity", "its momentum of up to m (|v| + |g| duration) =", body.mass * speed,
          " kg m/s", true);
    judge(path + ".mass", "its weight's impulse per step m |g| dt", body.mass * g * dt, " N s",
          true);
    if (body.rotation && body.inertia > 0.0) {
        judge(path + ".inertia", "its rotational inertia", body.inertia, " kg m^2", false);
        judge(path + ".inertia", "its inverse rotational inertia", 1.0 / body.inertia,
              " 1/(kg m^2)", false);
        judge(path + ".angular_velocity", "its angular momentum",
              body.inertia * body.angular_velocity, " kg m^2/s", true);
    }
    const double farthest =
        length(body.position) + circumradius(body.shape) + speed * scene.duration;
    judge(path + ".position",
          "the farthest it can get from the origin, |position| + size + "
          "(|v| + |g| duration) duration =",
          farthest, " m", true);
}

} // namespace

void require_single_precision(const Scene& scene, const std::string& engine, double dt) {
    const Judge judge{scene, engine};
    judge("gravity", "its x", scene.gravity.x, " m/s^2", true);
    judge("gravity", "its y", scene.gravity.y, " m/s^2", true);
    judge("dt", engine + "'s step", dt, " s", false);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneBody& body = scene.bodies[i];
        const std::string path =
            i < scene.listed_bodies ? "bodies[" + std::to_string(i) + "]" : std::string("gas");
        judge(path + ".position", "its x", body.position.x, " m", true);
        judge(path + ".position", "its y", body.position.y, " m", true);
        judge(path + ".angle", "its angle", body.angle, " rad", true);
        judge_shape(judge, body.shape, path + ".shape");
        if (body.is_static) {
            continue;
        }
        judge(path + ".velocity", "its x", body.velocity.x, " m/s", true);
        judge(path + ".velocity", "its y", body.velocity.y, " m/s", true);
        judge(path + ".angular_velocity", "its angular velocity", body.angular_velocity, " rad/s",
              true);
        judge_dynamics(judge, scene, body, path, dt);
    }
}

} // namespace impulse::harness
