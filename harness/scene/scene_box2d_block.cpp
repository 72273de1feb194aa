// The "box2d" block: how `impulse box2d` runs the scene in Box2D and which
// observables it compares (scene.h, Box2dObservable).
#include "scene_reading.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness::scene_reading {

namespace {

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

// Impacts counted or named by number: far more than any scene has.
constexpr long long max_box2d_impacts = 10000;
// Box2D's substeps and iteration counts: far more than any useful setting.
constexpr long long max_box2d_setting = 1000;

// One entry of box2d.observables (scene.h, Box2dObservable). An observable
// whose meaning rests on a formula of docs/physics.md is held to that formula's
// preconditions, as the expectations are: an apex measured above the contact
// height y0 - h0 needs a body falling straight onto static ground.
Box2dObservable read_box2d_observable(const Node& node, const Scene& scene) {
    require_object(node);
    const Box2dObservableKind& kind =
        read_kind(required_member(node, "kind"), box2d_observable_kinds());
    std::vector<std::string> keys = {"kind", "atol", "rtol"};
    keys.insert(keys.end(), kind.keys.begin(), kind.keys.end());
    reject_unknown_keys(node, keys);
    Box2dObservable observable;
    observable.kind = kind.kind;
    observable.path = node.path();
    // No silent defaults: every entry says how close is close enough.
    read_atol_rtol(node, "an observable", observable.atol, observable.rtol);
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

} // namespace

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

} // namespace impulse::harness::scene_reading
