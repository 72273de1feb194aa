// How the engine models a scene (docs/design.md, the solver table). Each variant is
// one enum value and one case where it is used; the seed's value comes first.
#pragma once

namespace impulse {

enum class Integrator { euler, symplectic_euler, verlet, rk4 };
inline constexpr int integrator_count = 4;

// bisection: the seed's binary search. secant: safeguarded regula falsi on the
// offending pair's signed separation, the same answer in fewer iterations
// (docs/engine.md, "The secant search").
enum class TimeOfImpactMethod { bisection, secant };
inline constexpr int time_of_impact_method_count = 2;
static_assert(static_cast<int>(TimeOfImpactMethod::secant) + 1 == time_of_impact_method_count,
              "time_of_impact_method_count must follow the last TimeOfImpactMethod");

// single: the seed's, one point of one pair at a time. simultaneous: every
// touching point of every touching pair at the collision time solved together
// (Newton's law at each point, non-negative impulses: a small LCP;
// docs/engine.md, "Simultaneous contact").
enum class ContactMode { single, simultaneous };
inline constexpr int contact_mode_count = 2;

// The normal of a vertex/vertex contact. reference_face: the seed's, treated
// as vertex/edge against the reference face the separating axes pick.
// bisector: the bisector of the cone of normals both vertices admit, which
// does not depend on which face happens to separate most (docs/engine.md,
// "Vertex/vertex").
enum class VertexNormal { reference_face, bisector };
inline constexpr int vertex_normal_count = 2;

// world: the seed's loop, where a collision anywhere rewinds and re-integrates
// every body. local: each body keeps its own clock within the step, so a
// collision re-integrates only the two bodies in it, and a broad phase picks
// the pairs worth a narrow-phase test (docs/engine.md, "Local stepping"). With
// one moving body the two give the same bits.
enum class Stepping { world, local };
inline constexpr int stepping_count = 2;

// How `resting: true` holds bodies in contact (docs/engine.md, "Dense contact").
// events: the event-driven model (collisions found by the time-of-impact search,
// resting points held by acceleration-level contact forces), exact where it
// applies. time_stepping: Moreau and Jean's velocity-level contact per step and
// per island, with Newton's law at impacts; no event search, so no Zeno
// cascade. automatic: events where they carry the scene, time-stepping from the
// step where they cannot (and from the start for local stepping or large piles).
enum class RestingMethod { automatic, events, time_stepping };
inline constexpr int resting_method_count = 3;

struct SolverSettings {
    Integrator integrator = Integrator::euler;
    TimeOfImpactMethod toi = TimeOfImpactMethod::bisection;
    double toi_tolerance = 1e-12;    // seconds
    double contact_tolerance = 1e-9; // metres
    ContactMode contacts = ContactMode::single;
    Stepping stepping = Stepping::world;
    VertexNormal vertex_normal = VertexNormal::reference_face;
    // Catch tunnelling: every pair's motion over the step is swept by
    // conservative advancement (docs/engine.md, "Tunnelling").
    bool ccd = false;
    // End Zeno cascades and hold resting bodies with contact forces
    // (docs/engine.md, "Resting contact").
    bool resting = false;
    RestingMethod resting_method = RestingMethod::automatic; // only with resting
    // Work bounds that turn a stall into a clear error instead of a hang.
    // Bounds every search the step makes: the bisection's halvings, the secant
    // search's trials and ccd's samples of one pair's sweep.
    int max_search_iterations = 200;
    int max_collisions_per_step = 4096;
};

// resting_method automatic starts a world of more than this many dynamic
// bodies in time-stepping: the events model's cost grows with every pair of it
// (as brute_force_bodies in local_stepping.cpp, the size beyond which pairs
// need a broad phase).
inline constexpr int events_bodies = 16;

// true when resting contact is time-stepping from the first step, which is
// known before it: "time-stepping", or "auto" with local stepping (the events
// model needs every pair of the world at once) or with more than
// events_bodies dynamic bodies. One rule for the engine (world.cpp) and the
// scene loader (the tunnelling check), so a scene the engine steps by
// time-stepping is never refused for what only events would do.
inline bool starts_in_time_stepping(const SolverSettings& solver, int dynamic_bodies) {
    if (!solver.resting || solver.resting_method == RestingMethod::events) {
        return false;
    }
    return solver.resting_method == RestingMethod::time_stepping ||
           solver.stepping == Stepping::local || dynamic_bodies > events_bodies;
}

} // namespace impulse
