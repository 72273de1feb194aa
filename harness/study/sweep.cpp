#include "sweep.h"

#include "expectations.h"
#include "input_error.h"
#include "number_format.h"
#include "record.h"
#include "run.h"
#include "simulator.h"
#include "single_precision.h"
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

namespace impulse::harness {

namespace {

bool is_exact_kind(Expectation::Kind kind) {
    return kind == Expectation::Kind::drop || kind == Expectation::Kind::corner_impact ||
           kind == Expectation::Kind::head_on;
}

double relative(double actual, double expected) {
    const double off = std::abs(actual - expected);
    if (!std::isfinite(off)) {
        return std::numeric_limits<double>::infinity();
    }
    return off / std::max(std::abs(expected), sweep_error_floor);
}

// The largest relative error over the exact-answer expectations.
double error_against_exact(const Scene& exact_only, const Trajectory& trajectory) {
    double worst = 0.0;
    for (const ExpectationResult& r : evaluate_expectations(exact_only, trajectory)) {
        // A check without numbers (a missing impact) has nothing to measure:
        // the run failed to produce the answer at all.
        if (!r.passed && r.expected == 0.0 && r.actual == 0.0) {
            return std::numeric_limits<double>::infinity();
        }
        worst = std::max(worst, relative(r.actual, r.expected));
    }
    return worst;
}

// The largest relative difference of the final frame's positions, angles and
// velocities (every column but t).
double error_against_reference(const Trajectory& reference, const Trajectory& trajectory) {
    if (trajectory.frames.empty() || reference.frames.empty()) {
        return std::numeric_limits<double>::infinity();
    }
    const std::vector<double>& a = trajectory.frames.back();
    const std::vector<double>& r = reference.frames.back();
    double worst = 0.0;
    for (std::size_t i = 1; i < a.size() && i < r.size(); ++i) {
        worst = std::max(worst, relative(a[i], r[i]));
    }
    return worst;
}

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
                point.error = error_of(trajectory);
            } else if (!same_work(work, point.work)) {
                point.work_identical = false;
            }
        }
        point.ok = true;
        point.cost_median = median_of(costs);
        const auto [lo, hi] = std::minmax_element(costs.begin(), costs.end());
        point.cost_spread = *hi - *lo;
    } catch (const InputError& e) {
        point.ok = false;
        point.failure = e.what();
        point.error = std::numeric_limits<double>::quiet_NaN();
    }
}

} // namespace

SweepConfig default_sweep_config(const Scene& scene) {
    SweepConfig config;
    for (const double hz : {30.0, 60.0, 120.0, 240.0, 480.0, 960.0}) {
        if (1.0 / hz <= scene.duration) {
            config.dts.push_back(1.0 / hz);
        }
    }
    config.integrators = {Integrator::euler, Integrator::symplectic_euler, Integrator::verlet,
                          Integrator::rk4};
    config.toi_methods = {TimeOfImpactMethod::bisection, TimeOfImpactMethod::secant};
    config.toi_tolerances = {1e-6, 1e-9, 1e-12};
    config.box2d_substeps = {1, 4};
    config.box2d_iterations = {{8, 3}, {30, 10}};
    return config;
}

std::string sweep_family(const SweepPoint& point) {
    if (point.box2d) {
        return "box2d";
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

// ccd sweeps every pair's whole motion at once; local stepping looks at one
// pair at a time (the scene loader refuses the two together).
std::vector<bool> ccd_settings(const Scene& scene, const SweepConfig& config) {
    std::vector<bool> ccds = config.ccd.empty() ? std::vector<bool>{scene.solver.ccd} : config.ccd;
    const bool any_ccd = std::find(ccds.begin(), ccds.end(), true) != ccds.end();
    if (any_ccd && scene.solver.stepping == Stepping::local) {
        throw InputError(scene.file, "solver.stepping",
                         "ccd on is not available with \"stepping\": \"local\" in this version "
                         "(local stepping looks at one pair at a time); sweep with --ccd off, "
                         "or use \"stepping\": \"world\"");
    }
    return ccds;
}

// The grid. ccd varies fastest, so a point with it sits next to the same
// point without.
std::vector<SweepPoint> impulse_points(const SweepConfig& config, const std::vector<bool>& ccds) {
    std::vector<SweepPoint> points;
    for (const double dt : config.dts) {
        for (const Integrator integrator : config.integrators) {
            for (const TimeOfImpactMethod toi : config.toi_methods) {
                for (const double tolerance : config.toi_tolerances) {
                    for (const bool ccd : ccds) {
                        SweepPoint p;
                        p.dt = dt;
                        p.integrator = integrator;
                        p.toi = toi;
                        p.toi_tolerance = tolerance;
                        p.ccd = ccd;
                        p.family = sweep_family(p);
                        points.push_back(p);
                    }
                }
            }
        }
    }
    return points;
}

// Box2D's points, after the impulse engine's (none in a build without Box2D).
void add_box2d_points(const SweepConfig& config, std::vector<SweepPoint>& points) {
#ifdef IMPULSE_WITH_BOX2D
    if (config.box2d) {
        for (const double dt : config.dts) {
            for (const int substeps : config.box2d_substeps) {
                for (const auto& [velocity, position] : config.box2d_iterations) {
                    SweepPoint p;
                    p.box2d = true;
                    p.dt = dt;
                    p.substeps = substeps;
                    p.velocity_iterations = velocity;
                    p.position_iterations = position;
                    p.family = sweep_family(p);
                    points.push_back(p);
                }
            }
        }
    }
#else
    (void)config;
    (void)points;
#endif
}

// The scene with only its exact-answer expectations: what the error is
// measured against when it declares any.
Scene with_exact_expectations_only(const Scene& scene) {
    Scene exact_only = scene;
    exact_only.expectations.clear();
    for (const Expectation& x : scene.expectations) {
        if (is_exact_kind(x.kind)) {
            exact_only.expectations.push_back(x);
        }
    }
    return exact_only;
}

// A run at the finest settings, for a scene without exact answers; says in
// `description` what it is.
Trajectory reference_run(const Scene& scene, const SweepConfig& config, bool any_ccd,
                         std::string& description) {
    const double finest = *std::min_element(config.dts.begin(), config.dts.end()) / 4.0;
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
    result.repeats = config.repeats;
    result.simulated_duration = static_cast<double>(step_count(scene)) * scene.dt;

    const std::vector<bool> ccds = ccd_settings(scene, config);
    const bool any_ccd = std::find(ccds.begin(), ccds.end(), true) != ccds.end();
    result.points = impulse_points(config, ccds);
    add_box2d_points(config, result.points);
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

    // What the error is measured against.
    const Scene exact_only = with_exact_expectations_only(scene);
    result.against_exact = !exact_only.expectations.empty();
    Trajectory reference;
    if (result.against_exact) {
        result.error_reference =
            "against the exact answers the scene declares (" +
            plural(exact_only.expectations.size(), "expectation", "expectations") +
            "): largest |actual - expected| / max(|expected|, " + format_double(sweep_error_floor) +
            ")";
    } else {
        reference = reference_run(scene, config, any_ccd, result.error_reference);
    }

    const std::size_t total = result.points.size();
    for (std::size_t i = 0; i < total; ++i) {
        SweepPoint& point = result.points[i];
        if (result.against_exact) {
            measure(scene, point, config.repeats,
                    [&](const Trajectory& t) { return error_against_exact(exact_only, t); });
        } else {
            measure(scene, point, config.repeats,
                    [&](const Trajectory& t) { return error_against_reference(reference, t); });
        }
        if (progress) {
            progress(i + 1, total, point);
        }
    }
    mark_fronts(result.points);
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

std::vector<std::size_t> pareto_front(const std::vector<std::pair<double, double>>& cost_error) {
    std::vector<std::size_t> order(cost_error.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        order[i] = i;
    }
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return cost_error[a] != cost_error[b] ? cost_error[a] < cost_error[b] : a < b;
    });
    std::vector<std::size_t> front;
    for (const std::size_t i : order) {
        const auto [cost, error] = cost_error[i];
        if (std::isnan(cost) || std::isnan(error)) {
            continue;
        }
        bool dominated = false;
        for (std::size_t j = 0; j < cost_error.size() && !dominated; ++j) {
            const auto [c, e] = cost_error[j];
            dominated = c <= cost && e <= error && (c < cost || e < error);
        }
        if (!dominated) {
            front.push_back(i);
        }
    }
    return front;
}

void mark_fronts(std::vector<SweepPoint>& points) {
    std::map<std::string, std::vector<std::size_t>> families;
    for (std::size_t i = 0; i < points.size(); ++i) {
        points[i].on_front = false;
        if (points[i].ok && !std::isnan(points[i].error)) {
            families[points[i].family].push_back(i);
        }
    }
    for (const auto& [family, members] : families) {
        std::vector<std::pair<double, double>> cost_error;
        for (const std::size_t i : members) {
            cost_error.emplace_back(points[i].cost_median, points[i].error);
        }
        for (const std::size_t k : pareto_front(cost_error)) {
            points[members[k]].on_front = true;
        }
    }
}

namespace {

// A point a front can use: it ran and its error means something.
bool measured_point(const SweepPoint& p) {
    return p.ok && !std::isnan(p.error) && !std::isnan(p.cost_median);
}

bool dominates(const SweepPoint& a, const SweepPoint& b) {
    return a.cost_median <= b.cost_median && a.error <= b.error &&
           (a.cost_median < b.cost_median || a.error < b.error);
}

bool is_box2d_60hz(const SweepPoint& p) {
    return p.box2d && p.substeps == target_box2d_substeps &&
           p.velocity_iterations == target_box2d_velocity_iterations &&
           p.position_iterations == target_box2d_position_iterations &&
           std::abs(p.dt - target_box2d_dt) <= 1e-12 * target_box2d_dt;
}

} // namespace

SweepTargets evaluate_targets(const SweepResult& result) {
    SweepTargets t;
    const std::vector<SweepPoint>& points = result.points;
    for (const SweepPoint& p : points) {
        t.measured = t.measured || (p.box2d && measured_point(p));
    }
    if (!t.measured) {
        return t;
    }

    // Target 1. A --dt list typed in decimal lands within rounding of 1/60,
    // not on it: the closest such dt is the 60 Hz point.
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (is_box2d_60hz(points[i]) &&
            (!t.box2d_60hz_found || std::abs(points[i].dt - target_box2d_dt) <
                                        std::abs(points[t.box2d_60hz].dt - target_box2d_dt))) {
            t.box2d_60hz_found = true;
            t.box2d_60hz = i;
        }
    }
    t.error_target_measured = t.box2d_60hz_found && measured_point(points[t.box2d_60hz]);
    if (t.error_target_measured) {
        const SweepPoint& b = points[t.box2d_60hz];
        for (std::size_t i = 0; i < points.size(); ++i) {
            const SweepPoint& p = points[i];
            if (p.box2d || !measured_point(p) || p.cost_median > b.cost_median) {
                continue;
            }
            const SweepPoint* best = t.impulse_found ? &points[t.best_impulse] : nullptr;
            if (best == nullptr || p.error < best->error ||
                (p.error == best->error && p.cost_median < best->cost_median)) {
                t.impulse_found = true;
                t.best_impulse = i;
            }
        }
        if (t.impulse_found) {
            const SweepPoint& p = points[t.best_impulse];
            // An error of exactly 0 says only that it is below what the
            // measurement resolves: the floor gives a ratio it is at least.
            t.impulse_error_zero = p.error == 0.0;
            t.error_ratio = b.error / (t.impulse_error_zero ? sweep_error_floor : p.error);
            t.cost_margin = b.cost_median / p.cost_median;
            t.error_target_met = t.error_ratio >= target_error_ratio;
        }
    }

    // Target 2. An impulse point that dominates a Box2D point is dominated by
    // or equal to one on the impulse front, so checking every impulse point
    // checks the front.
    std::vector<std::size_t> box2d;
    std::vector<std::pair<double, double>> cost_error;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (points[i].box2d && measured_point(points[i])) {
            box2d.push_back(i);
            cost_error.emplace_back(points[i].cost_median, points[i].error);
        }
    }
    for (const std::size_t k : pareto_front(cost_error)) {
        const SweepPoint& b = points[box2d[k]];
        ++t.box2d_front_size;
        const bool dominated = std::any_of(points.begin(), points.end(), [&](const SweepPoint& p) {
            return !p.box2d && measured_point(p) && dominates(p, b);
        });
        if (dominated) {
            ++t.box2d_front_dominated;
        } else if (!t.undominated_found) {
            t.undominated_found = true;
            t.first_undominated = box2d[k];
        }
    }
    t.front_target_met = t.box2d_front_size > 0 && !t.undominated_found;
    return t;
}

} // namespace impulse::harness
