// A scene in the impulse/scene@1 format (docs/design.md), loaded and validated.
// Every default is filled in here, so nothing downstream guesses.
#pragma once

#include "shape.h"
#include "solver_settings.h"
#include "tolerance.h"
#include "vec2.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

inline constexpr const char* scene_schema = "impulse/scene@1";

struct SceneBody {
    std::string name;
    bool is_static = false;
    Shape shape;   // centred on the centre of mass (polygons recentred on load)
    Vec2 position; // of the centre of mass
    double angle = 0.0;
    Vec2 velocity;
    double angular_velocity = 0.0;
    double mass = 0.0;    // kg; 0 for static bodies
    double inertia = 0.0; // kg m^2 about the centre of mass; 0 for static and non-rotating
    bool rotation = true; // false: infinite inertia
};

// An answer the scene declares and every run checks (docs/design.md: "A scene may
// declare expectations that every run checks"). The exact ones are computed
// from the scene's own parameters by the formulas of docs/physics.md, so they stay
// right when a parameter changes; the literal ones carry hand-derived numbers.
struct Expectation {
    enum class Kind {
        drop,                  // docs/physics.md drop: impact times, rebound speeds, apex ladder
        corner_impact,         // docs/physics.md single-corner impact on static ground
        head_on,               // docs/physics.md 1D head-on collision of two free bodies
        conserved,             // linear momentum, angular momentum about the origin, energy
        energy_non_increasing, // e < 1: energy never grows from frame to frame
        momentum_balance,      // momentum changes only by the static bodies' impulses
        event,                 // literal values of one collision event
        state,                 // literal values of one body at one frame time
        max_overlap,           // no pair interpenetrates deeper than atol in any frame
        at_rest,               // after `t`, kinetic energy <= rtol x energy released + atol
    };
    Kind kind = Kind::conserved;
    std::string path;                    // JSON path of this expectation, e.g. "expectations[2]"
    std::string description;             // optional, shown in reports
    std::string body;                    // drop, corner_impact, state; head_on: body A
    std::string other;                   // head_on: body B
    int impacts = 0;                     // drop: how many impacts to check
    std::vector<std::string> quantities; // conserved: "momentum", "angular_momentum", "energy"
    std::size_t index = 0;               // event: which event (0-based)
    double t = 0.0;                      // state: the frame time; at_rest: "after"
    // event / state: field name -> expected value ("t", "impulse", "vn_before",
    // "vn_after", "point.x", "normal.y", ...; "x", "y", "angle", "vx", "vy", "omega").
    std::vector<std::pair<std::string, double>> values;
    double atol = 0.0;
    double rtol = 0.0;
};

// What `impulse box2d` compares and how Box2D is run (the scene's "box2d"
// block). Observables survive Box2D's differences (skin, iterations, position
// correction, single precision): docs/physics.md, "Box2D, the second reference".
struct Box2dObservable {
    enum class Kind {
        impact_times,         // times of the body's first `count` impacts (within a step)
        apex_heights,         // apex gap above the contact height after each of `count` impacts
        apex_ratios,          // apex n / apex n-1: e^2 in the exact model
        post_impact_velocity, // vx, vy, omega just after impact `impact` (1-based)
        restitution_residual, // vn_after + e vn_before of every event: 0 in the exact model
        momentum,             // largest drift of total linear momentum over the run
        angular_momentum,     // largest drift of angular momentum about the origin
        energy,               // largest drift (or loss) of kinetic + potential energy
    };
    Kind kind = Kind::impact_times;
    std::string path; // "box2d.observables[1]"
    std::string body;
    int count = 1;
    int impact = 1;
    double atol = 0.0;
    double rtol = 0.0;
};

struct Box2dSettings {
    int substeps = 1; // Box2D steps per scene step (each dt / substeps)
    int velocity_iterations = 8;
    int position_iterations = 3;
    std::vector<Box2dObservable> observables;
};

// The scene's "gas" block as read, with its shape's mass properties resolved:
// a frictionless gas of `count` equal bodies on a square lattice in a closed
// square room (docs/formats.md, "The gas block"; harness/scene/gas.h generates it).
struct GasSpec {
    int count = 0;
    Shape shape; // centred on its centroid (a polygon given off it is recentred)
    double mass = 0.0;
    double inertia = 0.0;
    double spacing = 0.0;           // m between lattice sites
    double max_speed = 0.0;         // m/s: velocities uniform in the disc of this radius
    double max_angular_speed = 0.0; // rad/s: angular velocities uniform in [-max, max)
    bool random_angles = false;     // angles uniform in [-pi, pi), else 0
    std::uint64_t seed = 1;
    double wall_thickness = 1.0;
};

// The scene's "pile" block as read: `count` bodies at rest on a lattice in an
// open box of three static walls, their kinds, sizes, densities and angles
// drawn from splitmix64 (docs/formats.md, "The pile block"; harness/scene/pile.h
// generates it).
struct PileSpec {
    enum class Kinds { circle, box, mixed };
    int count = 0;
    Kinds kinds = Kinds::circle;
    double size_min = 0.0; // m: a circle's radius, a square box's half side
    double size_max = 0.0;
    double density_min = 1.0; // kg/m^2
    double density_max = 1.0;
    double spacing = 0.0;       // m between lattice sites
    int columns = 0;            // 0: the smallest k with k * k >= count
    bool random_angles = false; // angles uniform in [-pi, pi), else 0
    std::uint64_t seed = 1;
    double wall_thickness = 1.0;
};

struct Scene {
    std::string file; // as given on the command line, for messages
    std::string name;
    std::string description;
    Vec2 gravity{0.0, -9.81};
    double restitution = 1.0;
    double dt = 0.0;
    double duration = 0.0;
    SolverSettings solver;
    // The file's "bodies", then, with a "gas" block, its four walls and its
    // count bodies (gas.h, generate_gas); with a "pile" block, its three walls
    // and its count bodies (pile.h, generate_pile).
    std::vector<SceneBody> bodies;
    std::optional<GasSpec> gas;            // the "gas" block, when there is one
    std::optional<PileSpec> pile;          // the "pile" block, when there is one
    std::size_t listed_bodies = 0;         // how many of `bodies` the file's "bodies" array lists
    Tolerances tolerances;                 // "tolerance": per channel, empty when not given
    std::vector<Expectation> expectations; // "expectations", in file order
    Box2dSettings box2d;                   // "box2d": how to compare with Box2D
    std::string sha256;                    // of the canonical JSON of the file's content
    std::vector<std::string> warnings;     // e.g. a polygon recentred on its centroid
};

// Reads, parses and validates a scene file; throws InputError naming the file
// and the JSON path of the first problem.
Scene load_scene(const std::string& path);
// The same from text already in memory; `file` is used in messages only.
Scene parse_scene(const std::string& text, const std::string& file);

// A longer run is refused: it would take hours and write gigabytes.
inline constexpr long long max_steps = 10'000'000;

// The number of steps a run takes: duration / dt, rounded to the nearest
// integer when within 1e-9 of it (so 3 s at 1/60 s is 180 steps despite
// rounding), rounded up otherwise.
long long step_count(const Scene& scene);

// Names of the solver enums as they appear in scene files and trajectories.
const char* integrator_name(Integrator integrator);
const char* toi_method_name(TimeOfImpactMethod method);
const char* contact_mode_name(ContactMode mode);
const char* stepping_name(Stepping stepping);
const char* vertex_normal_name(VertexNormal normal);
const char* resting_method_name(RestingMethod method); // "auto", "events", "time-stepping"
// false when the name is unknown
bool integrator_from_name(const std::string& name, Integrator& out);
bool toi_method_from_name(const std::string& name, TimeOfImpactMethod& out);
bool stepping_from_name(const std::string& name, Stepping& out);
bool contact_mode_from_name(const std::string& name, ContactMode& out);
bool vertex_normal_from_name(const std::string& name, VertexNormal& out);
bool resting_method_from_name(const std::string& name, RestingMethod& out);

// true when the scene's contact is time-stepping from its first step, which
// is known at load: "resting_method": "time-stepping", or "auto" with local
// stepping (the event model needs every pair of the world at once). "auto"
// with world stepping may still switch during the run (the engine decides;
// docs/engine.md, "Dense contact").
inline bool time_stepping_from_start(const SolverSettings& solver) {
    return solver.resting && (solver.resting_method == RestingMethod::time_stepping ||
                              (solver.resting_method == RestingMethod::automatic &&
                               solver.stepping == Stepping::local));
}

// The same with the scene's bodies counted, the engine's own rule
// (starts_in_time_stepping, solver_settings.h): "auto" also starts in
// time-stepping with more than 16 dynamic bodies, whatever the stepping.
inline bool time_stepping_from_start(const Scene& scene) {
    int dynamic = 0;
    for (const SceneBody& body : scene.bodies) {
        dynamic += body.is_static ? 0 : 1;
    }
    return starts_in_time_stepping(scene.solver, dynamic);
}

} // namespace impulse::harness
