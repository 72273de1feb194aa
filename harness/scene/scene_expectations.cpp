// A scene's "tolerance" block and its "expectations" (docs/formats.md): each
// exact answer held to the preconditions of its formula (exact_answers.h).
#include "scene_reading.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness::scene_reading {

namespace {

// ULP distances are counted in a uint64_t; 2^53 is the largest whole number a
// JSON reader is sure to hold exactly, and far more than any useful bound.
constexpr long long max_ulp = 9007199254740992;

// at-rest's rtol times the energies the gate sums (at most 2^960 J) stays finite.
constexpr double max_rest_rtol = 0x1p60;

ChannelTolerance read_channel_tolerance(const Node& node) {
    require_object(node);
    reject_unknown_keys(node, {"atol", "rtol", "ulp"});
    // No silent defaults (docs/design.md): a channel named must say how close is close.
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

// docs/physics.md, drop: "no rotation", released at rest.
void validate_drop(const Node& node, const Scene& scene, Expectation& expectation) {
    const std::string formula = "the drop formula";
    const Node body_node = required_member(node, "body");
    const std::size_t body = read_dynamic_body_reference(body_node, scene, formula);
    expectation.body = scene.bodies[body].name;
    expectation.impacts = static_cast<int>(read_whole(required_member(node, "impacts"), 1, 10000));
    reject_refusal(drop_refusal(scene, scene.bodies[body], formula), node, body_node);
}

// docs/physics.md, single-corner impact: a rotating polygon, not spinning, falling
// onto static ground on exactly one corner.
void validate_corner_impact(const Node& node, const Scene& scene, Expectation& expectation) {
    const std::string formula = "the corner-impact formula";
    const Node body_node = required_member(node, "body");
    const std::size_t body = read_dynamic_body_reference(body_node, scene, formula);
    expectation.body = scene.bodies[body].name;
    reject_refusal(corner_impact_refusal(scene, scene.bodies[body], formula), node, body_node);
}

// docs/physics.md, head-on: 1D, no rotation, free space.
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

// docs/physics.md: "Frictionless contact in free space conserves linear momentum
// exactly and angular momentum about any fixed point; with e = 1 it conserves
// kinetic energy".
void require_conserved(const Node& node, const Scene& scene, const std::string& quantity) {
    if (const std::optional<std::string> refusal = conservation_refusal(scene, quantity)) {
        node.fail(*refusal + (quantity == "energy"
                                  ? "; declare {\"kind\": \"energy-non-increasing\"} in its "
                                    "place (an expectation of its own, not a quantity)"
                                  : ""));
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
            item.fail("must be one of " + list_of(conserved_quantities) + ", got " + shown(item));
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
    // Frames are recorded at k dt (docs/design.md): any other time has no frame.
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

// A depth in metres has no scale to be relative to: atol alone.
void validate_max_overlap(const Node& node, const Scene&, Expectation&) {
    if (node.has("rtol")) {
        node.member("rtol").fail("max-overlap judges a depth in metres against atol alone; "
                                 "remove rtol and give atol");
    }
}

// "after": the time from which every frame is judged, within the run so that
// at least one frame is; rtol is the fraction of the released energy allowed.
void validate_at_rest(const Node& node, const Scene& scene, Expectation& expectation) {
    const Node after = required_member(node, "after");
    expectation.t = read_non_negative(after);
    if (expectation.t > scene.duration) {
        after.fail("must be at most the scene's duration " + number_text(scene.duration) +
                   " s, so that some frame is judged, got " + number_text(expectation.t));
    }
    if (!node.has("rtol")) {
        node.fail("an at-rest expectation must give rtol, the fraction of the released energy "
                  "the kinetic energy may keep (atol, in J, is optional)");
    }
    // The energies the gate sums stay within 2^960 J (scene_pile_block.cpp),
    // so rtol times them is finite up to rtol 2^60; 1e308 overflowed to an
    // infinite allowance, and a run at rest failed against it.
    const Node rtol = node.member("rtol");
    if (rtol.json().is_number() && rtol.json().get<double>() > max_rest_rtol) {
        rtol.fail("must be at most 2^60 = 1152921504606846976, so that rtol times the "
                  "energies the gate sums stays finite (a fraction of the released energy: 1 "
                  "already allows all of it), got " +
                  number_text(rtol.json().get<double>()));
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
        {"max-overlap", Expectation::Kind::max_overlap, {}, validate_max_overlap},
        {"at-rest", Expectation::Kind::at_rest, {"after"}, validate_at_rest},
    };
    return kinds;
}

Expectation read_expectation(const Node& node, const Scene& scene) {
    require_object(node);
    const ExpectationKind& kind = read_kind(required_member(node, "kind"), expectation_kinds());
    std::vector<std::string> keys = {"kind", "description", "atol", "rtol"};
    keys.insert(keys.end(), kind.keys.begin(), kind.keys.end());
    reject_unknown_keys(node, keys);
    Expectation expectation;
    expectation.kind = kind.kind;
    expectation.path = node.path();
    expectation.description = read_string_or(node, "description", "");
    // No silent defaults: every entry says how close is close enough.
    read_atol_rtol(node, "an expectation", expectation.atol, expectation.rtol);
    kind.validate(node, scene, expectation);
    return expectation;
}

} // namespace

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

void read_expectations(const Node& node, Scene& scene) {
    require_array(node);
    for (std::size_t i = 0; i < node.json().size(); ++i) {
        scene.expectations.push_back(read_expectation(node.element(i), scene));
    }
}

// A formula that does not apply to the scene (exact_answers.h) is refused at
// the key its refusal blames: the entry, its body or its other body.
void reject_refusal(const std::optional<Refusal>& refusal, const Node& entry, const Node& body,
                    const Node* other) {
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

} // namespace impulse::harness::scene_reading
