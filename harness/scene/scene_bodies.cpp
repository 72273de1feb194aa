// The "bodies" of a scene: names, shapes, positions and mass properties; then,
// with the gas block's bodies appended, the overlap check at t = 0.
#include "rotation.h"
#include "scene_pile_block.h"
#include "scene_reading.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness::scene_reading {

namespace {

// A gas has thousands of bodies: a message lists this many names at most.
constexpr std::size_t max_names_listed = 20;

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

// Every impulse is multiplied by 1/m and 1/I (physics.md, Eq. 9): below the
// smallest normal double the inverse overflows to inf, and the first contact
// would give NaN blamed on sizes or speeds.
// Named at the first of `keys` the body gives (the key that set the value).
void require_invertible(const Node& node, double value, const std::string& what,
                        const std::string& unit, const std::vector<std::string>& keys) {
    if (value >= std::numeric_limits<double>::min()) {
        return;
    }
    Node given = node;
    for (const std::string& key : keys) {
        if (node.has(key)) {
            given = node.member(key);
            break;
        }
    }
    given.fail("gives " + what + " of " + number_text(value) + " " + unit +
               ", below the smallest normal double (2.2e-308), so its inverse, which every "
               "impulse is multiplied by, is not finite; scale the scene's units");
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
    require_invertible(node, body.mass, "a mass", "kg", {"mass", "density"});
    if (!body.rotation) {
        body.inertia = 0.0; // infinite: SceneBody::rotation says so
        return;
    }
    body.inertia = spec.inertia ? *spec.inertia : body.mass * shape.inertia_per_unit_mass;
    if (!std::isfinite(body.inertia) || !(body.inertia > 0.0)) {
        node.fail("its shape and mass give a moment of inertia of " + number_text(body.inertia) +
                  " kg m^2; it must be finite and > 0");
    }
    require_invertible(node, body.inertia, "a moment of inertia", "kg m^2",
                       {"inertia", "mass", "density"});
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
    if (shape.has("polygon")) { // a box is a polygon too, centred by construction
        refuse_unresolvable_vertices(shape.member("polygon"), body.shape.polygon,
                                     scene.solver.contact_tolerance);
    }
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
        refuse_infinite_weight(node, single_quoted(body.name), body.mass, scene.gravity);
    }
    return body;
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

} // namespace

// A mass whose weight m |g| overflows (1e308 kg under 9.81 m/s^2) turns the
// first contact force or potential energy into inf and the run into NaN,
// after a partial trajectory has been written over --out: refused here, at
// the key that gave the mass (a listed body's, or the gas block's). Finite
// weights run (1e307 kg does); a bound with room to spare would refuse the
// 1e300 kg bodies whose energies the gate reports as not finite
// (docs/refusals-and-progress.md).
void refuse_infinite_weight(const Node& node, const std::string& who, double mass, Vec2 gravity) {
    // hypot, not length: |g| beyond 1e154 would square to inf.
    const double weight = mass * std::hypot(gravity.x, gravity.y);
    if (std::isfinite(weight)) {
        return;
    }
    const std::string key = node.has("mass") ? "mass" : "density";
    const Node given = node.has(key) ? node.member(key) : node;
    given.fail("gives " + who + " a mass of " + number_text(mass) +
               " kg, whose weight m |g| under the scene's gravity overflows double precision; "
               "use a smaller " +
               (node.has(key) ? key : "shape") + " or gravity");
}

// "bodies", "gas" and "pile": the listed bodies, then the gas block's or the
// pile block's.
void read_bodies(const Node& root, Scene& scene) {
    const std::optional<Node> listed = optional_member(root, "bodies");
    const std::optional<Node> gas = optional_member(root, "gas");
    const std::optional<Node> pile = optional_member(root, "pile");
    if (!listed && !gas && !pile) {
        json_fields::fail("bodies",
                          "is required but missing; a scene lists its bodies, has a gas block, "
                          "or both (a pile block may stand in for the gas block)");
    }
    NameIndex names;
    if (listed) {
        read_listed_bodies(*listed, scene, gas.has_value() || pile.has_value(), names);
        refuse_unresolvable_bodies(*listed, scene); // the generated ones: their box
    }
    if (gas) {
        read_gas(*gas, scene);
    }
    if (pile) {
        read_pile(*pile, scene);
    }
    reject_initial_overlaps(scene);
}

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
    node.fail("no body is named " + shown(node) + "; the bodies are " + list_of(names) +
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

} // namespace impulse::harness::scene_reading
