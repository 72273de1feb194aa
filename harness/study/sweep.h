// `impulse sweep`: the speed/accuracy trade. A grid of solver settings run on
// one scene (impulse over time step, integrator, time-of-impact method,
// tolerance and, on request, ccd; Box2D over time step, sub-steps and iterations), each point's
// error and cost measured, and the Pareto front of every method family.
// Measurement only: the command line prints (harness/cli/sweep.cpp).
//
// The engine under study is any engine behind run_engine (engine.h). The
// impulse engine runs in process with its own grid (toi method and ccd too)
// and work counters; any other engine gets the grid that reaches an engine as
// a modified scene (Overrides: dt, integrator, toi_tolerance), and its cost is
// what it reports (the trajectory's "cost" block) or else the process's wall
// time, and the result says which.
#pragma once

#include "engine.h"
#include "scene.h"
#include "world.h"

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness {

// A reference engine of the registry (reference_engines.h) other than the
// in-process Box2D 2.4.1, swept over the grid's time steps and, for the Node
// references, over its sub-steps (`--substeps N` on its command line: Box2D
// v3's sub-steps, Rapier's solver iterations). Its points are one family,
// named after it, so its front sits on the same axes as impulse's.
struct SweepReference {
    std::string name;          // "box2d-3": the family and what --with takes
    std::string title;         // "Box2D v3", for the legend and the verdict
    EngineSpec spec;           // how to run it
    std::vector<int> substeps; // empty: the engine's own setting only
};

struct SweepConfig {
    // The engine under study; the Box2D points below are the reference beside it.
    EngineSpec engine = impulse_engine();
    std::vector<double> dts;
    std::vector<Integrator> integrators;
    // The impulse engine's own settings: another engine runs the scene's.
    std::vector<TimeOfImpactMethod> toi_methods;
    std::vector<double> toi_tolerances;
    // solver.ccd for the impulse points (docs/engine.md, "Tunnelling"); empty:
    // the scene's own setting only.
    std::vector<bool> ccd;
    bool box2d = true; // ignored (no Box2D points) when the tool is built without Box2D
    std::vector<int> box2d_substeps;
    std::vector<std::pair<int, int>> box2d_iterations; // (velocity, position)
    std::vector<SweepReference> references;            // every other reference's front
    int repeats = 5;                                   // timed runs per grid point
};

// One warning per time step of the grid run with ccd off at which the scene
// could tunnel (tunnelling.h): the sweep runs such points on purpose (the
// cost of ccd is what `--ccd off,on` measures), so it warns instead of refusing.
std::vector<std::string> tunnelling_warnings(const Scene& scene, const SweepConfig& config);

// The defaults: dt in {1/30, ..., 1/960} (those not longer than the scene's
// duration), all four integrators, both time-of-impact methods, toi_tolerance
// {1e-6, 1e-9, 1e-12}, ccd as the scene sets it; Box2D over the same dts x substeps {1, 4} x
// iterations {8/3, 30/10}; 5 repeats. On a pile stepped by time-stepping from
// its start (no time-of-impact search) the scene's own toi method and
// tolerance only.
SweepConfig default_sweep_config(const Scene& scene);

// Where a point's cost comes from.
enum class SweepCost {
    in_process,      // the impulse engine or Box2D, timed around the simulation
    engine_reported, // the engine's own "cost" seconds
    process_time,    // the whole process's wall time: the engine reports none
};

// "in-process", "engine" or "process", as the JSON and the CSV name it.
const char* sweep_cost_name(SweepCost cost);

// One grid point and what it measured.
struct SweepPoint {
    bool box2d = false;
    // A reference of SweepConfig::references: its name (also the family);
    // empty for the engine under study and for Box2D 2.4.1.
    std::string reference;
    // The engine under study's points (box2d false): its kind and name.
    EngineSpec::Kind kind = EngineSpec::Kind::impulse;
    std::string engine = "impulse";
    // "impulse verlet/secant", "impulse verlet/secant+ccd", "box2d", or for
    // another engine its name and the integrator asked for ("my-engine verlet").
    std::string family;
    double dt = 0.0;
    // The engine under study's points (toi and ccd vary for impulse only)
    Integrator integrator = Integrator::euler;
    TimeOfImpactMethod toi = TimeOfImpactMethod::bisection;
    double toi_tolerance = 0.0;
    bool ccd = false; // solver.ccd
    // Box2D points, and a reference's --substeps (0: the engine's own)
    int substeps = 0;
    int velocity_iterations = 0;
    int position_iterations = 0;

    bool ok = false;
    // The engine refused the point's settings (exit 3): neither measured nor
    // failed; failure then says "unsupported by ENGINE: ...".
    bool skipped = false;
    std::string failure; // why the engine refused this point, one sentence
    double error = 0.0;  // the largest relative error (see SweepResult::error_reference);
                         // on a pile, the deepest overlap in metres
    // A pile's second error axis (SweepResult::energy_reference); NaN elsewhere.
    double energy_error = std::numeric_limits<double>::quiet_NaN();
    // Seconds of (steady-clock) time per simulated second: median over the
    // repeats and their spread (max - min).
    double cost_median = 0.0;
    double cost_spread = 0.0;
    SweepCost cost_source = SweepCost::in_process;
    // Deterministic work of one run (Box2D: steps only, the rest 0; another
    // engine: the steps it reports, work_counted false when it reports none).
    WorkCounters work;
    bool work_counted = true;
    bool work_identical = true; // every repeat counted the same work
    bool on_front = false;      // on its family's Pareto front in (cost, error)
};

struct SweepResult {
    std::string scene;
    std::string engine = "impulse"; // the engine under study
    // Empty for the impulse engine (its cost is as it always was); otherwise
    // one sentence: "cost: process wall time (the engine reports none)", ...
    std::string cost_source;
    bool against_exact = false;  // the scene's exact answers; otherwise a reference run
    std::string error_reference; // one sentence saying which
    double simulated_duration = 0.0;
    int repeats = 0;
    // A pile (sweep_measures.h): errors are the deepest overlap and the
    // energy gained, costs seconds per body-step at the scene's dt.
    bool pile = false;
    std::string energy_reference; // a pile's energy axis, one sentence
    std::string cost_unit = "seconds per simulated second";
    // Box2D 2.4.1 (when it has points) and every reference: (family, title).
    std::vector<std::pair<std::string, std::string>> references;
    std::vector<SweepPoint> points; // impulse points first, then Box2D, in grid order
};

// Called after each grid point: points done so far, the total, the point.
using SweepProgress = std::function<void(std::size_t, std::size_t, const SweepPoint&)>;

// Relative error floor: values below this magnitude are compared absolutely.
inline constexpr double sweep_error_floor = 1e-9;

// Runs the grid. Throws InputError when the configuration cannot apply to the
// scene (an empty grid, a dt longer than the duration, ccd with local
// stepping) or when a reference run is needed and the engine refuses it; a
// grid point the impulse engine refuses is a failed point, never an
// exception, one another engine refuses (exit 3) a skipped point, and any
// other failure of another engine (a crash, a time-out, a bad trajectory) is
// run_engine's InputError: the engine is broken, not the grid point. The
// reference run uses ccd when the scene or any grid point does: a reference
// that tunnels is no reference.
SweepResult run_sweep(const Scene& scene, const SweepConfig& config,
                      const SweepProgress& progress = {});

// Indices of the points not dominated in (cost, error): no other point has
// cost <= and error <= with one of them strictly smaller. Sorted by cost,
// then error.
std::vector<std::size_t> pareto_front(const std::vector<std::pair<double, double>>& cost_error);

// Box2D 2.4.1's point or another reference's: not the engine under study.
bool is_reference_point(const SweepPoint& point);

// Sets on_front for every successful point, per family.
void mark_fronts(std::vector<SweepPoint>& points);

// "impulse verlet/secant", "impulse verlet/secant+ccd" (ccd on), "box2d",
// a reference's name ("box2d-3"), or "ENGINE INTEGRATOR" for another engine.
std::string sweep_family(const SweepPoint& point);

// The two targets against Box2D:
//  1. at Box2D's cost at 60 Hz or less, an error at least target_error_ratio
//     times smaller;
//  2. the impulse points' Pareto front (every family together) dominates
//     Box2D's front everywhere.
// Costs are the run's wall-clock medians, so a verdict near its threshold can
// flip from one run to the next: cost_margin says how near target 1 is.
inline constexpr double target_error_ratio = 1e6;

// Box2D's settings at 60 Hz: the point target 1 measures against.
inline constexpr double target_box2d_dt = 1.0 / 60.0;
inline constexpr int target_box2d_substeps = 1;
inline constexpr int target_box2d_velocity_iterations = 8;
inline constexpr int target_box2d_position_iterations = 3;

struct SweepTargets {
    // Some Box2D point succeeded: without one neither target is measured.
    bool measured = false;

    // Target 1. Indices are into SweepResult::points.
    bool box2d_60hz_found = false; // the grid has Box2D at target_box2d_* settings
    std::size_t box2d_60hz = 0;
    bool error_target_measured = false; // found and it succeeded
    bool impulse_found = false;         // a successful impulse point costs no more
    std::size_t best_impulse = 0;       // of those, the smallest error (then cost)
    bool impulse_error_zero = false;    // its error is 0: the ratio uses sweep_error_floor
    double error_ratio = 0.0;           // Box2D's error / the impulse point's
    double cost_margin = 0.0;           // Box2D's cost / the impulse point's (>= 1)
    bool error_target_met = false;

    // Target 2: Box2D's front in cost order, how many of its points some
    // impulse point dominates, and the cheapest that none does.
    std::size_t box2d_front_size = 0;
    std::size_t box2d_front_dominated = 0;
    bool undominated_found = false;
    std::size_t first_undominated = 0;
    bool front_target_met = false;
};

// Judges both targets on the result's successful points; a pure function of
// the result (the fronts are recomputed, not read from on_front).
SweepTargets evaluate_targets(const SweepResult& result);

} // namespace impulse::harness
