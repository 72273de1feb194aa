// Writing the normalized scene of the engine protocol. The text is built by
// hand rather than through nlohmann's dump() so that every double goes
// through format_double: the shortest text that reads back to the same bits,
// with -0.0 kept.
#include "scene_writer.h"

#include "number_format.h"

#include <nlohmann/json.hpp>

namespace impulse::harness {

namespace {

std::string quoted(const std::string& text) {
    return nlohmann::json(text).dump();
}

std::string vec2_text(Vec2 v) {
    return "[" + format_double(v.x) + ", " + format_double(v.y) + "]";
}

// A box is the loaded shape make_box would build from its half extents, so
// writing it as {"box": [hx, hy]} reads back to the same vertices and normals.
bool is_box(const Shape& shape) {
    if (shape.type != ShapeType::polygon || shape.polygon.count != 4) {
        return false;
    }
    const auto& v = shape.polygon.vertices;
    const double hx = v[2].x;
    const double hy = v[2].y;
    if (!(hx > 0.0) || !(hy > 0.0)) {
        return false;
    }
    const Shape box = make_box(hx, hy);
    for (std::size_t i = 0; i < 4; ++i) {
        if (!(box.polygon.vertices[i] == v[i])) {
            return false;
        }
    }
    return true;
}

std::string shape_text(const Shape& shape) {
    if (shape.type == ShapeType::circle) {
        return "{\"circle\": " + format_double(shape.radius) + "}";
    }
    if (is_box(shape)) {
        const Vec2 corner = shape.polygon.vertices[2];
        return "{\"box\": [" + format_double(corner.x) + ", " + format_double(corner.y) + "]}";
    }
    std::string text = "{\"polygon\": [";
    for (int i = 0; i < shape.polygon.count; ++i) {
        text +=
            (i == 0 ? "" : ", ") + vec2_text(shape.polygon.vertices[static_cast<std::size_t>(i)]);
    }
    return text + "]}";
}

// Every key the body's kind allows, "static" and "rotation" included, so an
// engine reads each one without a default.
std::string body_text(const SceneBody& body) {
    std::string text =
        "{\"name\": " + quoted(body.name) + ", \"static\": " + (body.is_static ? "true" : "false") +
        ", \"shape\": " + shape_text(body.shape) + ", \"position\": " + vec2_text(body.position) +
        ", \"angle\": " + format_double(body.angle);
    if (body.is_static) {
        return text + "}";
    }
    text += ", \"velocity\": " + vec2_text(body.velocity) +
            ", \"angular_velocity\": " + format_double(body.angular_velocity) +
            ", \"mass\": " + format_double(body.mass);
    if (body.rotation) {
        text += ", \"inertia\": " + format_double(body.inertia) + ", \"rotation\": true";
    } else {
        text += ", \"rotation\": false";
    }
    return text + "}";
}

// Every key, defaults included, except resting_method at "auto": it was added
// after the protocol's first release, and a fixed key set (the python-seed
// example engine's) must keep reading every scene that does not ask for more.
std::string solver_text(const SolverSettings& solver) {
    const auto name = [](const char* value) { return quoted(value); };
    const std::string method =
        solver.resting_method == RestingMethod::automatic
            ? ""
            : ", \"resting_method\": " + name(resting_method_name(solver.resting_method));
    return std::string("{") + "\"integrator\": " + name(integrator_name(solver.integrator)) +
           ", \"toi\": " + name(toi_method_name(solver.toi)) +
           ", \"toi_tolerance\": " + format_double(solver.toi_tolerance) +
           ", \"contact_tolerance\": " + format_double(solver.contact_tolerance) +
           ", \"contacts\": " + name(contact_mode_name(solver.contacts)) +
           ", \"stepping\": " + name(stepping_name(solver.stepping)) +
           ", \"vertex_normal\": " + name(vertex_normal_name(solver.vertex_normal)) +
           ", \"ccd\": " + (solver.ccd ? "true" : "false") +
           ", \"resting\": " + (solver.resting ? "true" : "false") + method + "}";
}

} // namespace

std::string write_normalized_scene(const Scene& scene) {
    std::string text = "{\n";
    text += "  \"schema\": " + quoted(scene_schema) + ",\n";
    text += "  \"name\": " + quoted(scene.name) + ",\n";
    text += "  \"gravity\": " + vec2_text(scene.gravity) + ",\n";
    text += "  \"restitution\": " + format_double(scene.restitution) + ",\n";
    text += "  \"dt\": " + format_double(scene.dt) + ",\n";
    text += "  \"duration\": " + format_double(scene.duration) + ",\n";
    text += "  \"solver\": " + solver_text(scene.solver) + ",\n";
    text += "  \"bodies\": [";
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        text += (i == 0 ? "\n    " : ",\n    ") + body_text(scene.bodies[i]);
    }
    return text + "\n  ]\n}\n";
}

} // namespace impulse::harness
