// The many-body scene set (harness/scenes/scale/): a frictionless gas of 10 to
// 10^4 circles or boxes in a closed room. At every size the run must hold its
// conservation laws, and the work per body-step must not grow with N (the
// machine-independent face of "cost grows about as N log N").
#include "expectations.h"
#include "run.h"
#include "scene.h"
#include "simulator.h"

#include <catch2/catch.hpp>
#include <string>

using namespace impulse;
using namespace impulse::harness;

namespace {

std::string scale_scene(const std::string& gas, int n) {
    return std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes/scale/" + gas + "-" +
           std::to_string(n) + ".json";
}

int dynamic_count(const Scene& scene) {
    int n = 0;
    for (const SceneBody& body : scene.bodies) {
        n += body.is_static ? 0 : 1;
    }
    return n;
}

// Work per body-step over the first `steps` steps of the gas.
WorkCounters work_of(const Scene& scene, int steps) {
    const std::unique_ptr<Simulator> simulator = make_impulse_simulator(scene);
    for (int k = 0; k < steps; ++k) {
        simulator->step(k * scene.dt, scene.dt);
        simulator->take_events();
    }
    return simulator->work();
}

} // namespace

TEST_CASE("a gas conserves energy and its momentum changes only at the walls, at every size",
          "[unit][scale]") {
    const std::string gas = GENERATE(as<std::string>(), "gas-circles", "gas-boxes");
    const int n = GENERATE(10, 100, 1000, 10000);
    const Scene scene = load_scene(scale_scene(gas, n));
    REQUIRE(dynamic_count(scene) == n);
    REQUIRE(scene.solver.stepping == Stepping::local);
    const Trajectory trajectory = run_scene(scene);
    CHECK(trajectory.frames.size() == 121);
    // About one collision per body per second at this density: something happens.
    CHECK(trajectory.events.size() >= static_cast<std::size_t>(n / 2));
    const std::vector<ExpectationResult> results = evaluate_expectations(scene, trajectory);
    REQUIRE(results.size() >= 2);
    for (const ExpectationResult& r : results) {
        INFO(scene.name << ": " << r.what << " expected " << r.expected << " got " << r.actual
                        << " " << r.detail);
        CHECK(r.passed);
    }
}

TEST_CASE("work per body-step does not grow from 100 to 10000 bodies", "[unit][scale]") {
    const std::string gas = GENERATE(as<std::string>(), "gas-circles", "gas-boxes");
    const Scene small = load_scene(scale_scene(gas, 100));
    const Scene large = load_scene(scale_scene(gas, 10000));
    const int steps = 30;
    const WorkCounters w100 = work_of(small, steps);
    const WorkCounters w10000 = work_of(large, steps);
    const auto per_body_step = [&](long long count, int n) {
        return static_cast<double>(count) / (static_cast<double>(n) * steps);
    };
    INFO(gas << ": narrow-phase queries per body-step "
             << per_body_step(w100.narrow_phase_queries, 100) << " at N = 100, "
             << per_body_step(w10000.narrow_phase_queries, 10000) << " at N = 10000");
    CHECK(per_body_step(w10000.narrow_phase_queries, 10000) <=
          2.0 * per_body_step(w100.narrow_phase_queries, 100));
    // Integrations: once per body per step, plus the searches of its own
    // collisions, never once per collision anywhere in the world.
    CHECK(per_body_step(w10000.body_advances, 10000) <=
          2.0 * per_body_step(w100.body_advances, 100));
}
