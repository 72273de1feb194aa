// Loading and validating impulse/scene@1 (DESIGN.md, "Scene format").
//
// Every problem becomes one InputError naming the file and the JSON path of the
// first thing wrong, so the command-line tool can exit with code 2 and one
// clear sentence. The reader checks each value's JSON type before reading it:
// no nlohmann exception ever escapes. Checks run in the order the format lists
// its rules, and within a list in document order, so the first problem named is
// the one a person reading the file top to bottom meets first.
#include "scene.h"

#include "atomic_file.h"
#include "body.h"
#include "exact_answers.h"
#include "gas.h"
#include "input_error.h"
#include "manifold.h"
#include "rotation.h"
#include "sha256.h"
#include "strict_json.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <set>
#include <system_error>
#include <utility>
#include <vector>

namespace impulse::harness {

namespace {

// std::map-backed objects: keys sorted, which is what makes dump() canonical
// for the scene's fingerprint.
using Json = nlohmann::json;

// A scene is a few kilobytes; anything near this is a mistake, not a scene.
constexpr std::size_t max_file_bytes = std::size_t{16} * 1024 * 1024;
constexpr std::size_t max_name_length = 64;
constexpr int min_polygon_vertices = 3;
// A polygon whose centroid is further than this fraction of its size from the
// origin is recentred (DESIGN.md: "centroid at the origin or recentred").
constexpr double centroid_tolerance = 1e-9;

// ---------------------------------------------------------------- text

// Shortest text that reads back to the same double (std::to_chars), so a
// value quoted in a message is exactly the value the file holds.
std::string number_text(double value) {
    char buffer[32];
    const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

bool is_ascii_letter_or_digit(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}

// What a value is, for "must be X, got Y": numbers and short strings verbatim,
// containers by kind.
std::string describe(const Json& value) {
    constexpr std::size_t max_shown = 40;
    switch (value.type()) {
    case Json::value_t::null:
        return "null";
    case Json::value_t::boolean:
        return value.get<bool>() ? "true" : "false";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
        return number_text(value.get<double>());
    case Json::value_t::string: {
        std::string text = value.dump();
        if (text.size() > max_shown) {
            // Never cut a UTF-8 sequence in half: the message must stay valid text.
            std::size_t cut = max_shown;
            while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U) {
                --cut;
            }
            text = text.substr(0, cut) + "...\"";
        }
        return text;
    }
    case Json::value_t::array:
        return "an array";
    case Json::value_t::object:
        return "an object";
    default:
        return "an unsupported value";
    }
}

// ---------------------------------------------------------------- the text before JSON

// ---------------------------------------------------------------- reading values

// A value in the document and the JSON path that leads to it: everything a
// message needs to name where a problem is.
class Node {
  public:
    Node(const Json& value, std::string path, const std::string& file)
        : value_(&value), path_(std::move(path)), file_(&file) {}

    const Json& json() const { return *value_; }
    const std::string& path() const { return path_; }
    const std::string& file() const { return *file_; }

    [[noreturn]] void fail(const std::string& message) const {
        throw InputError(*file_, path_, message);
    }

    // Callers have checked that this is an object / array.
    bool has(const std::string& key) const { return value_->contains(key); }
    Node member(const std::string& key) const {
        return Node(value_->at(key), json_member_path(path_, key), *file_);
    }
    Node element(std::size_t index) const {
        return Node(value_->at(index), json_element_path(path_, index), *file_);
    }
    // The path a missing key would have, for "is required".
    std::string path_of(const std::string& key) const { return json_member_path(path_, key); }

  private:
    const Json* value_;
    std::string path_;
    const std::string* file_;
};

void require_object(const Node& node) {
    if (!node.json().is_object()) {
        node.fail("must be an object, got " + describe(node.json()));
    }
}

void require_array(const Node& node) {
    if (!node.json().is_array()) {
        node.fail("must be an array, got " + describe(node.json()));
    }
}

std::optional<Node> optional_member(const Node& object, const std::string& key) {
    if (!object.has(key)) {
        return std::nullopt;
    }
    return object.member(key);
}

Node required_member(const Node& object, const std::string& key) {
    if (!object.has(key)) {
        throw InputError(object.file(), object.path_of(key), "is required but missing");
    }
    return object.member(key);
}

std::string list_of(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names) {
        out += (out.empty() ? "" : ", ") + name;
    }
    return out;
}

// Typos must not pass silently (DESIGN.md): every key must be one the format knows.
void reject_unknown_keys(const Node& object, const std::vector<std::string>& known) {
    for (const auto& [key, value] : object.json().items()) {
        if (std::find(known.begin(), known.end(), key) != known.end()) {
            continue;
        }
        // Suggest the closest known key when it is a plausible typo.
        const std::string closest = closest_known_key(key, known);
        const std::string message =
            closest.empty() ? "unknown key; " : "unknown key (did you mean " + closest + "?); ";
        object.member(key).fail(message + "expected one of " + list_of(known));
    }
}

std::string read_string(const Node& node) {
    if (!node.json().is_string()) {
        node.fail("must be a string, got " + describe(node.json()));
    }
    return node.json().get<std::string>();
}

bool read_bool(const Node& node) {
    if (!node.json().is_boolean()) {
        node.fail("must be true or false, got " + describe(node.json()));
    }
    return node.json().get<bool>();
}

double read_number(const Node& node) {
    if (!node.json().is_number()) {
        node.fail("must be a number, got " + describe(node.json()));
    }
    const double value = node.json().get<double>();
    if (!std::isfinite(value)) {
        node.fail("must be a finite number, got " + number_text(value));
    }
    return value;
}

double read_positive(const Node& node) {
    const double value = read_number(node);
    if (!(value > 0.0)) {
        node.fail("must be > 0, got " + number_text(value));
    }
    return value;
}

// A count: a JSON number with no fractional part (3, or 3.0 written as a
// float), from `low` to `high`.
long long read_whole(const Node& node, long long low, long long high) {
    const double value = read_number(node);
    if (value != std::floor(value) || value < static_cast<double>(low) ||
        value > static_cast<double>(high)) {
        node.fail("must be a whole number from " + std::to_string(low) + " to " +
                  std::to_string(high) + ", got " + number_text(value));
    }
    return static_cast<long long>(value);
}

double read_non_negative(const Node& node) {
    const double value = read_number(node);
    if (!(value >= 0.0)) {
        node.fail("must be >= 0, got " + number_text(value));
    }
    return value;
}

// [x, y]
Vec2 read_vec2(const Node& node) {
    if (!node.json().is_array() || node.json().size() != 2) {
        node.fail("must be an array of two numbers [x, y], got " + describe(node.json()));
    }
    return {read_number(node.element(0)), read_number(node.element(1))};
}

// Optional values with their documented defaults.
std::string read_string_or(const Node& object, const std::string& key, std::string fallback) {
    const std::optional<Node> node = optional_member(object, key);
    return node ? read_string(*node) : fallback;
}
bool read_bool_or(const Node& object, const std::string& key, bool fallback) {
    const std::optional<Node> node = optional_member(object, key);
    return node ? read_bool(*node) : fallback;
}
double read_number_or(const Node& object, const std::string& key, double fallback) {
    const std::optional<Node> node = optional_member(object, key);
    return node ? read_number(*node) : fallback;
}
double read_positive_or(const Node& object, const std::string& key, double fallback) {
    const std::optional<Node> node = optional_member(object, key);
    return node ? read_positive(*node) : fallback;
}
Vec2 read_vec2_or(const Node& object, const std::string& key, Vec2 fallback) {
    const std::optional<Node> node = optional_member(object, key);
    return node ? read_vec2(*node) : fallback;
}

// ---------------------------------------------------------------- the scene's fields

// Scene and body names become file names (goldens/NAME.json) and column
// prefixes (NAME.x), so they are kept to characters that cannot leave the
// goldens folder or break a column name: no slash, no leading dot.
bool is_valid_name(const std::string& name) {
    if (name.empty() || name.size() > max_name_length || !is_ascii_letter_or_digit(name[0])) {
        return false;
    }
    return std::all_of(name.begin(), name.end(), [](char c) {
        return is_ascii_letter_or_digit(c) || c == '.' || c == '_' || c == '-';
    });
}

std::string read_name(const Node& node) {
    const std::string name = read_string(node);
    if (!is_valid_name(name)) {
        node.fail("must be 1 to 64 letters, digits, '.', '_' or '-', starting with a letter or "
                  "digit, got " +
                  describe(node.json()));
    }
    return name;
}

void read_schema(const Node& root) {
    const std::string wanted = scene_schema;
    if (!root.has("schema")) {
        throw InputError(root.file(), "schema",
                         "is required but missing; a scene file declares \"schema\": \"" + wanted +
                             "\"");
    }
    const Node node = root.member("schema");
    if (node.json().is_string()) {
        const std::string schema = node.json().get<std::string>();
        if (schema == wanted) {
            return;
        }
        const std::string family = "impulse/scene@";
        if (schema.rfind(family, 0) == 0) {
            node.fail("unsupported scene version " + describe(node.json()) +
                      "; this build reads \"" + wanted + "\"");
        }
    }
    node.fail("not a scene: expected \"" + wanted + "\", got " + describe(node.json()));
}

double read_restitution(const Node& root) {
    const double e = read_number_or(root, "restitution", 1.0);
    if (e < 0.0 || e > 1.0) {
        root.member("restitution").fail("must be between 0 and 1, got " + number_text(e));
    }
    return e;
}

// duration / dt, in double so that an absurd ratio is reported rather than
// overflowing a long long (see step_count in scene.h for the rounding).
double steps_for(double duration, double dt) {
    const double ratio = duration / dt;
    const double nearest = std::round(ratio);
    return std::abs(ratio - nearest) <= 1e-9 ? nearest : std::ceil(ratio);
}

void read_time(const Node& root, Scene& scene) {
    scene.dt = read_positive(required_member(root, "dt"));
    const Node duration = required_member(root, "duration");
    scene.duration = read_positive(duration);
    if (scene.duration < scene.dt) {
        duration.fail("must be >= dt (" + number_text(scene.dt) + "), got " +
                      number_text(scene.duration));
    }
    const double steps = steps_for(scene.duration, scene.dt);
    if (steps > static_cast<double>(max_steps)) {
        // Whole numbers of steps below 2^53 are written as integers ("100000000",
        // not "1e+08"); beyond that the double's shortest form is all there is.
        const bool exact = steps < 9007199254740992.0;
        const std::string count =
            exact ? std::to_string(static_cast<long long>(steps)) : number_text(steps);
        duration.fail("duration / dt gives " + count + " steps; at most " +
                      std::to_string(max_steps) + " are allowed");
    }
}

void read_solver(const Node& node, SolverSettings& solver) {
    require_object(node);
    reject_unknown_keys(node, {"integrator", "toi", "toi_tolerance", "contact_tolerance",
                               "contacts", "stepping", "vertex_normal", "ccd", "resting"});
    if (const std::optional<Node> integrator = optional_member(node, "integrator")) {
        if (!integrator->json().is_string() ||
            !integrator_from_name(integrator->json().get<std::string>(), solver.integrator)) {
            integrator->fail(
                "must be one of \"euler\", \"symplectic-euler\", \"verlet\", \"rk4\", got " +
                describe(integrator->json()));
        }
    }
    if (const std::optional<Node> toi = optional_member(node, "toi")) {
        if (!toi->json().is_string() ||
            !toi_method_from_name(toi->json().get<std::string>(), solver.toi)) {
            toi->fail("must be \"bisection\" (the seed's) or \"secant\", got " +
                      describe(toi->json()));
        }
    }
    solver.toi_tolerance = read_positive_or(node, "toi_tolerance", solver.toi_tolerance);
    solver.contact_tolerance =
        read_positive_or(node, "contact_tolerance", solver.contact_tolerance);
    if (const std::optional<Node> stepping = optional_member(node, "stepping")) {
        if (!stepping->json().is_string() ||
            !stepping_from_name(stepping->json().get<std::string>(), solver.stepping)) {
            stepping->fail("must be \"world\" (the seed's) or \"local\", got " +
                           describe(stepping->json()));
        }
    }
    // Local stepping resolves one pair at a time by design; the modes below
    // look at every touching pair or every pair's whole motion at once.
    const auto refuse_with_local = [&](const Node& setting) {
        if (solver.stepping == Stepping::local) {
            setting.fail("is not available with \"stepping\": \"local\" in this version (local "
                         "stepping looks at one pair at a time); use \"stepping\": \"world\"");
        }
    };
    if (const std::optional<Node> contacts = optional_member(node, "contacts")) {
        if (!contacts->json().is_string() ||
            !contact_mode_from_name(contacts->json().get<std::string>(), solver.contacts)) {
            contacts->fail("must be \"single\" (the seed's) or \"simultaneous\", got " +
                           describe(contacts->json()));
        }
        if (solver.contacts != ContactMode::single) {
            refuse_with_local(*contacts);
        }
    }
    if (const std::optional<Node> normal = optional_member(node, "vertex_normal")) {
        if (!normal->json().is_string() ||
            !vertex_normal_from_name(normal->json().get<std::string>(), solver.vertex_normal)) {
            normal->fail("must be \"reference-face\" (the seed's) or \"bisector\", got " +
                         describe(normal->json()));
        }
    }
    solver.ccd = read_bool_or(node, "ccd", solver.ccd);
    if (solver.ccd) {
        refuse_with_local(*optional_member(node, "ccd"));
    }
    solver.resting = read_bool_or(node, "resting", solver.resting);
    if (solver.resting) {
        refuse_with_local(*optional_member(node, "resting"));
    }
}

// ---------------------------------------------------------------- shapes

Shape read_box(const Node& node) {
    if (!node.json().is_array() || node.json().size() != 2) {
        node.fail("must be the half extents [hx, hy], got " + describe(node.json()));
    }
    // In document order: a function's arguments are evaluated in no fixed order.
    const double hx = read_positive(node.element(0));
    const double hy = read_positive(node.element(1));
    return make_box(hx, hy);
}

// make_polygon assumes a convex counter-clockwise outline traced once; these
// checks are what make that assumption true.
void require_distinct_neighbours(const Node& node, const std::vector<Vec2>& v) {
    const std::size_t n = v.size();
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t previous = (i + n - 1) % n;
        if (v[i] == v[previous]) {
            node.element(i).fail("repeats vertex " + std::to_string(previous) +
                                 "; consecutive vertices must differ");
        }
    }
}

double twice_area(const std::vector<Vec2>& v) {
    double sum = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        sum += cross(v[i], v[(i + 1) % v.size()]);
    }
    return sum;
}

void require_counter_clockwise(const Node& node, const std::vector<Vec2>& v) {
    const double area = 0.5 * twice_area(v);
    if (!(area > 0.0)) {
        node.fail("vertices must be counter-clockwise (positive area), got area " +
                  number_text(area));
    }
}

// Every corner turns left: cross(edge in, edge out) > 0. Zero (collinear) and
// negative (reflex) are both refused: a collinear vertex gives a zero-length
// normal pair that the contact code would treat as two faces.
void require_left_turns(const Node& node, const std::vector<Vec2>& v) {
    const std::size_t n = v.size();
    for (std::size_t i = 0; i < n; ++i) {
        const double turn = twice_signed_area(v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
        if (turn == 0.0) {
            node.element(i).fail("is collinear with its neighbours; the polygon must be "
                                 "strictly convex");
        }
        if (turn < 0.0) {
            node.element(i).fail("is a reflex corner (turns right); the polygon must be convex "
                                 "with counter-clockwise vertices");
        }
    }
}

// Left turns everywhere still allow a star that winds round twice; a convex
// outline traced once has every vertex on the inner side of every edge.
void require_simple(const Node& node, const std::vector<Vec2>& v) {
    const std::size_t n = v.size();
    for (std::size_t edge = 0; edge < n; ++edge) {
        const Vec2 a = v[edge];
        const Vec2 b = v[(edge + 1) % n];
        for (std::size_t k = 0; k < n; ++k) {
            if (k != edge && k != (edge + 1) % n && !(twice_signed_area(a, b, v[k]) > 0.0)) {
                node.fail("winds around more than once (the outline crosses itself); a convex "
                          "polygon's vertices go round once");
            }
        }
    }
}

Shape read_polygon(const Node& node) {
    require_array(node);
    const std::size_t n = node.json().size();
    if (n < static_cast<std::size_t>(min_polygon_vertices) ||
        n > static_cast<std::size_t>(max_polygon_vertices)) {
        node.fail("must have " + std::to_string(min_polygon_vertices) + " to " +
                  std::to_string(max_polygon_vertices) + " vertices, got " + std::to_string(n));
    }
    std::vector<Vec2> vertices;
    for (std::size_t i = 0; i < n; ++i) {
        vertices.push_back(read_vec2(node.element(i)));
    }
    require_distinct_neighbours(node, vertices);
    require_counter_clockwise(node, vertices);
    require_left_turns(node, vertices);
    require_simple(node, vertices);
    return make_polygon(vertices.data(), static_cast<int>(n));
}

Shape read_shape(const Node& node) {
    require_object(node);
    const std::vector<std::string> kinds = {"box", "circle", "polygon"};
    reject_unknown_keys(node, kinds);
    std::optional<std::string> kind;
    for (const std::string& candidate : kinds) {
        if (!node.has(candidate)) {
            continue;
        }
        if (kind) {
            node.member(candidate).fail("a shape is exactly one of box, circle or polygon; this "
                                        "one also has " +
                                        *kind);
        }
        kind = candidate;
    }
    if (!kind) {
        node.fail("must have one of box, circle or polygon");
    }
    const Node value = node.member(*kind);
    if (*kind == "box") {
        return read_box(value);
    }
    if (*kind == "circle") {
        return make_circle(read_positive(value));
    }
    return read_polygon(value);
}

// Moves a polygon's vertices by minus its centroid; returns the centroid when
// it was off the origin (by more than centroid_tolerance of the size).
std::optional<Vec2> recentre_on_centroid(Shape& shape) {
    if (shape.type != ShapeType::polygon) {
        return std::nullopt;
    }
    const Polygon& polygon = shape.polygon;
    double size = 0.0;
    for (int i = 0; i < polygon.count; ++i) {
        size = std::max(size, length(polygon.vertices[static_cast<std::size_t>(i)]));
    }
    const Vec2 centroid = mass_properties(shape).centroid;
    if (!(length(centroid) > centroid_tolerance * size)) {
        return std::nullopt;
    }
    std::vector<Vec2> moved;
    for (int i = 0; i < polygon.count; ++i) {
        moved.push_back(polygon.vertices[static_cast<std::size_t>(i)] - centroid);
    }
    shape = make_polygon(moved.data(), polygon.count);
    return centroid;
}

std::string centroid_warning(const std::string& file, const std::string& shape_path, Vec2 centroid,
                             const std::string& consequence) {
    return file + ": " + shape_path + ".polygon: centroid is at (" + number_text(centroid.x) +
           ", " + number_text(centroid.y) + "), not at the origin; " + consequence;
}

// The engine puts a body's centre of mass at its shape's origin. A polygon
// given around some other point is moved so its centroid is the origin, and
// the body's position moved by the same offset (turned by the body's angle) so
// every vertex stays where the file put it in the world.
void recentre_polygon(SceneBody& body, const std::string& shape_path, const std::string& file,
                      std::vector<std::string>& warnings) {
    if (const std::optional<Vec2> centroid = recentre_on_centroid(body.shape)) {
        body.position += rotate(rotation_of(body.angle), *centroid);
        warnings.push_back(
            centroid_warning(file, shape_path, *centroid,
                             "vertices recentred and position moved to keep the body in place"));
    }
}

// ---------------------------------------------------------------- bodies

const std::vector<std::string> body_keys = {
    "name", "static",  "shape",   "position", "angle", "velocity", "angular_velocity",
    "mass", "density", "inertia", "rotation"};

// A static body has infinite mass and never moves, so anything describing its
// mass or motion would be ignored; saying so beats ignoring it.
void reject_motion_of_static_body(const Node& node) {
    for (const char* key :
         {"velocity", "angular_velocity", "mass", "density", "inertia", "rotation"}) {
        if (node.has(key)) {
            node.member(key).fail(std::string("a static body has infinite mass and does not "
                                              "move; remove ") +
                                  key);
        }
    }
}

// What the file says about a dynamic body's mass; resolved against the shape
// once the shape is final.
struct MassSpec {
    std::optional<double> mass;
    std::optional<double> density;
    std::optional<double> inertia;
};

MassSpec read_dynamics(const Node& node, SceneBody& body) {
    body.velocity = read_vec2_or(node, "velocity", {});
    body.angular_velocity = read_number_or(node, "angular_velocity", 0.0);
    MassSpec spec;
    if (const std::optional<Node> mass = optional_member(node, "mass")) {
        spec.mass = read_positive(*mass);
    }
    if (const std::optional<Node> density = optional_member(node, "density")) {
        spec.density = read_positive(*density);
        if (spec.mass) {
            density->fail("give mass or density, not both");
        }
    }
    body.rotation = read_bool_or(node, "rotation", true);
    if (const std::optional<Node> inertia = optional_member(node, "inertia")) {
        if (!body.rotation) {
            inertia->fail("a body with \"rotation\": false has infinite inertia; remove inertia");
        }
        spec.inertia = read_positive(*inertia);
    }
    if (!body.rotation && body.angular_velocity != 0.0) {
        node.member("angular_velocity")
            .fail("must be 0 for a body with \"rotation\": false, got " +
                  number_text(body.angular_velocity));
    }
    return spec;
}

void resolve_mass(const Node& node, const MassSpec& spec, SceneBody& body) {
    const MassProperties shape = mass_properties(body.shape);
    // A body that gives neither mass nor density has density 1 (kg per square
    // metre), so the simplest scene needs no mass at all.
    body.mass = spec.mass ? *spec.mass : spec.density.value_or(1.0) * shape.area;
    if (!std::isfinite(body.mass) || !(body.mass > 0.0)) {
        node.fail("its shape and density give a mass of " + number_text(body.mass) +
                  " kg; it must be finite and > 0");
    }
    if (!body.rotation) {
        body.inertia = 0.0; // infinite: SceneBody::rotation says so
        return;
    }
    body.inertia = spec.inertia ? *spec.inertia : body.mass * shape.inertia_per_unit_mass;
    if (!std::isfinite(body.inertia) || !(body.inertia > 0.0)) {
        node.fail("its shape and mass give a moment of inertia of " + number_text(body.inertia) +
                  " kg m^2; it must be finite and > 0");
    }
}

// Every body name read so far and its index: a lookup, so that a long list of
// bodies loads in O(N log N).
using NameIndex = std::map<std::string, std::size_t>;

// Reads bodies[i]; `names` holds the bodies before it (for unique names) and
// `scene` collects warnings.
SceneBody read_body(const Node& node, Scene& scene, NameIndex& names) {
    require_object(node);
    reject_unknown_keys(node, body_keys);
    SceneBody body;
    const Node name = required_member(node, "name");
    body.name = read_name(name);
    const auto [previous, fresh] = names.emplace(body.name, names.size());
    if (!fresh) {
        name.fail("\"" + body.name + "\" is already the name of bodies[" +
                  std::to_string(previous->second) + "]; body names must be unique");
    }
    body.is_static = read_bool_or(node, "static", false);
    const Node shape = required_member(node, "shape");
    body.shape = read_shape(shape);
    body.position = read_vec2_or(node, "position", {});
    body.angle = read_number_or(node, "angle", 0.0);
    MassSpec mass;
    if (body.is_static) {
        reject_motion_of_static_body(node);
    } else {
        mass = read_dynamics(node, body);
    }
    recentre_polygon(body, shape.path(), scene.file, scene.warnings);
    if (!body.is_static) {
        resolve_mass(node, mass, body);
    }
    return body;
}

BodyState initial_state(const SceneBody& body) {
    BodyState state;
    state.position = body.position;
    state.angle = body.angle;
    return state;
}

// The file's "bodies" array; with a gas block it may be empty or left out.
void read_listed_bodies(const Node& node, Scene& scene, bool has_gas, NameIndex& names) {
    require_array(node);
    if (node.json().empty() && !has_gas) {
        node.fail("must list at least one body");
    }
    for (std::size_t i = 0; i < node.json().size(); ++i) {
        scene.bodies.push_back(read_body(node.element(i), scene, names));
    }
    scene.listed_bodies = scene.bodies.size();
    const bool all_static = std::all_of(scene.bodies.begin(), scene.bodies.end(),
                                        [](const SceneBody& body) { return body.is_static; });
    if (all_static && !has_gas) {
        node.fail("every body is static, so nothing would move; at least one body must be "
                  "dynamic");
    }
}

// ---------------------------------------------------------------- the gas block

// Far more than a scale scene needs; a bound keeps a typo from asking for a
// billion bodies.
constexpr long long max_gas_count = 100000;
// 2^53: the largest whole number a JSON reader is sure to hold exactly.
constexpr long long max_gas_seed = 9007199254740992;

const std::vector<std::string> gas_keys = {"count",
                                           "shape",
                                           "mass",
                                           "density",
                                           "spacing",
                                           "max_speed",
                                           "max_angular_speed",
                                           "random_angles",
                                           "seed",
                                           "wall_thickness"};

// Whether `name` is one the gas block gives a body: a wall's, or gas-N with
// N < count written without leading zeros.
bool is_gas_name(const std::string& name, int count) {
    for (const char* wall : {"wall-bottom", "wall-top", "wall-left", "wall-right"}) {
        if (name == wall) {
            return true;
        }
    }
    const std::string prefix = "gas-";
    if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size() ||
        name.size() > prefix.size() + 6) {
        return false;
    }
    const std::string digits = name.substr(prefix.size());
    if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) ||
        (digits.size() > 1 && digits[0] == '0')) {
        return false;
    }
    return std::stol(digits) < count;
}

// The gas's mass and inertia, from mass or density (default 1) as for a body.
void read_gas_mass(const Node& node, GasSpec& gas) {
    const MassProperties shape = mass_properties(gas.shape);
    std::optional<double> mass;
    if (const std::optional<Node> given = optional_member(node, "mass")) {
        mass = read_positive(*given);
    }
    double density = 1.0;
    if (const std::optional<Node> given = optional_member(node, "density")) {
        density = read_positive(*given);
        if (mass) {
            given->fail("give mass or density, not both");
        }
    }
    gas.mass = mass ? *mass : density * shape.area;
    if (!std::isfinite(gas.mass) || !(gas.mass > 0.0)) {
        node.fail("its shape and density give each body a mass of " + number_text(gas.mass) +
                  " kg; it must be finite and > 0");
    }
    gas.inertia = gas.mass * shape.inertia_per_unit_mass;
    if (!std::isfinite(gas.inertia) || !(gas.inertia > 0.0)) {
        node.fail("its shape and mass give each body a moment of inertia of " +
                  number_text(gas.inertia) + " kg m^2; it must be finite and > 0");
    }
}

// "gas": reads and validates the block, then appends its walls and bodies
// (gas.h) after the listed ones. The names it gives must not be taken.
void read_gas(const Node& node, Scene& scene) {
    require_object(node);
    reject_unknown_keys(node, gas_keys);
    GasSpec gas;
    gas.count = static_cast<int>(read_whole(required_member(node, "count"), 1, max_gas_count));
    const Node shape = required_member(node, "shape");
    gas.shape = read_shape(shape);
    // Each body's centre of mass sits on its site, so there is no position to
    // move: only the vertices are recentred.
    if (const std::optional<Vec2> centroid = recentre_on_centroid(gas.shape)) {
        scene.warnings.push_back(centroid_warning(
            scene.file, shape.path(), *centroid,
            "vertices recentred; each gas body's centroid sits on its lattice site"));
    }
    read_gas_mass(node, gas);
    const Node spacing = required_member(node, "spacing");
    gas.spacing = read_positive(spacing);
    // Closer sites could let two bodies overlap at some angles; the room is
    // checked for overlaps below, but this says what to change.
    const double diameter = bounding_diameter(gas.shape);
    if (!(gas.spacing > diameter)) {
        spacing.fail("must be more than the shape's bounding diameter " + number_text(diameter) +
                     " m (twice its furthest point from the centroid), so that no two bodies "
                     "overlap at any angle, got " +
                     number_text(gas.spacing));
    }
    gas.max_speed = read_non_negative(required_member(node, "max_speed"));
    if (const std::optional<Node> given = optional_member(node, "max_angular_speed")) {
        gas.max_angular_speed = read_non_negative(*given);
    }
    gas.random_angles = read_bool_or(node, "random_angles", false);
    if (const std::optional<Node> given = optional_member(node, "seed")) {
        gas.seed = static_cast<std::uint64_t>(read_whole(*given, 0, max_gas_seed));
    }
    gas.wall_thickness = read_positive_or(node, "wall_thickness", gas.wall_thickness);
    const double side = static_cast<double>(gas_lattice_side(gas.count)) * gas.spacing;
    if (!std::isfinite(side)) {
        spacing.fail("gives a room " + number_text(side) + " m wide; it must be finite");
    }
    if (!std::isfinite(side + 2.0 * gas.wall_thickness)) {
        node.member("wall_thickness")
            .fail("gives a room " + number_text(side + 2.0 * gas.wall_thickness) +
                  " m wide with its walls; it must be finite");
    }
    for (std::size_t i = 0; i < scene.listed_bodies; ++i) {
        if (is_gas_name(scene.bodies[i].name, gas.count)) {
            node.fail("makes a body named \"" + scene.bodies[i].name +
                      "\", which is already the name of bodies[" + std::to_string(i) +
                      "]; body names must be unique (the gas block's are wall-bottom, wall-top, "
                      "wall-left, wall-right and gas-0 to gas-" +
                      std::to_string(gas.count - 1) + ")");
        }
    }
    std::vector<SceneBody> made = generate_gas(gas);
    scene.bodies.insert(scene.bodies.end(), std::make_move_iterator(made.begin()),
                        std::make_move_iterator(made.end()));
    scene.gas = gas;
}

// ---------------------------------------------------------------- overlaps at t = 0

// A body's bounding box at t = 0, from the same world vertices the narrow
// phase computes, widened by a hair (see reject_initial_overlaps).
struct Extent {
    double lo_x = 0.0, hi_x = 0.0, lo_y = 0.0, hi_y = 0.0;
};

Extent extent_of(const SceneBody& body, const Transform& xf) {
    Extent e;
    if (body.shape.type == ShapeType::circle) {
        const double r = body.shape.radius;
        e = {xf.p.x - r, xf.p.x + r, xf.p.y - r, xf.p.y + r};
    } else {
        const Polygon& polygon = body.shape.polygon;
        const Vec2 first = apply(xf, polygon.vertices[0]);
        e = {first.x, first.x, first.y, first.y};
        for (int i = 1; i < polygon.count; ++i) {
            const Vec2 v = apply(xf, polygon.vertices[static_cast<std::size_t>(i)]);
            e = {std::min(e.lo_x, v.x), std::max(e.hi_x, v.x), std::min(e.lo_y, v.y),
                 std::max(e.hi_y, v.y)};
        }
    }
    const double slack =
        1e-9 * (std::max(e.hi_x - e.lo_x, e.hi_y - e.lo_y) + std::abs(xf.p.x) + std::abs(xf.p.y));
    return {e.lo_x - slack, e.hi_x + slack, e.lo_y - slack, e.hi_y + slack};
}

// The JSON path a problem with scene body `index` is reported at: its entry in
// "bodies", or the gas block that made it.
std::string body_path(const Scene& scene, std::size_t index) {
    return index < scene.listed_bodies ? json_element_path("bodies", index) : std::string("gas");
}

std::string body_reference(const Scene& scene, std::size_t index) {
    const std::string name = "'" + scene.bodies[index].name + "'";
    return index < scene.listed_bodies ? "bodies[" + std::to_string(index) + "] " + name
                                       : name + " of the gas block";
}

// The engine resolves collisions as they happen; bodies already interpenetrating
// at t = 0 have no collision time, so the run would be meaningless. Touching is
// fine. Static bodies may overlap one another (walls meeting in a corner).
//
// The pair reported is the one the plain double loop over (j, i < j) meets
// first: the smallest j, then the smallest i, at bodies[j]. Testing every pair
// is O(N^2), too slow for a gas of 10,000; instead the bodies are swept in
// order of their bounding boxes' left edges and only pairs whose boxes meet
// are tested, each with the same call (same argument order, same bits) as the
// double loop would make. Every overlap found is a candidate and the least
// (j, i) wins, so the sweep's order never decides which pair is named. The
// boxes are widened by 1e-9 of their size and position so that a pair whose
// computed gap is negative only by rounding is still tested, as before.
void reject_initial_overlaps(const Scene& scene) {
    const std::vector<SceneBody>& bodies = scene.bodies;
    std::vector<Transform> transforms;
    std::vector<Extent> extents;
    transforms.reserve(bodies.size());
    extents.reserve(bodies.size());
    for (const SceneBody& body : bodies) {
        transforms.push_back(transform_of(initial_state(body)));
        extents.push_back(extent_of(body, transforms.back()));
    }
    std::vector<std::size_t> order(bodies.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return extents[a].lo_x < extents[b].lo_x || (extents[a].lo_x == extents[b].lo_x && a < b);
    });
    struct Overlap {
        std::size_t j = 0, i = 0;
        double gap = 0.0;
    };
    std::optional<Overlap> first;
    std::vector<std::size_t> active; // boxes that may still reach the next one's left edge
    for (const std::size_t p : order) {
        const Extent& e = extents[p];
        active.erase(std::remove_if(active.begin(), active.end(),
                                    [&](std::size_t q) { return extents[q].hi_x < e.lo_x; }),
                     active.end());
        for (const std::size_t q : active) {
            const Extent& f = extents[q];
            if (f.hi_y < e.lo_y || e.hi_y < f.lo_y) {
                continue;
            }
            const std::size_t j = std::max(p, q);
            const std::size_t i = std::min(p, q);
            if ((bodies[i].is_static && bodies[j].is_static) ||
                (first && (j > first->j || (j == first->j && i > first->i)))) {
                continue;
            }
            const double gap =
                separation(bodies[i].shape, transforms[i], bodies[j].shape, transforms[j]);
            if (gap < 0.0) {
                first = Overlap{j, i, gap};
            }
        }
        active.push_back(p);
    }
    if (first) {
        throw InputError(scene.file, body_path(scene, first->j),
                         "'" + bodies[first->j].name + "' overlaps " +
                             body_reference(scene, first->i) + " at t = 0 by " +
                             number_text(-first->gap) + " m");
    }
}

// "bodies" and "gas": the listed bodies, then the gas block's.
void read_bodies(const Node& root, Scene& scene) {
    const std::optional<Node> listed = optional_member(root, "bodies");
    const std::optional<Node> gas = optional_member(root, "gas");
    if (!listed && !gas) {
        throw InputError(root.file(), "bodies",
                         "is required but missing; a scene lists its bodies, has a gas block, "
                         "or both");
    }
    NameIndex names;
    if (listed) {
        read_listed_bodies(*listed, scene, gas.has_value(), names);
    }
    if (gas) {
        read_gas(*gas, scene);
    }
    reject_initial_overlaps(scene);
}

// ---------------------------------------------------------------- tolerances

// ULP distances are counted in a uint64_t; 2^53 is the largest whole number a
// JSON reader is sure to hold exactly, and far more than any useful bound.
constexpr long long max_ulp = 9007199254740992;

ChannelTolerance read_channel_tolerance(const Node& node) {
    require_object(node);
    reject_unknown_keys(node, {"atol", "rtol", "ulp"});
    // No silent defaults (DESIGN.md): a channel named must say how close is close.
    if (!node.has("atol") && !node.has("rtol") && !node.has("ulp")) {
        node.fail("must give at least one of atol, rtol or ulp; a tolerance has no defaults");
    }
    ChannelTolerance tolerance;
    if (const std::optional<Node> atol = optional_member(node, "atol")) {
        tolerance.atol = read_non_negative(*atol);
    }
    if (const std::optional<Node> rtol = optional_member(node, "rtol")) {
        tolerance.rtol = read_non_negative(*rtol);
    }
    if (const std::optional<Node> ulp = optional_member(node, "ulp")) {
        tolerance.ulp = static_cast<std::uint64_t>(read_whole(*ulp, 0, max_ulp));
    }
    return tolerance;
}

// "tolerance": {"position": {"atol": 1e-9}, ...}; channels not named stay
// empty, so comparing them in tolerance mode is refused rather than guessed.
void read_tolerances(const Node& node, Tolerances& tolerances) {
    require_object(node);
    reject_unknown_keys(node, std::vector<std::string>(channel_names.begin(), channel_names.end()));
    for (int c = 0; c < channel_count; ++c) {
        const std::string name = channel_names[static_cast<std::size_t>(c)];
        if (const std::optional<Node> channel = optional_member(node, name)) {
            tolerances[static_cast<Channel>(c)] = read_channel_tolerance(*channel);
        }
    }
}

// ---------------------------------------------------------------- expectations

// A gas has thousands of bodies: a message lists this many names at most.
constexpr std::size_t max_names_listed = 20;

// The index of the body a string value names.
std::size_t read_body_reference(const Node& node, const Scene& scene) {
    const std::string name = read_string(node);
    std::vector<std::string> names;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        if (scene.bodies[i].name == name) {
            return i;
        }
        if (names.size() < max_names_listed) {
            names.push_back(scene.bodies[i].name);
        }
    }
    const std::size_t more = scene.bodies.size() - names.size();
    node.fail("no body is named " + describe(node.json()) + "; the bodies are " + list_of(names) +
              (more > 0 ? " and " + std::to_string(more) + " more" : ""));
}

// Static bodies have no columns in a trajectory and no motion to check.
std::size_t read_dynamic_body_reference(const Node& node, const Scene& scene,
                                        const std::string& needs) {
    const std::size_t index = read_body_reference(node, scene);
    if (scene.bodies[index].is_static) {
        node.fail("'" + scene.bodies[index].name + "' is static; " + needs +
                  " needs a dynamic body");
    }
    return index;
}

// A formula that does not apply to the scene (exact_answers.h) is refused at
// the key its refusal blames: the entry, its body or its other body.
void reject_refusal(const std::optional<Refusal>& refusal, const Node& entry, const Node& body,
                    const Node* other = nullptr) {
    if (!refusal) {
        return;
    }
    switch (refusal->where) {
    case Refusal::Where::entry:
        entry.fail(refusal->message);
    case Refusal::Where::body:
        body.fail(refusal->message);
    case Refusal::Where::other:
        (other ? *other : entry).fail(refusal->message);
    }
}

// PHYSICS.md, drop: "no rotation", released at rest.
void validate_drop(const Node& node, const Scene& scene, Expectation& expectation) {
    const std::string formula = "the drop formula";
    const Node body_node = required_member(node, "body");
    const std::size_t body = read_dynamic_body_reference(body_node, scene, formula);
    expectation.body = scene.bodies[body].name;
    expectation.impacts = static_cast<int>(read_whole(required_member(node, "impacts"), 1, 10000));
    reject_refusal(drop_refusal(scene, scene.bodies[body], formula), node, body_node);
}

// PHYSICS.md, single-corner impact: a rotating polygon, not spinning, falling
// onto static ground on exactly one corner.
void validate_corner_impact(const Node& node, const Scene& scene, Expectation& expectation) {
    const std::string formula = "the corner-impact formula";
    const Node body_node = required_member(node, "body");
    const std::size_t body = read_dynamic_body_reference(body_node, scene, formula);
    expectation.body = scene.bodies[body].name;
    reject_refusal(corner_impact_refusal(scene, scene.bodies[body], formula), node, body_node);
}

// PHYSICS.md, head-on: 1D, no rotation, free space.
void validate_head_on(const Node& node, const Scene& scene, Expectation& expectation) {
    const std::string formula = "the head-on formula";
    const Node a_node = required_member(node, "a");
    const Node b_node = required_member(node, "b");
    const SceneBody& a = scene.bodies[read_dynamic_body_reference(a_node, scene, formula)];
    const SceneBody& b = scene.bodies[read_dynamic_body_reference(b_node, scene, formula)];
    reject_refusal(head_on_refusal(scene, a, b, formula), node, a_node, &b_node);
    expectation.body = a.name;
    expectation.other = b.name;
}

const std::vector<std::string> conserved_quantities = {"momentum", "angular_momentum", "energy"};

// PHYSICS.md: "Frictionless contact in free space conserves linear momentum
// exactly and angular momentum about any fixed point; with e = 1 it conserves
// kinetic energy".
void require_conserved(const Node& node, const Scene& scene, const std::string& quantity) {
    if (const std::optional<std::string> refusal = conservation_refusal(scene, quantity)) {
        node.fail(*refusal + (quantity == "energy" ? "; use energy-non-increasing" : ""));
    }
}

void validate_conserved(const Node& node, const Scene& scene, Expectation& expectation) {
    const Node list = required_member(node, "quantities");
    require_array(list);
    if (list.json().empty()) {
        list.fail("must name at least one of " + list_of(conserved_quantities));
    }
    for (std::size_t i = 0; i < list.json().size(); ++i) {
        const Node item = list.element(i);
        const bool known = item.json().is_string() &&
                           std::find(conserved_quantities.begin(), conserved_quantities.end(),
                                     item.json().get<std::string>()) != conserved_quantities.end();
        if (!known) {
            item.fail("must be one of " + list_of(conserved_quantities) + ", got " +
                      describe(item.json()));
        }
        const std::string quantity = item.json().get<std::string>();
        const auto previous =
            std::find(expectation.quantities.begin(), expectation.quantities.end(), quantity);
        if (previous != expectation.quantities.end()) {
            item.fail("repeats quantities[" +
                      std::to_string(previous - expectation.quantities.begin()) +
                      "]; each quantity is checked once");
        }
        require_conserved(item, scene, quantity);
        expectation.quantities.push_back(quantity);
    }
}

// A gas in a closed room: the walls change the total momentum, by exactly the
// impulses they give. Gravity would add m g t on top, which this check does not
// model.
void validate_momentum_balance(const Node& node, const Scene& scene, Expectation&) {
    if (scene.gravity != Vec2{}) {
        node.fail("momentum-balance needs zero gravity, but the scene's gravity is (" +
                  number_text(scene.gravity.x) + ", " + number_text(scene.gravity.y) +
                  "); gravity would add m g t to the momentum, which the balance of impulses "
                  "does not account for");
    }
}

// Literal values, read in the order they are listed, so a report lists them so.
void read_literal_values(const Node& node, const std::vector<std::string>& scalars,
                         const std::vector<std::string>& pairs, Expectation& expectation) {
    for (const std::string& key : scalars) {
        if (const std::optional<Node> value = optional_member(node, key)) {
            expectation.values.emplace_back(key, read_number(*value));
        }
    }
    for (const std::string& key : pairs) {
        if (const std::optional<Node> value = optional_member(node, key)) {
            const Vec2 v = read_vec2(*value);
            expectation.values.emplace_back(key + ".x", v.x);
            expectation.values.emplace_back(key + ".y", v.y);
        }
    }
}

// The largest event index accepted: far more than any run records.
constexpr long long max_event_index = 1'000'000'000;

void validate_event(const Node& node, const Scene& scene, Expectation& expectation) {
    expectation.index =
        static_cast<std::size_t>(read_whole(required_member(node, "index"), 0, max_event_index));
    if (const std::optional<Node> a = optional_member(node, "a")) {
        expectation.body = scene.bodies[read_body_reference(*a, scene)].name;
    }
    if (const std::optional<Node> b = optional_member(node, "b")) {
        expectation.other = scene.bodies[read_body_reference(*b, scene)].name;
    }
    read_literal_values(node, {"t", "impulse", "vn_before", "vn_after"}, {"point", "normal"},
                        expectation);
    if (expectation.body.empty() && expectation.other.empty() && expectation.values.empty()) {
        node.fail("an event expectation must give at least one of a, b, t, impulse, vn_before, "
                  "vn_after, point or normal");
    }
}

void validate_state(const Node& node, const Scene& scene, Expectation& expectation) {
    expectation.body = scene
                           .bodies[read_dynamic_body_reference(required_member(node, "body"), scene,
                                                               "a state expectation")]
                           .name;
    const Node t = required_member(node, "t");
    expectation.t = read_non_negative(t);
    // Frames are recorded at k dt (DESIGN.md): any other time has no frame.
    const double k = std::round(expectation.t / scene.dt);
    if (std::abs(expectation.t - k * scene.dt) > 1e-9 * scene.dt ||
        k > static_cast<double>(step_count(scene))) {
        t.fail("must be the time of a frame, a multiple of dt = " + number_text(scene.dt) +
               " s up to the end of the run, got " + number_text(expectation.t));
    }
    read_literal_values(node, {"x", "y", "angle", "vx", "vy", "omega"}, {}, expectation);
    if (expectation.values.empty()) {
        node.fail("a state expectation must give at least one of x, y, angle, vx, vy or omega");
    }
}

struct ExpectationKind {
    const char* name;
    Expectation::Kind kind;
    std::vector<std::string> keys; // besides kind, description, atol, rtol
    void (*validate)(const Node&, const Scene&, Expectation&);
};

void validate_nothing(const Node&, const Scene&, Expectation&) {}

const std::vector<ExpectationKind>& expectation_kinds() {
    static const std::vector<ExpectationKind> kinds = {
        {"drop", Expectation::Kind::drop, {"body", "impacts"}, validate_drop},
        {"corner-impact", Expectation::Kind::corner_impact, {"body"}, validate_corner_impact},
        {"head-on", Expectation::Kind::head_on, {"a", "b"}, validate_head_on},
        {"conserved", Expectation::Kind::conserved, {"quantities"}, validate_conserved},
        {"energy-non-increasing", Expectation::Kind::energy_non_increasing, {}, validate_nothing},
        {"momentum-balance", Expectation::Kind::momentum_balance, {}, validate_momentum_balance},
        {"event",
         Expectation::Kind::event,
         {"index", "a", "b", "t", "impulse", "vn_before", "vn_after", "point", "normal"},
         validate_event},
        {"state",
         Expectation::Kind::state,
         {"body", "t", "x", "y", "angle", "vx", "vy", "omega"},
         validate_state},
    };
    return kinds;
}

const ExpectationKind& read_expectation_kind(const Node& node) {
    std::vector<std::string> names;
    for (const ExpectationKind& kind : expectation_kinds()) {
        if (node.json().is_string() && node.json().get<std::string>() == kind.name) {
            return kind;
        }
        names.push_back(std::string("\"") + kind.name + "\"");
    }
    node.fail("must be one of " + list_of(names) + ", got " + describe(node.json()));
}

Expectation read_expectation(const Node& node, const Scene& scene) {
    require_object(node);
    const ExpectationKind& kind = read_expectation_kind(required_member(node, "kind"));
    std::vector<std::string> keys = {"kind", "description", "atol", "rtol"};
    keys.insert(keys.end(), kind.keys.begin(), kind.keys.end());
    reject_unknown_keys(node, keys);
    Expectation expectation;
    expectation.kind = kind.kind;
    expectation.path = node.path();
    expectation.description = read_string_or(node, "description", "");
    // No silent defaults: every expectation says how close is close enough.
    if (!node.has("atol") && !node.has("rtol")) {
        node.fail("must give atol or rtol (or both); an expectation has no default tolerance");
    }
    if (const std::optional<Node> atol = optional_member(node, "atol")) {
        expectation.atol = read_non_negative(*atol);
    }
    if (const std::optional<Node> rtol = optional_member(node, "rtol")) {
        expectation.rtol = read_non_negative(*rtol);
    }
    kind.validate(node, scene, expectation);
    return expectation;
}

void read_expectations(const Node& node, Scene& scene) {
    require_array(node);
    for (std::size_t i = 0; i < node.json().size(); ++i) {
        scene.expectations.push_back(read_expectation(node.element(i), scene));
    }
}

// ---------------------------------------------------------------- box2d

struct Box2dObservableKind {
    const char* name;
    Box2dObservable::Kind kind;
    std::vector<std::string> keys; // besides kind, atol, rtol
};

const std::vector<Box2dObservableKind>& box2d_observable_kinds() {
    using Kind = Box2dObservable::Kind;
    static const std::vector<Box2dObservableKind> kinds = {
        {"impact-times", Kind::impact_times, {"body", "count"}},
        {"apex-heights", Kind::apex_heights, {"body", "count"}},
        {"apex-ratios", Kind::apex_ratios, {"body", "count"}},
        {"post-impact-velocity", Kind::post_impact_velocity, {"body", "impact"}},
        {"restitution-residual", Kind::restitution_residual, {"body"}},
        {"momentum", Kind::momentum, {}},
        {"angular-momentum", Kind::angular_momentum, {}},
        {"energy", Kind::energy, {}},
    };
    return kinds;
}

const Box2dObservableKind& read_box2d_observable_kind(const Node& node) {
    std::vector<std::string> names;
    for (const Box2dObservableKind& kind : box2d_observable_kinds()) {
        if (node.json().is_string() && node.json().get<std::string>() == kind.name) {
            return kind;
        }
        names.push_back(std::string("\"") + kind.name + "\"");
    }
    node.fail("must be one of " + list_of(names) + ", got " + describe(node.json()));
}

// Impacts counted or named by number: far more than any scene has.
constexpr long long max_box2d_impacts = 10000;
// Box2D's substeps and iteration counts: far more than any useful setting.
constexpr long long max_box2d_setting = 1000;

// One entry of box2d.observables (scene.h, Box2dObservable). An observable
// whose meaning rests on a formula of PHYSICS.md is held to that formula's
// preconditions, as the expectations are: an apex measured above the contact
// height y0 - h0 needs a body falling straight onto static ground.
Box2dObservable read_box2d_observable(const Node& node, const Scene& scene) {
    require_object(node);
    const Box2dObservableKind& kind = read_box2d_observable_kind(required_member(node, "kind"));
    std::vector<std::string> keys = {"kind", "atol", "rtol"};
    keys.insert(keys.end(), kind.keys.begin(), kind.keys.end());
    reject_unknown_keys(node, keys);
    Box2dObservable observable;
    observable.kind = kind.kind;
    observable.path = node.path();
    // No silent defaults: every observable says how close Box2D must come.
    if (!node.has("atol") && !node.has("rtol")) {
        node.fail("must give atol or rtol (or both); an observable has no default tolerance");
    }
    if (const std::optional<Node> atol = optional_member(node, "atol")) {
        observable.atol = read_non_negative(*atol);
    }
    if (const std::optional<Node> rtol = optional_member(node, "rtol")) {
        observable.rtol = read_non_negative(*rtol);
    }
    const std::string subject = std::string("the ") + kind.name + " observable";
    const auto body_of = [&](const Node& body_node) {
        const std::size_t index = read_dynamic_body_reference(body_node, scene, subject);
        observable.body = scene.bodies[index].name;
        return index;
    };
    using Kind = Box2dObservable::Kind;
    switch (kind.kind) {
    case Kind::impact_times:
    case Kind::apex_heights:
    case Kind::apex_ratios: {
        const Node body_node = required_member(node, "body");
        const std::size_t body = body_of(body_node);
        observable.count =
            static_cast<int>(read_whole(required_member(node, "count"), 1, max_box2d_impacts));
        if (kind.kind != Kind::impact_times) {
            reject_refusal(drop_refusal(scene, scene.bodies[body],
                                        std::string("the drop formula behind ") + kind.name),
                           node, body_node);
        }
        break;
    }
    case Kind::post_impact_velocity:
        body_of(required_member(node, "body"));
        observable.impact =
            static_cast<int>(read_whole(required_member(node, "impact"), 1, max_box2d_impacts));
        break;
    case Kind::restitution_residual:
        if (const std::optional<Node> body = optional_member(node, "body")) {
            body_of(*body);
        }
        break;
    case Kind::momentum:
    case Kind::angular_momentum:
    case Kind::energy:
        break;
    }
    return observable;
}

// "box2d": how `impulse box2d` runs the scene in Box2D and what it compares.
void read_box2d(const Node& node, Scene& scene) {
    require_object(node);
    reject_unknown_keys(node,
                        {"substeps", "velocity_iterations", "position_iterations", "observables"});
    Box2dSettings& settings = scene.box2d;
    for (const auto& [key, value] :
         {std::pair{"substeps", &settings.substeps},
          std::pair{"velocity_iterations", &settings.velocity_iterations},
          std::pair{"position_iterations", &settings.position_iterations}}) {
        if (const std::optional<Node> given = optional_member(node, key)) {
            *value = static_cast<int>(read_whole(*given, 1, max_box2d_setting));
        }
    }
    if (const std::optional<Node> list = optional_member(node, "observables")) {
        require_array(*list);
        for (std::size_t i = 0; i < list->json().size(); ++i) {
            settings.observables.push_back(read_box2d_observable(list->element(i), scene));
        }
    }
}

const std::vector<std::string> scene_keys = {
    "schema", "name",   "description", "gravity",   "restitution",  "dt",   "duration",
    "solver", "bodies", "gas",         "tolerance", "expectations", "box2d"};

Scene read_scene(const Node& root) {
    if (!root.json().is_object()) {
        root.fail("the top level must be a JSON object, got " + describe(root.json()));
    }
    // The schema comes before the unknown-key check: a trajectory file or a
    // newer scene version given by mistake should be named as such, not as a
    // list of unknown keys.
    read_schema(root);
    reject_unknown_keys(root, scene_keys);
    Scene scene;
    scene.file = root.file();
    scene.name = read_name(required_member(root, "name"));
    scene.description = read_string_or(root, "description", "");
    scene.gravity = read_vec2_or(root, "gravity", scene.gravity);
    scene.restitution = read_restitution(root);
    read_time(root, scene);
    if (const std::optional<Node> solver = optional_member(root, "solver")) {
        read_solver(*solver, scene.solver);
    }
    read_bodies(root, scene);
    // These refer to bodies, so they are read once the bodies are known.
    if (const std::optional<Node> tolerance = optional_member(root, "tolerance")) {
        read_tolerances(*tolerance, scene.tolerances);
    }
    if (const std::optional<Node> expectations = optional_member(root, "expectations")) {
        read_expectations(*expectations, scene);
    }
    if (const std::optional<Node> box2d = optional_member(root, "box2d")) {
        read_box2d(*box2d, scene);
    }
    return scene;
}

} // namespace

Scene load_scene(const std::string& path) {
    return parse_scene(read_file(path, max_file_bytes, "a scene is a few kilobytes"), path);
}

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

Scene parse_scene(const std::string& text, const std::string& file) {
    const Json document = parse_strict_json<Json>(text, file);
    Scene scene = read_scene(Node(document, "", file));
    // Sorted keys and no whitespace: the same content gives the same
    // fingerprint however the file is laid out.
    scene.sha256 = sha256_hex(canonical(document).dump());
    return scene;
}

long long step_count(const Scene& scene) {
    return static_cast<long long>(steps_for(scene.duration, scene.dt));
}

const char* integrator_name(Integrator integrator) {
    switch (integrator) {
    case Integrator::euler:
        return "euler";
    case Integrator::symplectic_euler:
        return "symplectic-euler";
    case Integrator::verlet:
        return "verlet";
    case Integrator::rk4:
        return "rk4";
    }
    return "unknown";
}

const char* toi_method_name(TimeOfImpactMethod method) {
    switch (method) {
    case TimeOfImpactMethod::bisection:
        return "bisection";
    case TimeOfImpactMethod::secant:
        return "secant";
    }
    return "unknown";
}

const char* contact_mode_name(ContactMode mode) {
    switch (mode) {
    case ContactMode::single:
        return "single";
    case ContactMode::simultaneous:
        return "simultaneous";
    }
    return "unknown";
}

bool contact_mode_from_name(const std::string& name, ContactMode& out) {
    for (int i = 0; i < contact_mode_count; ++i) {
        const auto candidate = static_cast<ContactMode>(i);
        if (name == contact_mode_name(candidate)) {
            out = candidate;
            return true;
        }
    }
    return false;
}

const char* vertex_normal_name(VertexNormal normal) {
    switch (normal) {
    case VertexNormal::reference_face:
        return "reference-face";
    case VertexNormal::bisector:
        return "bisector";
    }
    return "unknown";
}

bool vertex_normal_from_name(const std::string& name, VertexNormal& out) {
    for (int i = 0; i < vertex_normal_count; ++i) {
        const auto candidate = static_cast<VertexNormal>(i);
        if (name == vertex_normal_name(candidate)) {
            out = candidate;
            return true;
        }
    }
    return false;
}

const char* stepping_name(Stepping stepping) {
    switch (stepping) {
    case Stepping::world:
        return "world";
    case Stepping::local:
        return "local";
    }
    return "unknown";
}

bool stepping_from_name(const std::string& name, Stepping& out) {
    for (int i = 0; i < stepping_count; ++i) {
        const auto candidate = static_cast<Stepping>(i);
        if (name == stepping_name(candidate)) {
            out = candidate;
            return true;
        }
    }
    return false;
}

bool toi_method_from_name(const std::string& name, TimeOfImpactMethod& out) {
    for (int i = 0; i < time_of_impact_method_count; ++i) {
        const auto candidate = static_cast<TimeOfImpactMethod>(i);
        if (name == toi_method_name(candidate)) {
            out = candidate;
            return true;
        }
    }
    return false;
}

bool integrator_from_name(const std::string& name, Integrator& out) {
    for (int i = 0; i < integrator_count; ++i) {
        const auto candidate = static_cast<Integrator>(i);
        if (name == integrator_name(candidate)) {
            out = candidate;
            return true;
        }
    }
    return false;
}

} // namespace impulse::harness
