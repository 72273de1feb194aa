// Scale: microseconds per body-step of the impulse engine and of Box2D on the
// same frictionless gas (harness/scenes/scale/), in the same process, side by
// side, and their ratio. Run with scripts/bench-scale. Wall-clock numbers on a
// shared machine are noisy; the ratio of two runs made moments apart is what
// the table is for.
#include "box2d_simulator.h"
#include "scene.h"
#include "simulator.h"

#include <benchmark/benchmark.h>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace impulse::harness;

namespace {

const std::vector<int> sizes{10, 100, 1000, 10000};
const std::vector<std::string> gases{"gas-circles", "gas-boxes"};

std::string scene_path(const std::string& gas, int n) {
    return std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes/scale/" + gas + "-" +
           std::to_string(n) + ".json";
}

int dynamic_bodies(const Scene& scene) {
    int n = 0;
    for (const SceneBody& body : scene.bodies) {
        n += body.is_static ? 0 : 1;
    }
    return n;
}

// Steps the gas for as long as Google Benchmark asks; one iteration is one step.
void step_gas(benchmark::State& state, const std::string& path, bool box2d) {
    const Scene scene = load_scene(path);
    std::vector<std::string> warnings;
    std::unique_ptr<Simulator> simulator =
        box2d ? make_box2d_simulator(scene, warnings) : make_impulse_simulator(scene);
    double t = 0.0;
    long long collisions = 0;
    for (auto _ : state) {
        simulator->step(t, scene.dt);
        t += scene.dt;
        // Both simulators record their collisions; handing them over is part of a step.
        collisions += static_cast<long long>(simulator->take_events().size());
    }
    const double steps = static_cast<double>(state.iterations());
    state.counters["bodies"] = dynamic_bodies(scene);
    state.counters["collisions_per_step"] = static_cast<double>(collisions) / steps;
}

// Keeps each benchmark's median CPU time per step for the table at the end.
class TableReporter : public benchmark::ConsoleReporter {
  public:
    void ReportRuns(const std::vector<Run>& runs) override {
        ConsoleReporter::ReportRuns(runs);
        for (const Run& run : runs) {
            if (run.error_occurred) {
                continue;
            }
            const bool aggregate = run.run_type == Run::RT_Aggregate;
            if (aggregate && run.aggregate_name != "median") {
                continue;
            }
            std::string name = run.run_name.function_name;
            const auto bodies = run.counters.find("bodies");
            if (bodies == run.counters.end()) {
                continue;
            }
            // CPU seconds per step, then per body-step in microseconds.
            const double seconds =
                run.GetAdjustedCPUTime() / benchmark::GetTimeUnitMultiplier(run.time_unit);
            const double per_body = 1e6 * seconds / bodies->second.value;
            // A median, when there is one, wins over the single repetitions.
            if (aggregate || times_.count(name) == 0) {
                times_[name] = per_body;
            }
        }
    }

    void print_table() const {
        std::printf("\nmicroseconds of CPU per body-step (median), same process, same gas\n");
        std::printf("%-12s %7s %12s %12s %10s\n", "gas", "N", "impulse", "box2d", "ratio");
        for (const std::string& gas : gases) {
            double per_body_100 = 0.0;
            double per_body_10000 = 0.0;
            for (const int n : sizes) {
                const auto ours = times_.find(gas + "/" + std::to_string(n) + "/impulse");
                const auto theirs = times_.find(gas + "/" + std::to_string(n) + "/box2d");
                if (ours == times_.end()) {
                    continue;
                }
                if (n == 100) {
                    per_body_100 = ours->second;
                } else if (n == 10000) {
                    per_body_10000 = ours->second;
                }
                if (theirs == times_.end()) {
                    std::printf("%-12s %7d %12.3f %12s %10s\n", gas.c_str(), n, ours->second, "-",
                                "-");
                } else {
                    std::printf("%-12s %7d %12.3f %12.3f %10.2f\n", gas.c_str(), n, ours->second,
                                theirs->second, ours->second / theirs->second);
                }
            }
            if (per_body_100 > 0.0 && per_body_10000 > 0.0) {
                std::printf("%-12s impulse per body-step at N = 10000 / at N = 100: %.2f\n",
                            gas.c_str(), per_body_10000 / per_body_100);
            }
        }
        std::printf("ratio = impulse / box2d: below 1 the engine is faster.\n");
    }

  private:
    std::map<std::string, double> times_;
};

} // namespace

int main(int argc, char** argv) {
    for (const std::string& gas : gases) {
        for (const int n : sizes) {
            const std::string path = scene_path(gas, n);
            const std::string name = gas + "/" + std::to_string(n);
            benchmark::RegisterBenchmark((name + "/impulse").c_str(), step_gas, path, false)
                ->Unit(benchmark::kMicrosecond);
            benchmark::RegisterBenchmark((name + "/box2d").c_str(), step_gas, path, true)
                ->Unit(benchmark::kMicrosecond);
        }
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    TableReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    reporter.print_table();
    benchmark::Shutdown();
    return 0;
}
