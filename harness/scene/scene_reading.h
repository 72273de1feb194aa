// What the section readers of a scene file share (scene_top_level.cpp,
// scene_shapes.cpp, scene_bodies.cpp, scene_gas_block.cpp, scene_pile_block.cpp,
// resolvable_extent.cpp,
// initial_overlaps.cpp, scene_expectations.cpp, scene_box2d_block.cpp):
// a value with its JSON path, and the typed reads on it. Private to the scene
// loader; scene.h is the public header.
//
// Every problem is a json_fields::FieldError (path, message); parse_scene
// turns the first one into an InputError naming the file. Checks run in the
// order the format lists its rules, and within a list in document order, so
// the first problem named is the one a person reading the file top to bottom
// meets first.
#pragma once

#include "exact_answers.h"
#include "json_fields.h"
#include "scene.h"
#include "strict_json.h"

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness::scene_reading {

// std::map-backed objects: keys sorted, which is what makes dump() canonical
// for the scene's fingerprint.
using Json = nlohmann::json;
using json_fields::list_of;

// A value in the document and the JSON path that leads to it: everything a
// message needs to name where a problem is.
class Node {
  public:
    Node(const Json& value, std::string path) : value_(&value), path_(std::move(path)) {}

    const Json& json() const { return *value_; }
    const std::string& path() const { return path_; }

    [[noreturn]] void fail(const std::string& message) const { json_fields::fail(path_, message); }

    // Callers have checked that this is an object / array.
    bool has(const std::string& key) const { return value_->contains(key); }
    Node member(const std::string& key) const {
        return Node(value_->at(key), json_member_path(path_, key));
    }
    Node element(std::size_t index) const {
        return Node(value_->at(index), json_element_path(path_, index));
    }

  private:
    const Json* value_;
    std::string path_;
};

// ---------------------------------------------------------------- typed reads (scene_reading.cpp)

// Shortest text that reads back to the same double (std::to_chars), so a
// value quoted in a message is exactly the value the file holds.
std::string number_text(double value);
// What a value is, for messages: json_fields::shown.
std::string shown(const Node& node);

void require_object(const Node& node);
void require_array(const Node& node);
std::optional<Node> optional_member(const Node& object, const std::string& key);
Node required_member(const Node& object, const std::string& key);
void reject_unknown_keys(const Node& object, const std::vector<std::string>& known);

std::string read_string(const Node& node);
bool read_bool(const Node& node);
double read_number(const Node& node);
double read_positive(const Node& node);
double read_non_negative(const Node& node);
// A count: a JSON number with no fractional part (3, or 3.0 written as a
// float), from `low` to `high`.
long long read_whole(const Node& node, long long low, long long high);
// [x, y]
Vec2 read_vec2(const Node& node);
// A scene or body name (see is_valid_name in scene_reading.cpp).
std::string read_name(const Node& node);

// The entry of `kinds` (each with a `name`) whose name the string value is;
// "must be one of ..." otherwise. For the "kind" of an expectation or an
// observable.
template <class Kind> const Kind& read_kind(const Node& node, const std::vector<Kind>& kinds) {
    std::vector<std::string> names;
    for (const Kind& kind : kinds) {
        if (node.json().is_string() && node.json().get<std::string>() == kind.name) {
            return kind;
        }
        names.push_back(std::string("\"") + kind.name + "\"");
    }
    node.fail("must be one of " + list_of(names) + ", got " + shown(node));
}

// "atol" and "rtol" of an expectation or an observable: no silent defaults,
// so at least one must be given; `what` names the entry in the message.
void read_atol_rtol(const Node& node, const std::string& what, double& atol, double& rtol);

// Optional values with their documented defaults: the value at `key` read
// by `read`, or `fallback` when the key is absent.
template <class T, class Read>
T read_or(const Node& object, const std::string& key, T fallback, Read read) {
    const std::optional<Node> node = optional_member(object, key);
    return node ? read(*node) : fallback;
}
std::string read_string_or(const Node& object, const std::string& key, std::string fallback);
bool read_bool_or(const Node& object, const std::string& key, bool fallback);
double read_number_or(const Node& object, const std::string& key, double fallback);
double read_positive_or(const Node& object, const std::string& key, double fallback);
Vec2 read_vec2_or(const Node& object, const std::string& key, Vec2 fallback);

// ---------------------------------------------------------------- the sections

// scene_top_level.cpp: the whole document, section by section.
Scene read_scene(const Node& root, const std::string& file);

// scene_shapes.cpp: a "shape" object, checked so that make_polygon's
// assumptions hold.
Shape read_shape(const Node& node);
// Moves a polygon's vertices by minus its centroid; returns the centroid when
// it was off the origin.
std::optional<Vec2> recentre_on_centroid(Shape& shape);
std::string centroid_warning(const std::string& file, const std::string& shape_path, Vec2 centroid,
                             const std::string& consequence);

// scene_bodies.cpp: "bodies" and "gas", then the overlap check at t = 0.
void read_bodies(const Node& root, Scene& scene);
// The index of the body a string value names; the dynamic one refuses a
// static body, saying what `needs` it.
std::size_t read_body_reference(const Node& node, const Scene& scene);
std::size_t read_dynamic_body_reference(const Node& node, const Scene& scene,
                                        const std::string& needs);

// Refuses a mass whose weight m |g| overflows double precision, at `node`'s
// "mass" or "density" (or `node` when it gives neither); `who` names the body
// in the sentence ("'ball'", "each gas body").
void refuse_infinite_weight(const Node& node, const std::string& who, double mass, Vec2 gravity);

// scene_gas_block.cpp: the "gas" block, its bodies appended to the listed ones.
void read_gas(const Node& node, Scene& scene);

// resolvable_extent.cpp: a generated block's box reaches at most
// resolvable_extent(contact_tolerance) from the origin (2^48 tolerances);
// refuse_unresolvable_extent fails at the block's `key` ("gives BOX reaching
// ...; CURE") when `extent` is beyond it.
double resolvable_extent(double contact_tolerance);
void refuse_unresolvable_extent(const Node& block, const std::string& key, const std::string& box,
                                double extent, double contact_tolerance, const std::string& cure);
// Every listed body (scene.bodies, read so far) within the same extent, or
// InputError at its bodies[i].position.
void refuse_unresolvable_bodies(const Node& listed, const Scene& scene);
// A listed polygon's vertices (as given, before recentring) within the same
// extent of its body's origin, or InputError at its shape's "polygon".
void refuse_unresolvable_vertices(const Node& node, const Polygon& polygon,
                                  double contact_tolerance);

// initial_overlaps.cpp: refuses bodies interpenetrating at t = 0.
void reject_initial_overlaps(const Scene& scene);

// scene_expectations.cpp: "tolerance" and "expectations".
void read_tolerances(const Node& node, Tolerances& tolerances);
void read_expectations(const Node& node, Scene& scene);
// A formula that does not apply to the scene (exact_answers.h) is refused at
// the key its refusal blames: the entry, its body or its other body.
void reject_refusal(const std::optional<Refusal>& refusal, const Node& entry, const Node& body,
                    const Node* other = nullptr);

// scene_box2d_block.cpp: "box2d".
void read_box2d(const Node& node, Scene& scene);

} // namespace impulse::harness::scene_reading
