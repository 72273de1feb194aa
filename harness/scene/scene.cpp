// Loading impulse/scene@1 (docs/design.md, "Scene format"): the file, its
// fingerprint, and the names of the solver enums. Each section of the file is
// read by its own scene_*.cpp (scene_reading.h). Every problem becomes one
// InputError naming the file and the JSON path of the first thing wrong, so
// the command-line tool can exit with code 2 and one clear sentence.
#include "scene.h"

#include "atomic_file.h"
#include "input_error.h"
#include "scene_reading.h"
#include "sha256.h"
#include "strict_json.h"

#include <cstddef>
#include <iterator>
#include <string>

namespace impulse::harness {

namespace {

using scene_reading::Json;

// A scene is a few kilobytes; anything near this is a mistake, not a scene.
constexpr std::size_t max_file_bytes = std::size_t{16} * 1024 * 1024;

// Every number as a double, so `3` and `3.0` (the same scene) hash alike.
Json canonical(const Json& value) {
    if (value.is_number()) {
        return Json(value.get<double>());
    }
    if (value.is_array() || value.is_object()) {
        Json out = value;
        for (auto& item : out) {
            item = canonical(item);
        }
        return out;
    }
    return value;
}

// The solver enums' names as scene files and trajectories spell them, in
// each enum's order (solver_settings.h); the sizes are checked against the
// enums' counts so that a new value cannot go without a name.
constexpr const char* integrator_names[] = {"euler", "symplectic-euler", "verlet", "rk4"};
constexpr const char* toi_method_names[] = {"bisection", "secant"};
constexpr const char* contact_mode_names[] = {"single", "simultaneous"};
constexpr const char* vertex_normal_names[] = {"reference-face", "bisector"};
constexpr const char* stepping_names[] = {"world", "local"};
constexpr const char* resting_method_names[] = {"auto", "events", "time-stepping"};
static_assert(std::size(integrator_names) == static_cast<std::size_t>(integrator_count));
static_assert(std::size(toi_method_names) == static_cast<std::size_t>(time_of_impact_method_count));
static_assert(std::size(contact_mode_names) == static_cast<std::size_t>(contact_mode_count));
static_assert(std::size(vertex_normal_names) == static_cast<std::size_t>(vertex_normal_count));
static_assert(std::size(stepping_names) == static_cast<std::size_t>(stepping_count));
static_assert(std::size(resting_method_names) == static_cast<std::size_t>(resting_method_count));

// The name of `value` in its enum's table.
template <class Enum, std::size_t N>
const char* name_in(const char* const (&names)[N], Enum value) {
    const auto index = static_cast<std::size_t>(value);
    return index < N ? names[index] : "unknown";
}

// false, leaving `out` alone, when `name` is none of `names`.
template <class Enum, std::size_t N>
bool enum_from_name(const std::string& name, const char* const (&names)[N], Enum& out) {
    for (std::size_t i = 0; i < N; ++i) {
        if (name == names[i]) {
            out = static_cast<Enum>(i);
            return true;
        }
    }
    return false;
}

} // namespace

Scene load_scene(const std::string& path) {
    return parse_scene(read_file(path, max_file_bytes, "a scene is a few kilobytes"), path);
}

Scene parse_scene(const std::string& text, const std::string& file) {
    const Json document = parse_strict_json<Json>(text, file);
    Scene scene;
    try {
        scene = scene_reading::read_scene(scene_reading::Node(document, ""), file);
    } catch (const json_fields::FieldError& error) {
        // The section readers name the JSON path; the file is named here.
        throw InputError(file, error.path, error.message);
    }
    // Sorted keys and no whitespace: the same content gives the same
    // fingerprint however the file is laid out.
    scene.sha256 = sha256_hex(canonical(document).dump());
    return scene;
}

const char* integrator_name(Integrator integrator) {
    return name_in(integrator_names, integrator);
}
const char* toi_method_name(TimeOfImpactMethod method) {
    return name_in(toi_method_names, method);
}
const char* contact_mode_name(ContactMode mode) {
    return name_in(contact_mode_names, mode);
}
const char* vertex_normal_name(VertexNormal normal) {
    return name_in(vertex_normal_names, normal);
}
const char* stepping_name(Stepping stepping) {
    return name_in(stepping_names, stepping);
}
const char* resting_method_name(RestingMethod method) {
    return name_in(resting_method_names, method);
}

bool integrator_from_name(const std::string& name, Integrator& out) {
    return enum_from_name(name, integrator_names, out);
}
bool toi_method_from_name(const std::string& name, TimeOfImpactMethod& out) {
    return enum_from_name(name, toi_method_names, out);
}
bool contact_mode_from_name(const std::string& name, ContactMode& out) {
    return enum_from_name(name, contact_mode_names, out);
}
bool vertex_normal_from_name(const std::string& name, VertexNormal& out) {
    return enum_from_name(name, vertex_normal_names, out);
}
bool stepping_from_name(const std::string& name, Stepping& out) {
    return enum_from_name(name, stepping_names, out);
}
bool resting_method_from_name(const std::string& name, RestingMethod& out) {
    return enum_from_name(name, resting_method_names, out);
}

} // namespace impulse::harness
