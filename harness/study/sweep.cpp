#include "sweep.h"

#include "engine.h"
#include "engine_failure.h"
#include "expectations.h"
#include "ignored_overrides.h"
#include "input_error.h"
#include "number_format.h"
#include "record.h"
#include "run.h"
#include "simulator.h"
#include "single_precision.h"
#include "sweep_grid.h"
#include "sweep_measures.h"
#include "text.h"
#include "tunnelling.h"
#ifdef IMPULSE_WITH_BOX2D
#include "box2d_simulator.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>

namespace impulse::harness {

namespace {

double median_of(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    if (n == 0) {
        return 0.0;
    }
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

bool same_work(const WorkCounters& a, const WorkCounters& b) {
    return a.steps == b.steps && a.narrow_phase_queries == b.narrow_phase_queries &&
           a.toi_iterations == b.toi_iterations && a.collisions == b.collisions;
}

// The scene as one grid point runs it.
Scene scene_for(const Scene& scene, const SweepPoint& point) {
    Overrides overrides;
    overrides.dt = point.dt;
    Scene s = scene;
    if (!point.box2d) {
        overrides.integrator = point.integrator;
        overrides.toi_tolerance = point.toi_tolerance;
        s.solver.toi = point.toi;
        s.solver.ccd = point.ccd;
    } else {
        s.box2d.substeps = point.substeps;
        s.box2d.velocity_iterations = point.velocity_iterations;
        s.box2d.position_iterations = point.position_iterations;
    }
    return with_overrides(std::move(s), overrides);
}

std::unique_ptr<Simulator> simulator_for(const Scene& scene, bool box2d) {
    if (!box2d) {
        return make_impulse_simulator(scene);
    }
#ifdef IMPULSE_WITH_BOX2D
    std::vector<std::string> warnings; // clamp warnings do not change the measurement
    return make_box2d_simulator(scene, warnings);
#else
    throw InputError(scene.file, "", "this tool was built without Box2D");
#endif
}

// Seconds per simulated second: their median and spread (max - min).
void set_costs(SweepPoint& point, const std::vector<double>& costs) {
    point.cost_median = median_of(costs);
    const auto [lo, hi] = std::minmax_element(costs.begin(), costs.end());
    point.cost_spread = *hi - *lo;
}

template <typename Measure>
void measure(const Scene& scene, SweepPoint& point, int repeats, const Measure& error_of) {
    std::vector<double> costs;
    try {
        const Scene effective = scene_for(scene, point);
        const double simulated = static_cast<double>(step_count(effective)) * effective.dt;
        for (int k = 0; k < repeats; ++k) {
            const auto start = std::chrono::steady_clock::now();
            std::unique_ptr<Simulator> simulator = simulator_for(effective, point.box2d);
            const Trajectory trajectory = record(*simulator, effective);
            const auto stop = std::chrono::steady_clock::now();
            costs.push_back(std::chrono::duration<double>(stop - start).count() / simulated);
            WorkCounters work = simulator->work();
            if (point.box2d) {
                work.steps = step_count(effective) * effective.box2d.substeps;
            }
            if (k == 0) {
                point.work = work;
                error_of(trajectory, point);
            } else if (!same_work(work, point.work)) {
                point.work_identical = false;
            }
        }
        point.ok = true;
        set_costs(point, costs);
    } catch (const InputError& e) {
        point.ok = false;
        point.failure = e.what();
        point.error = std::numeric_limits<double>::quiet_NaN();
    }
}

// The overrides one grid point of another engine sends it: the grid is what
// reaches an engine as a modified scene (docs/engine-protocol.md).
Overrides engine_overrides(const SweepPoint& point) {
    Overrides overrides;
    overrides.dt = point.dt;
    overrides.integrator = point.integrator;
    overrides.toi_tolerance = point.toi_tolerance;
    return overrides;
}

// A point of another engine, run through the protocol. Its cost is what the
// engine reports when every repeat reports it (a median of mixed clocks would
// mean nothing), otherwise the process's wall time. A refusal (exit 3) skips
// the point at its first repeat, and exit 1 (the engine's model cannot go on,
// as impulse's own stops) makes it a failed point; any other failure is
// run_engine's InputError, for the whole sweep: the engine is broken, not
// the point.
template <typename Measure>
void measure_engine(const EngineSpec& engine, const Scene& scene, SweepPoint& point, int repeats,
                    const Measure& error_of) {
    // A reference gets the grid's dt only: the rest is its own algorithm.
    Overrides overrides = engine_overrides(point);
    if (!point.reference.empty()) {
        overrides = Overrides{};
        overrides.dt = point.dt;
    }
    const Scene effective = with_overrides(scene, overrides);
    const double simulated = static_cast<double>(step_count(effective)) * effective.dt;
    std::vector<double> reported, process;
    std::vector<std::optional<long long>> steps;
    for (int k = 0; k < repeats; ++k) {
        EngineRun run;
        try {
            run = run_engine(engine, scene, overrides);
        } catch (const EngineFailure& e) {
            if (!e.model_stopped) {
                throw;
            }
            point.ok = false;
            point.failure = e.what();
            point.error = std::numeric_limits<double>::quiet_NaN();
            return;
        }
        if (run.outcome == EngineRun::Outcome::unsupported) {
            point.skipped = true;
            point.failure = "unsupported by " + engine.name + ": " + run.message;
            point.error = std::numeric_limits<double>::quiet_NaN();
            return;
        }
        process.push_back(run.seconds / simulated);
        if (run.cost) {
            reported.push_back(run.cost->seconds / simulated);
        }
        steps.push_back(run.cost ? run.cost->steps : std::nullopt);
        if (k == 0) {
            error_of(run.trajectory, point);
        }
    }
    point.ok = true;
    const bool all_reported = reported.size() == process.size();
    point.cost_source = all_reported                                ? SweepCost::engine_reported
                        : engine.kind == EngineSpec::Kind::external ? SweepCost::process_time
                                                                    : SweepCost::in_process;
    set_costs(point, all_reported ? reported : process);
    point.work_counted = steps.front().has_value();
    point.work.steps = steps.front().value_or(0);
    point.work_identical =
        std::all_of(steps.begin(), steps.end(), [&](const auto& s) { return s == steps.front(); });
}

} // namespace

const char* sweep_cost_name(SweepCost cost) {
    switch (cost) {
    case SweepCost::engine_reported:
        return "engine";
    case SweepCost::process_time:
        return "process";
    case SweepCost::in_process:
        break;
    }
    return "in-process";
}

bool is_reference_point(const SweepPoint& point) {
    return point.box2d || !point.reference.empty();
}

std::string sweep_family(const SweepPoint& point) {
    if (point.box2d) {
        return "box2d";
    }
    if (!point.reference.empty()) {
        return point.reference;
    }
    if (point.kind != EngineSpec::Kind::impulse) {
        return point.engine + " " + integrator_name(point.integrator);
    }
    return std::string("impulse ") + integrator_name(point.integrator) + "/" +
           toi_method_name(point.toi) + (point.ccd ? "+ccd" : "");
}

namespace {

// What Box2D cannot represent is the scene's error, up front, not a failed
// point (nor Box2D's abort).
void require_box2d_can_run(const Scene& scene, const SweepConfig& config) {
#ifdef IMPULSE_WITH_BOX2D
    if (config.box2d) {
        for (const double dt : config.dts) {
            for (const int substeps : config.box2d_substeps) {
                require_single_precision(scene, "Box2D", dt / static_cast<double>(substeps));
            }
        }
    }
#else
    (void)scene;
    (void)config;
#endif
}

// The reference's engine as one point runs it: `--substeps N` before the
// scene's path, which the harness appends.
EngineSpec reference_spec(const SweepConfig& config, const SweepPoint& point) {
    for (const SweepReference& reference : config.references) {
        if (reference.name == point.reference) {
            EngineSpec spec = reference.spec;
            if (point.substeps > 0) {
                spec.command.push_back("--substeps");
                spec.command.push_back(std::to_string(point.substeps));
            }
            return spec;
        }
    }
    throw InputError("", "", "the sweep has no reference named " + point.reference);
}

// Another engine's reference: itself at the finest dt / 4, with the scene's
// own solver settings (an integrator it may not have is not asked for).
Trajectory engine_reference_run(const Scene& scene, const EngineSpec& engine, double finest,
                                std::string& description) {
    Overrides o;
    o.dt = finest;
    EngineRun run = run_engine(engine, scene, o);
    if (run.outcome == EngineRun::Outcome::unsupported) {
        throw InputError(scene.file, "",
                         "the sweep's reference run (dt " + format_double(finest) +
                             " s) is unsupported by " + engine.name + ": " + run.message);
    }
    description = "against a reference run at the finest settings (" + engine.name + ", dt " +
                  format_double(finest) +
                  " s, the scene's own solver settings): largest relative difference of the "
                  "final frame's positions and velocities";
    return std::move(run.trajectory);
}

// A run at the finest settings, for a scene without exact answers; says in
// `description` what it is.
Trajectory reference_run(const Scene& scene, const SweepConfig& config, bool any_ccd,
                         std::string& description) {
    const double finest = *std::min_element(config.dts.begin(), config.dts.end()) / 4.0;
    if (config.engine.kind != EngineSpec::Kind::impulse) {
        return engine_reference_run(scene, config.engine, finest, description);
    }
    Scene s = scene;
    s.solver.toi = TimeOfImpactMethod::secant;
    s.solver.ccd = any_ccd; // a reference that tunnels is no reference
    Overrides o;
    o.dt = finest;
    o.integrator = Integrator::rk4;
    o.toi_tolerance = 1e-14;
    s = with_overrides(std::move(s), o);
    std::unique_ptr<Simulator> simulator = make_impulse_simulator(s);
    Trajectory reference = record(*simulator, s); // a refusal here is the sweep's error
    description = "against a reference run at the finest settings (impulse rk4, "
                  "dt " +
                  format_double(finest) + " s, secant, toi_tolerance 1e-14, ccd " +
                  (any_ccd ? "on" : "off") +
                  "): largest relative difference of the final frame's positions "
                  "and velocities";
    return reference;
}

// Where the engine under study's costs came from, one sentence; empty for
// the impulse engine, whose cost is measured as it always was.
std::string cost_source(const SweepConfig& config, const std::vector<SweepPoint>& points) {
    if (config.engine.kind == EngineSpec::Kind::impulse) {
        return "";
    }
    std::size_t reported = 0, timed = 0;
    for (const SweepPoint& p : points) {
        if (is_reference_point(p)) {
            continue; // a reference's cost is its own, said per point
        }
        reported += p.ok && p.cost_source == SweepCost::engine_reported ? 1 : 0;
        timed += p.ok && p.cost_source == SweepCost::process_time ? 1 : 0;
    }
    if (reported > 0 && timed == 0) {
        return "cost: the engine's own (its trajectory's cost.seconds)";
    }
    if (reported == 0) {
        return "cost: process wall time (the engine reports none)";
    }
    return "cost: the engine's own (its trajectory's cost.seconds) at " +
           plural(reported, "point", "points") +
           ", process wall time (the engine reports none) at " + plural(timed, "point", "points");
}

// What every point's error is measured against, said in `result`; the
// reference run when the scene has neither exact answers nor a pile's
// expectations.
struct ErrorBasis {
    Scene exact_only;
    Trajectory reference;
};

ErrorBasis error_basis(const Scene& scene, const SweepConfig& config, bool any_ccd,
                       SweepResult& result) {
    ErrorBasis basis{with_exact_expectations_only(scene), {}};
    result.against_exact = !basis.exact_only.expectations.empty();
    result.pile = !result.against_exact && is_pile_scene(scene);
    if (result.against_exact) {
        result.error_reference =
            "against the exact answers the scene declares (" +
            plural(basis.exact_only.expectations.size(), "expectation", "expectations") +
            "): largest |actual - expected| / max(|expected|, " + format_double(sweep_error_floor) +
            ")";
    } else if (result.pile) {
        result.error_reference = "deepest overlap: the deepest interpenetration of any pair in "
                                 "any frame, in metres (as max-overlap measures it)";
        result.energy_reference =
            "energy gained: the largest rise of kinetic + potential energy over the run above "
            "the lowest energy before it, relative to the energy's scale at t = 0 (a pile's "
            "energy is fixed by no closed form, so the error is the gain physics forbids)";
        result.cost_unit = "seconds per body-step (per dynamic body, per step of the scene's dt " +
                           format_double(scene.dt) + " s)";
    } else {
        basis.reference = reference_run(scene, config, any_ccd, result.error_reference);
    }
    return basis;
}

// The titles the legend and the verdicts use, in the points' order.
std::vector<std::pair<std::string, std::string>> reference_titles(const SweepConfig& config,
                                                                  const SweepResult& result) {
    std::vector<std::pair<std::string, std::string>> titles;
    if (std::any_of(result.points.begin(), result.points.end(),
                    [](const SweepPoint& p) { return p.box2d; })) {
        titles.emplace_back("box2d", "Box2D 2.4.1");
    }
    for (const SweepReference& reference : config.references) {
        titles.emplace_back(reference.name, reference.title);
    }
    return titles;
}

std::size_t dynamic_bodies(const Scene& scene) {
    return static_cast<std::size_t>(std::count_if(scene.bodies.begin(), scene.bodies.end(),
                                                  [](const SceneBody& b) { return !b.is_static; }));
}

// Measures every point in order. For an outside engine under study, the
// first time step's runs show which grid settings it ignores (their
// trajectories are identical), and the later points that would only repeat
// one run are skipped with the reason (ignored_overrides.h).
template <typename Measure>
void measure_points(const Scene& scene, const SweepConfig& config, double cost_scale,
                    const Measure& error_of, const SweepProgress& progress,
                    std::vector<SweepPoint>& points) {
    const bool outside_engine = config.engine.kind != EngineSpec::Kind::impulse;
    FirstStepRuns first{config.integrators.size(), config.toi_tolerances.size(), {}};
    first.digests.assign(outside_engine ? first.integrators * first.tolerances : 0, 0);
    const auto measured = [&](const Trajectory& t, SweepPoint& point) {
        error_of(t, point);
        const auto index = static_cast<std::size_t>(&point - points.data());
        if (index < first.digests.size()) {
            first.digests[index] = digest_of(t);
        }
    };
    const std::size_t total = points.size();
    for (std::size_t i = 0; i < total; ++i) {
        SweepPoint& point = points[i];
        if (point.skipped) {
            // a repeat of another point (skip_repeated_points)
        } else if (point.box2d || point.kind == EngineSpec::Kind::impulse) {
            measure(scene, point, config.repeats, error_of);
        } else if (!point.reference.empty()) {
            measure_engine(reference_spec(config, point), scene, point, config.repeats, error_of);
        } else {
            measure_engine(config.engine, scene, point, config.repeats, measured);
        }
        point.cost_median *= cost_scale;
        point.cost_spread *= cost_scale;
        if (i + 1 == first.digests.size()) {
            skip_repeated_points(points, config, ignored_overrides(first));
        }
        if (progress) {
            progress(i + 1, total, point);
        }
    }
}

} // namespace

SweepResult run_sweep(const Scene& scene, const SweepConfig& config,
                      const SweepProgress& progress) {
    if (config.dts.empty()) {
        throw InputError(scene.file, "dt", "the sweep has no time step to try");
    }
    if (config.repeats < 1) {
        throw InputError(scene.file, "", "the sweep needs at least one repeat");
    }
    SweepResult result;
    result.scene = scene.name;
    result.engine = config.engine.name;
    result.repeats = config.repeats;
    result.simulated_duration = static_cast<double>(step_count(scene)) * scene.dt;

    const bool impulse_grid = config.engine.kind == EngineSpec::Kind::impulse;
    const std::vector<bool> ccds =
        impulse_grid ? ccd_settings(scene, config) : std::vector<bool>{scene.solver.ccd};
    const bool any_ccd = std::find(ccds.begin(), ccds.end(), true) != ccds.end();
    result.points = impulse_grid ? impulse_points(config, ccds) : engine_points(config, scene);
    add_box2d_points(config, result.points);
    add_reference_points(config, result.points);
    if (result.points.empty()) {
        throw InputError(scene.file, "", "the sweep's grid is empty");
    }
    // Every dt must suit the scene: a bad option, not a failed point.
    for (const double dt : config.dts) {
        Overrides o;
        o.dt = dt;
        (void)with_overrides(scene, o);
    }
    require_box2d_can_run(scene, config);
    const ErrorBasis basis = error_basis(scene, config, any_ccd, result);
    result.references = reference_titles(config, result);
    // A pile's cost per body-step at the scene's own dt: seconds per
    // simulated second times dt / N, the same scale for every point.
    const double cost_scale =
        result.pile
            ? scene.dt / static_cast<double>(std::max<std::size_t>(dynamic_bodies(scene), 1))
            : 1.0;

    const auto error_of = [&](const Trajectory& t, SweepPoint& point) {
        if (result.pile) {
            point.error = deepest_overlap_over_run(scene, t);
            point.energy_error = energy_gain_over_run(scene, t);
        } else {
            point.error = result.against_exact ? error_against_exact(basis.exact_only, t)
                                               : error_against_reference(basis.reference, t);
        }
    };
    measure_points(scene, config, cost_scale, error_of, progress, result.points);
    mark_fronts(result.points);
    result.cost_source = cost_source(config, result.points);
    return result;
}

std::vector<std::string> tunnelling_warnings(const Scene& scene, const SweepConfig& config) {
    const bool ccd_off = config.ccd.empty() ? !scene.solver.ccd
                                            : std::find(config.ccd.begin(), config.ccd.end(),
                                                        false) != config.ccd.end();
    std::vector<std::string> warnings;
    if (!ccd_off) {
        return warnings;
    }
    for (const double dt : config.dts) {
        Overrides o;
        o.dt = dt;
        Scene s = with_overrides(scene, o);
        s.solver.ccd = false;
        if (const std::optional<TunnellingRefusal> r = tunnelling_refusal(s)) {
            warnings.push_back(scene.file + ": the points at dt " + format_double(dt) +
                               ", ccd off can tunnel: " + r->path + ": " + r->message);
        }
    }
    return warnings;
}

} // namespace impulse::harness
