#include "reference_comparison.h"

#include "engine.h"
#include "input_error.h"
#include "record.h"
#include "run.h"
#include "simulator.h"
#include "tunnelling.h"
#ifdef IMPULSE_WITH_BOX2D
#include "box2d_simulator.h"
#include "single_precision.h"
#endif

#include <cstdio>
#include <memory>
#include <utility>

namespace impulse::harness {

namespace {

// About six significant digits, as the verb's table shows times.
std::string six_digits(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", value);
    return buffer;
}

// The impulse engine refuses to go on where the seed model ends (a Zeno
// cascade, a resting contact: README, "Canonical scenes"). Scenes end before
// that with their own integrator; symplectic Euler loses a little speed in
// every flight, so its bounces die out sooner and can reach the limit inside
// the scene. The run then stops at the last step it completed and both runs
// are compared up to there: the observables of the bounces before are sound.
class StoppingSimulator final : public Simulator {
  public:
    explicit StoppingSimulator(std::unique_ptr<Simulator> inner) : inner_(std::move(inner)) {}

    std::string engine() const override { return inner_->engine(); }
    std::vector<std::pair<std::string, std::string>> settings() const override {
        return inner_->settings();
    }
    void step(double t0, double dt) override {
        if (stopped_at_) {
            return;
        }
        try {
            inner_->step(t0, dt);
        } catch (const InputError& error) {
            stopped_at_ = t0;
            reason_ = error.what();
        }
    }
    BodyState state(int index) const override { return inner_->state(index); }
    std::vector<TrajectoryEvent> take_events() override { return inner_->take_events(); }

    const std::optional<double>& stopped_at() const { return stopped_at_; }
    const std::string& reason() const { return reason_; }

  private:
    std::unique_ptr<Simulator> inner_;
    std::optional<double> stopped_at_;
    std::string reason_;
};

// Keeps the frames and events up to time `end`.
void truncate(Trajectory& trajectory, double end) {
    const auto after = [end](double t) { return t > end; };
    trajectory.frames.erase(
        std::remove_if(trajectory.frames.begin(), trajectory.frames.end(),
                       [&](const std::vector<double>& f) { return f.empty() || after(f.front()); }),
        trajectory.frames.end());
    trajectory.events.erase(std::remove_if(trajectory.events.begin(), trajectory.events.end(),
                                           [&](const TrajectoryEvent& e) { return after(e.t); }),
                            trajectory.events.end());
}

// The engine under study's run, or nullopt when it refused the scene's
// settings (c.skipped says so). The impulse engine runs in process so that a
// stop where the seed model ends keeps the steps before it (c.stopped and
// stopped_at say where); any other engine runs through run_engine.
std::optional<Trajectory> run_under_study(const EngineSpec& engine, const Scene& scene,
                                          const Overrides& overrides, ReferenceComparison& c,
                                          std::optional<double>& stopped_at) {
    if (engine.kind != EngineSpec::Kind::impulse) {
        EngineRun run = run_engine(engine, scene, overrides);
        if (run.outcome == EngineRun::Outcome::unsupported) {
            c.skipped = "unsupported by " + engine.name + ": " + run.message;
            return std::nullopt;
        }
        return std::move(run.trajectory);
    }
    const Scene impulse_scene = with_overrides(scene, overrides);
    StoppingSimulator impulse_simulator(make_impulse_simulator(impulse_scene));
    Trajectory impulse = record(impulse_simulator, impulse_scene);
    if (const std::optional<double> end = impulse_simulator.stopped_at()) {
        truncate(impulse, *end);
        stopped_at = end;
        c.stopped = "the impulse engine stopped in the step after t = " + six_digits(*end) +
                    " s (" + impulse_simulator.reason() +
                    "); both runs are compared up to t = " + six_digits(*end) + " s";
    }
    return impulse;
}

// A reference's column: its run of the scene with `overrides`, or its refusal.
EngineColumn reference_column(const EngineSpec& spec, const Scene& scene,
                              const Overrides& overrides, std::optional<double> stopped_at,
                              std::vector<std::string>& warnings) {
    EngineColumn column;
    column.name = spec.name;
    column.command = spec.command;
    EngineRun run = run_engine(spec, scene, overrides);
    warnings.insert(warnings.end(), run.warnings.begin(), run.warnings.end());
    if (run.outcome == EngineRun::Outcome::unsupported) {
        column.unsupported = "unsupported by " + spec.name + ": " + run.message;
        return column;
    }
    if (stopped_at) {
        truncate(run.trajectory, *stopped_at);
    }
    column.engine = run.trajectory.engine;
    column.settings = run.trajectory.solver;
    column.run = std::move(run.trajectory);
    return column;
}

} // namespace

EngineComparison compare_engines(const std::string& path, const CompareOptions& options) {
    const Scene scene = load_scene(path);
    EngineComparison c;
    c.name = scene.name;
    c.file = scene.file;
    c.warnings = scene.warnings;
    c.scene_integrator = integrator_name(scene.solver.integrator);
    Overrides overrides;
    overrides.dt = options.dt;
    c.dt = with_overrides(scene, overrides).dt;
    if (scene.box2d.observables.empty()) {
        return c; // nothing to compare: no engine is run
    }
    // The references get --dt only: each integrates as its own model does.
    const Overrides for_references = overrides;
    if (!options.scene_integrator) {
        overrides.integrator = Integrator::symplectic_euler;
    }
    if (options.engine.kind == EngineSpec::Kind::impulse) {
        refuse_tunnelling(with_overrides(scene, overrides));
    }
    // The fields run_under_study fills for impulse box2d.
    ReferenceComparison studied_fields;
    std::optional<double> stopped_at;
    std::optional<Trajectory> studied =
        run_under_study(options.engine, scene, overrides, studied_fields, stopped_at);
    EngineColumn first;
    first.name = options.engine.name;
    first.command = options.engine.command;
    if (!studied) {
        first.unsupported = studied_fields.skipped;
        c.engines.push_back(std::move(first));
        return c;
    }
    c.stopped = studied_fields.stopped;
    // The sentence run_under_study writes for two runs, said of all of them.
    if (const std::size_t both = c.stopped.find("both runs are compared");
        both != std::string::npos) {
        c.stopped.replace(both, 22, "every run is compared");
    }
    first.engine = studied->engine;
    first.settings = studied->solver;
    first.run = std::move(*studied);
    c.engines.push_back(std::move(first));
    for (const EngineSpec& reference : options.references) {
        c.engines.push_back(
            reference_column(reference, scene, for_references, stopped_at, c.warnings));
    }
    std::vector<ObservedRun> runs;
    std::vector<std::size_t> ran;
    for (std::size_t i = 0; i < c.engines.size(); ++i) {
        if (c.engines[i].run) {
            runs.push_back({&*c.engines[i].run, c.engines[i].name});
            ran.push_back(i);
        }
    }
    for (ObservableReadings& row : read_observables(scene, runs)) {
        std::vector<std::optional<double>> values(c.engines.size());
        for (std::size_t k = 0; k < ran.size(); ++k) {
            values[ran[k]] = row.values[k];
        }
        row.values = std::move(values);
        c.rows.push_back(std::move(row));
    }
    return c;
}

#ifdef IMPULSE_WITH_BOX2D
ReferenceComparison compare_with_box2d(const std::string& path, const ReferenceOptions& options) {
    const Scene scene = load_scene(path);
    ReferenceComparison c;
    c.name = scene.name;
    c.file = scene.file;
    c.engine = options.engine.name;
    c.warnings = scene.warnings;
    c.scene_integrator = integrator_name(scene.solver.integrator);
    // --dt is the step of both runs; the integrator is the engine under study's only.
    Overrides overrides;
    overrides.dt = options.dt;
    Scene box2d_scene = with_overrides(scene, overrides);
    Box2dSettings& settings = box2d_scene.box2d;
    settings.substeps = options.substeps.value_or(settings.substeps);
    settings.velocity_iterations =
        options.velocity_iterations.value_or(settings.velocity_iterations);
    settings.position_iterations =
        options.position_iterations.value_or(settings.position_iterations);
    // A scene Box2D cannot represent is refused even when it names nothing
    // to compare: asked to run it in Box2D, the answer is that it cannot.
    require_single_precision(box2d_scene, "Box2D",
                             box2d_scene.dt / static_cast<double>(settings.substeps));
    if (scene.box2d.observables.empty()) {
        return c;
    }
    if (!options.scene_integrator) {
        overrides.integrator = Integrator::symplectic_euler;
    }
    const Scene impulse_scene = with_overrides(scene, overrides);

    // Both refusals come before either run: a scene that would tunnel
    // unseen, and one Box2D cannot represent (single_precision.h).
    std::vector<std::string> warnings;
    const std::unique_ptr<Simulator> box2d_simulator = make_box2d_simulator(box2d_scene, warnings);
    refuse_tunnelling(impulse_scene);
    std::optional<double> stopped_at;
    std::optional<Trajectory> studied =
        run_under_study(options.engine, scene, overrides, c, stopped_at);
    if (!studied) {
        return c;
    }
    Trajectory impulse = std::move(*studied);
    Trajectory box2d = record(*box2d_simulator, box2d_scene);
    if (stopped_at) {
        truncate(box2d, *stopped_at);
    }

    c.dt = box2d_scene.dt;
    c.integrator = integrator_name(impulse_scene.solver.integrator);
    c.box2d = settings;
    c.impulse_engine = impulse.engine;
    c.box2d_engine = box2d.engine;
    c.warnings.insert(c.warnings.end(), warnings.begin(), warnings.end());
    c.rows = compare_observables(box2d_scene, impulse, box2d);
    c.impulse_run = std::move(impulse);
    c.box2d_run = std::move(box2d);
    return c;
}
#endif // IMPULSE_WITH_BOX2D

} // namespace impulse::harness
