// The top level of an impulse/scene@1 file (docs/formats.md): schema, name,
// dt, duration, gravity, restitution and the solver block, then each section
// in the order the format lists them.
#include "scene_reading.h"

#include <cmath>
#include <optional>
#include <string>

namespace impulse::harness::scene_reading {

namespace {

void read_schema(const Node& root) {
    const std::string wanted = scene_schema;
    if (!root.has("schema")) {
        json_fields::fail("schema",
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
            node.fail("unsupported scene version " + shown(node) + "; this build reads \"" +
                      wanted + "\"");
        }
    }
    node.fail("not a scene: expected \"" + wanted + "\", got " + shown(node));
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

// solver.resting_method: how `resting: true` holds bodies in contact. Only
// with resting on: without it there is no resting contact to hold, and a key
// that silently did nothing would mislead.
void read_resting_method(const Node& node, SolverSettings& solver) {
    const std::optional<Node> method = optional_member(node, "resting_method");
    if (!method) {
        return;
    }
    if (!method->json().is_string() ||
        !resting_method_from_name(method->json().get<std::string>(), solver.resting_method)) {
        method->fail("must be \"auto\" (the default), \"events\" or \"time-stepping\", got " +
                     shown(*method));
    }
    if (!solver.resting) {
        method->fail("needs \"resting\": true in the solver block (it chooses how resting "
                     "contact is held, and without resting there is none); add \"resting\": "
                     "true or remove \"resting_method\"");
    }
    // The event model finds each collision by one search over every pair of
    // the world; local stepping gives each body its own clock instead.
    if (solver.resting_method == RestingMethod::events && solver.stepping == Stepping::local) {
        method->fail("\"events\" is not available with \"stepping\": \"local\" (the event "
                     "model holds every resting pair of the world at once); use "
                     "\"resting_method\": \"auto\" or \"time-stepping\" with local stepping, or "
                     "\"stepping\": \"world\" with events");
    }
}

void read_solver(const Node& node, SolverSettings& solver) {
    require_object(node);
    reject_unknown_keys(node,
                        {"integrator", "toi", "toi_tolerance", "contact_tolerance", "contacts",
                         "stepping", "vertex_normal", "ccd", "resting", "resting_method"});
    if (const std::optional<Node> integrator = optional_member(node, "integrator")) {
        if (!integrator->json().is_string() ||
            !integrator_from_name(integrator->json().get<std::string>(), solver.integrator)) {
            integrator->fail(
                "must be one of \"euler\", \"symplectic-euler\", \"verlet\", \"rk4\", got " +
                shown(*integrator));
        }
    }
    if (const std::optional<Node> toi = optional_member(node, "toi")) {
        if (!toi->json().is_string() ||
            !toi_method_from_name(toi->json().get<std::string>(), solver.toi)) {
            toi->fail("must be \"bisection\" (the seed's) or \"secant\", got " + shown(*toi));
        }
    }
    solver.toi_tolerance = read_positive_or(node, "toi_tolerance", solver.toi_tolerance);
    solver.contact_tolerance =
        read_positive_or(node, "contact_tolerance", solver.contact_tolerance);
    if (const std::optional<Node> stepping = optional_member(node, "stepping")) {
        if (!stepping->json().is_string() ||
            !stepping_from_name(stepping->json().get<std::string>(), solver.stepping)) {
            stepping->fail("must be \"world\" (the seed's) or \"local\", got " + shown(*stepping));
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
                           shown(*contacts));
        }
        if (solver.contacts != ContactMode::single) {
            refuse_with_local(*contacts);
        }
    }
    if (const std::optional<Node> normal = optional_member(node, "vertex_normal")) {
        if (!normal->json().is_string() ||
            !vertex_normal_from_name(normal->json().get<std::string>(), solver.vertex_normal)) {
            normal->fail("must be \"reference-face\" (the seed's) or \"bisector\", got " +
                         shown(*normal));
        }
    }
    // resting (and its method) before ccd: whether ccd has anything to do
    // depends on the contact method.
    solver.resting = read_bool_or(node, "resting", solver.resting);
    read_resting_method(node, solver);
    // Time-stepping solves every touching point of an island together in each
    // step, whatever "contacts" says (the same bits either way), so a request
    // for another contact model there would do nothing; refused, not ignored.
    if (solver.contacts != ContactMode::single && solver.resting &&
        solver.resting_method == RestingMethod::time_stepping) {
        optional_member(node, "contacts")
            ->fail("is not used with \"resting_method\": \"time-stepping\", which solves every "
                   "touching point of an island together in each step; remove \"contacts\", or "
                   "use \"resting_method\": \"auto\" or \"events\" for the event model it "
                   "chooses");
    }
    solver.ccd = read_bool_or(node, "ccd", solver.ccd);
    if (solver.ccd) {
        const Node ccd = *optional_member(node, "ccd");
        refuse_with_local(ccd);
    }
}

const std::vector<std::string> scene_keys = {
    "schema", "name",   "description", "gravity", "restitution", "dt",           "duration",
    "solver", "bodies", "gas",         "pile",    "tolerance",   "expectations", "box2d"};

} // namespace

Scene read_scene(const Node& root, const std::string& file) {
    if (!root.json().is_object()) {
        root.fail("the top level must be a JSON object, got " + shown(root));
    }
    // The schema comes before the unknown-key check: a trajectory file or a
    // newer scene version given by mistake should be named as such, not as a
    // list of unknown keys.
    read_schema(root);
    reject_unknown_keys(root, scene_keys);
    Scene scene;
    scene.file = file;
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

} // namespace impulse::harness::scene_reading

namespace impulse::harness {

long long step_count(const Scene& scene) {
    return static_cast<long long>(scene_reading::steps_for(scene.duration, scene.dt));
}

} // namespace impulse::harness
