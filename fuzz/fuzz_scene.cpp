// Fuzz target: the scene loader, parse_scene(text, "fuzz.json"), and the
// engine on the scenes that load.
//
// Bad input must end in InputError (normal here). A scene that loads must keep
// the loader's promises (finite numbers, positive masses and inertias, a step
// count within max_steps). A small one (at most max_fuzz_steps steps and
// max_fuzz_bodies bodies) is then simulated as `impulse run` does it: every
// step, the trajectory written and read back, the expectations evaluated. The
// engine may refuse a scene with InputError (a Zeno cascade, a search that
// does not converge); a run that would take long is abandoned by a work budget
// (deterministic, so a rerun of a saved input does the same) with a wall-clock
// cap behind it, and the engine's bound on collisions in one step is lowered,
// so slow inputs are skipped rather than reported as timeouts.
#include "expectations.h"
#include "fuzz_support.h"
#include "input_error.h"
#include "number_format.h"
#include "record.h"
#include "simulator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace {

using impulse::fuzz::finding;
using namespace impulse::harness;

constexpr long long max_fuzz_steps = 2000;
constexpr std::size_t max_fuzz_bodies = 50;
// A run is abandoned, between two steps, after this much engine work
// (narrow-phase queries + time-of-impact iterations + body advances: the same
// count on every machine, so a saved input reruns the same way) or this much
// time. The clock is what stops resting and simultaneous contact, whose
// matrix solves the counters do not see: `stack` (1800 steps, 10 boxes
// resting) takes about 5 s under the sanitizers and is cut after a quarter of
// its steps; most canonical scenes run to the end. IMPULSE_FUZZ_VERBOSE=1
// prints each run's steps, work, time and outcome, to tune these.
constexpr long long max_fuzz_work = 1'000'000;
constexpr auto max_fuzz_wall_time = std::chrono::milliseconds(500);
// The budget is checked between steps, so one step must stay short too: the
// engine's own bound on collisions in one step (4096) lets a Zeno cascade of
// ten stacked boxes take 0.6 s in a release build and over 10 s under the
// sanitizers. The canonical scenes need at most 8 in a step.
constexpr int max_fuzz_collisions_per_step = 64;

struct OverBudget {};

long long work_of(const impulse::WorkCounters& w) {
    return w.narrow_phase_queries + w.toi_iterations + w.body_advances;
}

// The impulse simulator, stopped by the budget between steps.
class BudgetedSimulator final : public Simulator {
  public:
    explicit BudgetedSimulator(const Scene& scene)
        : inner_(make_impulse_simulator(scene)), start_(std::chrono::steady_clock::now()) {}

    std::string engine() const override { return inner_->engine(); }
    std::vector<std::pair<std::string, std::string>> settings() const override {
        return inner_->settings();
    }
    void step(double t0, double dt) override {
        if (work_of(inner_->work()) > max_fuzz_work || elapsed() > max_fuzz_wall_time) {
            throw OverBudget{};
        }
        inner_->step(t0, dt);
        ++steps_;
    }
    impulse::BodyState state(int index) const override { return inner_->state(index); }
    std::vector<TrajectoryEvent> take_events() override { return inner_->take_events(); }
    impulse::WorkCounters work() const override { return inner_->work(); }

    long long steps() const { return steps_; }
    std::chrono::steady_clock::duration elapsed() const {
        return std::chrono::steady_clock::now() - start_;
    }

  private:
    std::unique_ptr<Simulator> inner_;
    std::chrono::steady_clock::time_point start_;
    long long steps_ = 0;
};

bool finite(impulse::Vec2 v) {
    return std::isfinite(v.x) && std::isfinite(v.y);
}

void check_loaded(const Scene& scene) {
    const long long steps = step_count(scene);
    if (steps < 1 || steps > max_steps) {
        finding("parse_scene accepted a scene of " + std::to_string(steps) + " steps");
    }
    if (!(scene.dt > 0.0) || !std::isfinite(scene.duration) || !finite(scene.gravity) ||
        !(scene.restitution >= 0.0 && scene.restitution <= 1.0)) {
        finding("parse_scene accepted a bad dt, duration, gravity or restitution");
    }
    if (scene.sha256.size() != 64 || scene.listed_bodies > scene.bodies.size()) {
        finding("parse_scene gave a bad sha256 or listed_bodies");
    }
    for (const SceneBody& body : scene.bodies) {
        const bool numbers_finite = finite(body.position) && std::isfinite(body.angle) &&
                                    finite(body.velocity) && std::isfinite(body.angular_velocity);
        const bool mass_ok =
            body.is_static ? body.mass == 0.0 : std::isfinite(body.mass) && body.mass > 0.0;
        const bool inertia_ok = body.is_static || !body.rotation
                                    ? body.inertia == 0.0
                                    : std::isfinite(body.inertia) && body.inertia > 0.0;
        if (!numbers_finite || !mass_ok || !inertia_ok) {
            finding("parse_scene accepted body '" + body.name +
                    "' with a non-finite state or a bad mass or inertia");
        }
    }
}

// As `impulse run SCENE`: run, write the trajectory, check the expectations.
void simulate(Scene scene) {
    scene.solver.max_collisions_per_step =
        std::min(scene.solver.max_collisions_per_step, max_fuzz_collisions_per_step);
    static const bool verbose = std::getenv("IMPULSE_FUZZ_VERBOSE") != nullptr;
    BudgetedSimulator simulator(scene);
    const char* outcome = "ran to the end";
    Trajectory trajectory;
    try {
        trajectory = record(simulator, scene);
    } catch (const OverBudget&) {
        outcome = "over budget";
    } catch (const InputError&) {
        outcome = "refused by the engine"; // its documented answer
    }
    if (verbose) {
        std::fprintf(
            stderr, "fuzz_scene: '%s' %lld/%lld steps, work %lld, %.0f ms: %s\n",
            scene.name.c_str(), simulator.steps(), step_count(scene), work_of(simulator.work()),
            std::chrono::duration<double, std::milli>(simulator.elapsed()).count(), outcome);
    }
    if (simulator.steps() < step_count(scene)) {
        return;
    }
    impulse::fuzz::check_round_trip(trajectory); // write_trajectory throws on NaN or infinity
    for (const ExpectationResult& result : evaluate_expectations(scene, trajectory)) {
        if (!result.passed) {
            // What `impulse run` prints for a failed expectation.
            (void)format_double(result.expected);
            (void)format_double(result.actual);
        }
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Scene scene;
    try {
        scene = parse_scene(impulse::fuzz::text_of(data, size), "fuzz.json");
    } catch (const InputError&) {
        return 0;
    }
    check_loaded(scene);
    if (step_count(scene) <= max_fuzz_steps && scene.bodies.size() <= max_fuzz_bodies) {
        simulate(scene);
    }
    return 0;
}
