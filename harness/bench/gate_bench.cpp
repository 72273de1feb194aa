// How long the gate takes: the whole gate over every canonical scene, each
// scene's run, and loading plus diffing one golden. Run with scripts/bench.
#include "atomic_file.h"
#include "compare.h"
#include "gate.h"
#include "run.h"

#include <benchmark/benchmark.h>
#include <filesystem>

using namespace impulse::harness;

namespace {

GateRoot source_root() {
    GateRoot root;
    root.root = IMPULSE_SOURCE_DIR;
    return root;
}

void whole_gate(benchmark::State& state) {
    const GateRoot root = source_root();
    const std::vector<std::string> scenes = canonical_scenes(root);
    CheckOptions options;
    options.jobs = static_cast<int>(state.range(0));
    for (auto _ : state) {
        const std::vector<SceneCheck> checks = check_scenes(root, scenes, options);
        benchmark::DoNotOptimize(checks.data());
    }
    state.counters["scenes"] = static_cast<double>(scenes.size());
}
BENCHMARK(whole_gate)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The largest golden: the worst case of reading and comparing one file.
std::string largest_golden(const GateRoot& root) {
    std::string best;
    std::uintmax_t size = 0;
    for (const std::string& scene : canonical_scenes(root)) {
        const std::string golden = root.golden_path(std::filesystem::path(scene).stem().string());
        std::error_code error;
        const std::uintmax_t s = std::filesystem::file_size(golden, error);
        if (!error && s > size) {
            size = s;
            best = golden;
        }
    }
    return best;
}

void load_and_diff_golden(benchmark::State& state) {
    const std::string golden = largest_golden(source_root());
    if (golden.empty()) {
        state.SkipWithError("no goldens: run scripts/regen-goldens first");
        return;
    }
    const Trajectory reference = read_trajectory(read_file(golden, 1u << 28, ""), golden);
    for (auto _ : state) {
        const Trajectory t = read_trajectory(read_file(golden, 1u << 28, ""), golden);
        const Comparison c = compare(reference, t, std::nullopt);
        benchmark::DoNotOptimize(c.identical);
    }
    state.SetLabel(std::filesystem::path(golden).filename().string());
}
BENCHMARK(load_and_diff_golden)->Unit(benchmark::kMicrosecond)->UseRealTime();

void run_one_scene(benchmark::State& state, const std::string& path) {
    const Scene scene = load_scene(path);
    for (auto _ : state) {
        const Trajectory t = run_scene(scene);
        benchmark::DoNotOptimize(t.frames.data());
    }
}

} // namespace

int main(int argc, char** argv) {
    for (const std::string& path : canonical_scenes(source_root())) {
        benchmark::RegisterBenchmark(("run/" + std::filesystem::path(path).stem().string()).c_str(),
                                     run_one_scene, path)
            ->Unit(benchmark::kMillisecond);
    }
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
