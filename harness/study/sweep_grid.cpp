// The sweep's grid: which points run, in which order (sweep_grid.h).
#include "sweep_grid.h"

#include "input_error.h"
#include "sweep_measures.h"

#include <algorithm>

namespace impulse::harness {

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
    // A pile stepped by time-stepping from its start has no time-of-impact
    // search: the toi method and tolerance would only repeat each point.
    if (is_pile_scene(scene) && time_stepping_from_start(scene.solver)) {
        config.toi_methods = {scene.solver.toi};
        config.toi_tolerances = {scene.solver.toi_tolerance};
    }
    return config;
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

// Another engine's grid: what reaches it as a modified scene (dt, integrator,
// toi_tolerance), the scene's own toi method and ccd.
std::vector<SweepPoint> engine_points(const SweepConfig& config, const Scene& scene) {
    std::vector<SweepPoint> points;
    for (const double dt : config.dts) {
        for (const Integrator integrator : config.integrators) {
            for (const double tolerance : config.toi_tolerances) {
                SweepPoint p;
                p.kind = config.engine.kind;
                p.engine = config.engine.name;
                p.dt = dt;
                p.integrator = integrator;
                p.toi = scene.solver.toi;
                p.toi_tolerance = tolerance;
                p.ccd = scene.solver.ccd;
                p.family = sweep_family(p);
                points.push_back(p);
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

// Every other reference's points, after Box2D's: its own settings, or each of
// its sub-step counts, at every dt.
void add_reference_points(const SweepConfig& config, std::vector<SweepPoint>& points) {
    for (const SweepReference& reference : config.references) {
        const std::vector<int> substeps =
            reference.substeps.empty() ? std::vector<int>{0} : reference.substeps;
        for (const double dt : config.dts) {
            for (const int n : substeps) {
                SweepPoint p;
                p.kind = reference.spec.kind;
                p.engine = reference.name;
                p.reference = reference.name;
                p.dt = dt;
                p.substeps = n;
                p.family = sweep_family(p);
                points.push_back(p);
            }
        }
    }
}

} // namespace impulse::harness
