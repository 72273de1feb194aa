// Dense contact at scale (issue 14, "Targets"): microseconds of CPU per
// body-step of the impulse engine and of Box2D 2.4.1 on the same frictionless
// piles (harness/scenes/scale/pile-{discs,boxes}-N.json), in the same process,
// for two phases:
//
//   settling  every iteration builds the simulator afresh (timing paused) and
//             steps the first S seconds, while the pile falls and packs;
//   settled   the simulator is stepped, untimed, to T seconds (once per
//             process), then each iteration is one step of the resting pile.
//
// Box2D runs as box2d_simulator.cpp sets it up: friction 0, restitution
// threshold 0, the scene's 8 velocity and 3 position iterations, no sleeping.
// Beside the times: the deepest overlap of each engine on the true shapes
// (overlap.h) over every frame the benchmark stepped, and the impulse engine's
// islands and solver sweeps (matrix products) per step, and the overlap
// guard's share of those products. Run with scripts/bench-scale; the table at
// the end is the README's (markdown). Wall-clock numbers on a shared machine are
// noisy: the ratio of two runs made moments apart is what the table is for.
#include "body.h"
#include "box2d_simulator.h"
#include "overlap.h"
#include "progress.h"
#include "scene.h"
#include "simulator.h"

#include <algorithm>
#include <benchmark/benchmark.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace impulse;
using namespace impulse::harness;

namespace {

const std::vector<int> sizes{100, 1000, 10000};
const std::vector<std::string> piles{"pile-discs", "pile-boxes"};
const std::vector<std::string> phases{"settling", "settled"};
const std::vector<std::string> engines{"impulse", "box2d"};

// The phases' times, in simulated seconds (--pile_settling=S, --pile_settled=T):
// the scale scenes release their piles at rest and declare them at rest after 6 s.
double settling_seconds = 3.0;
double settled_seconds = 6.0;

std::string scene_path(const std::string& pile, int n) {
    return std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes/scale/" + pile + "-" +
           std::to_string(n) + ".json";
}

int dynamic_bodies(const Scene& scene) {
    int n = 0;
    for (const SceneBody& body : scene.bodies) {
        n += body.is_static ? 0 : 1;
    }
    return n;
}

long long steps_in(double seconds, double dt) {
    return std::llround(seconds / dt);
}

std::unique_ptr<Simulator> simulator_for(const Scene& scene, bool box2d) {
    std::vector<std::string> warnings; // clamps: a pile released at rest never reaches them
    return box2d ? make_box2d_simulator(scene, warnings) : make_impulse_simulator(scene);
}

// The deepest overlap of the simulator's bodies now, on the true shapes (0: none).
double deepest_now(const Scene& scene, const Simulator& simulator) {
    std::vector<Transform> poses;
    poses.reserve(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        poses.push_back(transform_of(simulator.state(static_cast<int>(i))));
    }
    const std::optional<Overlap> overlap = deepest_overlap(scene.bodies, poses);
    return overlap ? overlap->depth : 0.0;
}

// One step of a run the benchmark watches: the simulator's collisions handed
// over (part of a step, as in gas_bench.cpp), then, with the clock stopped,
// the overlap measured and the progress bar told.
struct Stepper {
    const Scene& scene;
    Simulator& simulator;
    double until; // the simulated time the progress bar counts to
    double t = 0.0;
    double deepest = 0.0;

    void step(benchmark::State* timed, bool measure) {
        simulator.step(t, scene.dt);
        t += scene.dt;
        static_cast<void>(simulator.take_events());
        if (!measure) {
            return;
        }
        if (timed != nullptr) {
            timed->PauseTiming();
        }
        deepest = std::max(deepest, deepest_now(scene, simulator));
        note_simulated_time(t, until);
        if (timed != nullptr) {
            timed->ResumeTiming();
        }
    }
};

// `since`: the counters when the measured phase began (zeros for a fresh simulator).
void report(benchmark::State& state, const Scene& scene, const Simulator& simulator,
            long long steps_per_iteration, double deepest, const WorkCounters& since = {}) {
    const WorkCounters now = simulator.work();
    const long long taken = now.steps - since.steps;
    const double steps = static_cast<double>(taken > 0 ? taken : 1);
    state.counters["bodies"] = dynamic_bodies(scene);
    state.counters["steps"] = static_cast<double>(steps_per_iteration);
    state.counters["overlap"] = deepest;
    if (simulator.engine().rfind("impulse", 0) == 0) {
        state.counters["islands"] = static_cast<double>(now.islands - since.islands) / steps;
        state.counters["sweeps"] =
            static_cast<double>(now.solver_sweeps - since.solver_sweeps) / steps;
        state.counters["guard"] =
            static_cast<double>(now.overlap_guard_products - since.overlap_guard_products) / steps;
        state.counters["unconverged"] =
            static_cast<double>(now.unconverged_islands - since.unconverged_islands);
    }
}

// Settling: a fresh simulator per iteration (built with the clock stopped),
// stepped through the first settling_seconds. The overlap is measured in every
// frame of the first iteration (the runs are deterministic, so all are alike).
void settling_runs(benchmark::State& state, const std::string& path, bool box2d) {
    const Scene scene = load_scene(path);
    const long long steps = steps_in(settling_seconds, scene.dt);
    Progress progress(scene.name + (box2d ? " box2d" : " impulse") + " settling",
                      progress_wanted(false));
    double deepest = 0.0;
    std::unique_ptr<Simulator> simulator;
    bool first = true;
    for (auto _ : state) {
        state.PauseTiming();
        simulator = simulator_for(scene, box2d);
        Stepper stepper{scene, *simulator, settling_seconds};
        state.ResumeTiming();
        for (long long k = 0; k < steps; ++k) {
            stepper.step(&state, first);
        }
        deepest = std::max(deepest, stepper.deepest);
        first = false;
    }
    report(state, scene, *simulator, steps, deepest);
}

// A simulator that refuses the scene or stops (an InputError) ends its
// benchmark with the engine's sentence instead of ending the process.
template <typename Run> void guarded(benchmark::State& state, const Run& run) {
    try {
        run();
    } catch (const std::exception& error) {
        state.SkipWithError(error.what());
    }
}

void settling(benchmark::State& state, const std::string& path, bool box2d) {
    guarded(state, [&] { settling_runs(state, path, box2d); });
}

// The settled piles, one per benchmark, kept for the process: Google Benchmark
// calls a function several times while it picks an iteration count, and the
// pile should settle only once.
struct SettledPile {
    Scene scene;
    std::unique_ptr<Simulator> simulator;
    std::unique_ptr<Stepper> stepper;
    WorkCounters at_rest; // the counters when the pile reached settled_seconds
};

SettledPile& settled_pile(const std::string& path, bool box2d) {
    static std::map<std::pair<std::string, bool>, SettledPile> cache;
    const std::pair<std::string, bool> key{path, box2d};
    SettledPile& pile = cache[key];
    if (!pile.simulator) {
        pile.scene = load_scene(path);
        pile.simulator = simulator_for(pile.scene, box2d);
        pile.stepper =
            std::make_unique<Stepper>(Stepper{pile.scene, *pile.simulator, settled_seconds});
        Progress progress(pile.scene.name + (box2d ? " box2d" : " impulse") + " to rest",
                          progress_wanted(false));
        const long long steps = steps_in(settled_seconds, pile.scene.dt);
        try {
            for (long long k = 0; k < steps; ++k) {
                pile.stepper->step(nullptr, true);
            }
        } catch (...) {
            cache.erase(key); // a pile that stopped on the way is not settled
            throw;
        }
        pile.stepper->deepest = 0.0; // the settled phase's own overlap from here on
        pile.at_rest = pile.simulator->work();
    }
    return pile;
}

// Settled: one step per iteration of a pile that has come to rest.
void settled(benchmark::State& state, const std::string& path, bool box2d) {
    guarded(state, [&] {
        SettledPile& pile = settled_pile(path, box2d);
        for (auto _ : state) {
            pile.stepper->step(&state, true);
        }
        report(state, pile.scene, *pile.simulator, 1, pile.stepper->deepest, pile.at_rest);
    });
}

// What the table shows of one benchmark.
struct Measured {
    double per_body_step = 0.0; // µs of CPU
    double overlap = 0.0;       // m
    double sweeps = -1.0;       // per step; impulse only
    double guard = -1.0;        // the overlap guard's share of sweeps
    double islands = -1.0;
    std::string stopped; // the engine's sentence when it refused or stopped
};

// Keeps each benchmark's median CPU time per body-step for the table at the end.
class TableReporter : public benchmark::ConsoleReporter {
  public:
    void ReportRuns(const std::vector<Run>& runs) override {
        ConsoleReporter::ReportRuns(runs);
        for (const Run& run : runs) {
            keep(run);
        }
    }

    void print_table() const;

  private:
    void keep(const Run& run) {
        if (run.error_occurred) {
            measured_[run.run_name.function_name].stopped = run.error_message;
            return;
        }
        const bool aggregate = run.run_type == Run::RT_Aggregate;
        if (aggregate && run.aggregate_name != "median") {
            return;
        }
        const auto bodies = run.counters.find("bodies");
        const auto steps = run.counters.find("steps");
        if (bodies == run.counters.end() || steps == run.counters.end()) {
            return;
        }
        const std::string name = run.run_name.function_name;
        // A median, when there is one, wins over the single repetitions.
        if (!aggregate && measured_.count(name) != 0) {
            return;
        }
        // CPU seconds per iteration, then per body-step in microseconds.
        const double seconds =
            run.GetAdjustedCPUTime() / benchmark::GetTimeUnitMultiplier(run.time_unit);
        Measured m;
        m.per_body_step = 1e6 * seconds / (bodies->second.value * steps->second.value);
        m.overlap = counter(run, "overlap", 0.0);
        m.sweeps = counter(run, "sweeps", -1.0);
        m.guard = counter(run, "guard", -1.0);
        m.islands = counter(run, "islands", -1.0);
        measured_[name] = m;
    }

    static double counter(const Run& run, const char* key, double otherwise) {
        const auto found = run.counters.find(key);
        return found == run.counters.end() ? otherwise : found->second.value;
    }

    const Measured* find(const std::string& pile, int n, const std::string& phase,
                         const std::string& engine) const {
        const auto found =
            measured_.find(pile + "/" + std::to_string(n) + "/" + phase + "/" + engine);
        return found == measured_.end() ? nullptr : &found->second;
    }

    std::map<std::string, Measured> measured_;
};

std::string number(double value, const char* format) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, format, value);
    return buffer;
}

// Overlap ratio Box2D / impulse: "> 1e9" style when impulse never overlapped
// measurably (its deepest is 0 or below 1e-15 m).
std::string overlap_ratio(double theirs, double ours) {
    if (ours <= 1e-15) {
        return theirs > 0.0 ? "> " + number(theirs / 1e-15, "%.0e") : "-";
    }
    return number(theirs / ours, "%.3g");
}

// One cell of a row: the value, "-" when not measured, or a footnote number
// when the engine stopped (its sentence is printed under the table).
std::string cell(const Measured* m, double value, const char* format,
                 std::vector<std::string>& stops) {
    if (m != nullptr && !m->stopped.empty()) {
        const auto known = std::find(stops.begin(), stops.end(), m->stopped);
        const auto index = static_cast<std::size_t>(known - stops.begin()) + 1;
        if (known == stops.end()) {
            stops.push_back(m->stopped);
        }
        return "stopped [" + std::to_string(index) + "]";
    }
    return m == nullptr || value < 0.0 ? std::string("-") : number(value, format);
}

// A table row: pile, N, phase, then both engines side by side.
std::string row_text(const std::string& pile, int n, const std::string& phase, const Measured* ours,
                     const Measured* theirs, std::vector<std::string>& stops) {
    const Measured none;
    const Measured& o = ours != nullptr ? *ours : none;
    const Measured& b = theirs != nullptr ? *theirs : none;
    const bool both =
        ours != nullptr && theirs != nullptr && o.stopped.empty() && b.stopped.empty();
    const std::vector<std::string> cells{pile,
                                         std::to_string(n),
                                         phase,
                                         cell(ours, o.per_body_step, "%.3f", stops),
                                         cell(theirs, b.per_body_step, "%.3f", stops),
                                         both ? number(o.per_body_step / b.per_body_step, "%.2f")
                                              : "-",
                                         cell(ours, o.overlap, "%.1e", stops),
                                         cell(theirs, b.overlap, "%.1e", stops),
                                         both ? overlap_ratio(b.overlap, o.overlap) : "-",
                                         cell(ours, o.sweeps, "%.1f", stops),
                                         cell(ours, o.guard, "%.1f", stops),
                                         cell(ours, o.islands, "%.1f", stops)};
    std::string text = "|";
    for (const std::string& c : cells) {
        text += " " + c + " |";
    }
    return text;
}

// Markdown: one row per pile, N and phase, the footnotes, then each pile's 10^4 / 10^2.
void TableReporter::print_table() const {
    std::printf("\n| pile | N | phase | impulse µs/body-step | Box2D µs/body-step | impulse / "
                "Box2D | impulse overlap (m) | Box2D overlap (m) | Box2D / impulse overlap | "
                "sweeps/step | of which guard | islands/step |\n");
    std::printf("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    std::vector<std::string> stops;
    for (const std::string& pile : piles) {
        for (const int n : sizes) {
            for (const std::string& phase : phases) {
                const Measured* ours = find(pile, n, phase, "impulse");
                const Measured* theirs = find(pile, n, phase, "box2d");
                if (ours != nullptr || theirs != nullptr) {
                    std::printf("%s\n", row_text(pile, n, phase, ours, theirs, stops).c_str());
                }
            }
        }
    }
    std::printf("\n");
    for (std::size_t k = 0; k < stops.size(); ++k) {
        std::printf("[%zu] %s\n", k + 1, stops[k].c_str());
    }
    for (const std::string& pile : piles) {
        for (const std::string& phase : phases) {
            const Measured* small = find(pile, 100, phase, "impulse");
            const Measured* large = find(pile, 10000, phase, "impulse");
            if (small != nullptr && large != nullptr && small->stopped.empty() &&
                large->stopped.empty()) {
                std::printf("%s, %s: impulse per body-step at N = 10000 / at N = 100: %.2f "
                            "(target <= 2)\n",
                            pile.c_str(), phase.c_str(),
                            large->per_body_step / small->per_body_step);
            }
        }
    }
    std::printf("Targets (issue 14): impulse / Box2D <= 2 at N = 1000 and 10000; Box2D / "
                "impulse overlap >= 1000. Settling = the first %g s from release, rebuilt "
                "per iteration; settled = one step at a time from %g s on.\n",
                settling_seconds, settled_seconds);
}

// --pile_settling=S and --pile_settled=T, taken out of argv before Google
// Benchmark reads the rest; false on a bad value.
bool read_own_flags(int& argc, char** argv) {
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        double* target = nullptr;
        std::string value;
        for (const auto& [flag, seconds] :
             {std::pair<std::string, double*>{"--pile_settling=", &settling_seconds},
              {"--pile_settled=", &settled_seconds}}) {
            if (arg.rfind(flag, 0) == 0) {
                target = seconds;
                value = arg.substr(flag.size());
            }
        }
        if (target == nullptr) {
            argv[kept++] = argv[i];
            continue;
        }
        char* end = nullptr;
        const double seconds = std::strtod(value.c_str(), &end);
        if (value.empty() || *end != '\0' || !(seconds > 0.0) || !std::isfinite(seconds)) {
            std::fprintf(stderr, "impulse_pile_bench: %s: expected a positive number of seconds\n",
                         arg.c_str());
            return false;
        }
        *target = seconds;
    }
    argc = kept;
    return true;
}

} // namespace

int main(int argc, char** argv) {
    if (!read_own_flags(argc, argv)) {
        return 2;
    }
    for (const std::string& pile : piles) {
        for (const int n : sizes) {
            const std::string path = scene_path(pile, n);
            if (!std::filesystem::exists(path)) {
                std::fprintf(stderr, "impulse_pile_bench: %s is missing; its rows are skipped\n",
                             path.c_str());
                continue;
            }
            for (const std::string& engine : engines) {
                const bool box2d = engine == "box2d";
                const std::string name = pile + "/" + std::to_string(n);
                // Settling runs are long: one per iteration, repeated only by
                // --benchmark_repetitions; the small pile a few times over.
                benchmark::RegisterBenchmark((name + "/settling/" + engine).c_str(), settling, path,
                                             box2d)
                    ->Unit(benchmark::kMillisecond)
                    ->Iterations(n <= 100 ? 10 : 1);
                benchmark::RegisterBenchmark((name + "/settled/" + engine).c_str(), settled, path,
                                             box2d)
                    ->Unit(benchmark::kMicrosecond);
            }
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
