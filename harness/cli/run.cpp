// `impulse run SCENE`: simulate one scene and write its trajectory.
#include "run.h"

#include "cli.h"
#include "engine.h"
#include "engine_option.h"
#include "expectations.h"
#include "gate.h"
#include "input_error.h"
#include "number_format.h"
#include "output_path.h"
#include "progress.h"
#include "project_options.h"
#include "record.h"
#include "run_json.h"

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace impulse::harness::cli {

namespace {
constexpr const char* run_help =
    R"(usage: impulse run SCENE [--out FILE] [--engine NAME | --engine-command CMD] [--root DIR] [--dt S] [--integrator NAME] [--toi-tolerance S] [--json FILE] [--quiet]

Simulates SCENE (an impulse/scene@1 file, or the name of a project scene) in the project's first
engine (the impulse engine without a project file) and writes its
impulse/trajectory@1 to FILE (atomically) or to standard output.

  --out FILE            write the trajectory here instead of standard output (a
                        regular file, never one in goldens/; - is standard output)
  --engine NAME         the project's engine NAME instead of its first (or the
                        built-in impulse, box2d or chipmunk)
  --engine-command 'PROGRAM ARGS'
                        an engine that speaks docs/engine-protocol.md, run in the
                        current folder, instead of one in impulse.json
  --root DIR            the project's folder (default: the first impulse.json
                        found from the current folder upwards)
  --dt S                time step in seconds (overrides the scene's dt)
  --integrator NAME     euler, symplectic-euler, verlet or rk4
  --toi-tolerance S     time-of-impact tolerance in seconds
  --json FILE           also write the run's result as JSON (impulse/run@1,
                        docs/formats.md): scene, engine, steps, frames, events,
                        partial, each expectation with its message, the --out
                        path. - is standard output, which then needs --out FILE
                        for the trajectory. Same rules as --out for the path
  --quiet               no progress bar (drawn on standard error only when that is a
                        terminal, after about a second of work)

Overrides change the physics and are recorded in the trajectory's solver block.
The scene's declared expectations are checked: exit 1 when one fails (the
trajectory is still written), 2 for bad input, an engine that fails, or one
that refuses the scene as unsupported. A run that stops early (a refused
resting contact, a Zeno cascade, too many collisions) still writes what it
simulated, marked "partial" with the reason and the last frame's time, and
exits 2 (with --json, its "partial" says so and "expectations" is null).
)";
// --json FILE: "-" only when the trajectory goes to a file, and never the
// trajectory's own file.
void check_json_file(const std::string& json_out, const std::string& trajectory_out,
                     const std::vector<std::string>& goldens) {
    if (is_standard_output(json_out) && is_standard_output(trajectory_out)) {
        throw UsageError("--json - and the trajectory cannot both go to standard output: "
                         "give the trajectory a file with --out FILE");
    }
    if (same_output_file(json_out, trajectory_out)) {
        throw UsageError("--json and --out name the same file, " + json_out);
    }
    check_output_file("--json", json_out, goldens);
}

// The trajectory (--out or standard output), then the result (--json).
void write_run(const RunResult& result, const std::vector<std::string>& goldens,
               const std::optional<std::string>& json_out, std::ostream& out) {
    const std::string text = write_trajectory(*result.trajectory);
    const std::string file = result.trajectory_file.value_or(standard_output);
    // Nothing that diff, check or render would refuse, on a file or on stdout.
    require_readable_size(text, result.trajectory_file.value_or("standard output"));
    write_output_file("--out", file, text, goldens, out);
    if (json_out) {
        write_output_file("--json", *json_out, run_json(result), goldens, out);
    }
}

} // namespace

int run_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    const Arguments a = parse_arguments(args,
                                        {"--out", "--engine", "--engine-command", "--root", "--dt",
                                         "--integrator", "--toi-tolerance", "--json"},
                                        {"--help", "--quiet"});
    if (a.has_flag("--help")) {
        out << run_help;
        return exit_ok;
    }
    if (a.positional.size() != 1) {
        throw UsageError("needs exactly one SCENE, got " + std::to_string(a.positional.size()));
    }
    Overrides overrides;
    if (const auto dt = a.option("--dt")) {
        overrides.dt = positive_seconds("--dt", *dt);
    }
    if (const auto tol = a.option("--toi-tolerance")) {
        overrides.toi_tolerance = positive_seconds("--toi-tolerance", *tol);
    }
    if (const auto name = a.option("--integrator")) {
        Integrator integrator{};
        if (!integrator_from_name(*name, integrator)) {
            throw UsageError("--integrator must be euler, symplectic-euler, verlet or rk4, got '" +
                             *name + "'");
        }
        overrides.integrator = integrator;
    }

    const Project project = find_project(a.option("--root"));
    const EngineSpec engine = chosen_engine(project, a);
    const std::vector<std::string> goldens = protected_folders(project);
    const std::string trajectory_out = a.option("--out").value_or(standard_output);
    const std::optional<std::string> json_out = a.option("--json");
    check_output_file("--out", trajectory_out, goldens);
    if (json_out) {
        check_json_file(*json_out, trajectory_out, goldens);
    }
    const Scene scene = load_scene(scene_argument(project, a.positional.front()));
    for (const std::string& warning : scene.warnings) {
        err << "warning: " << warning << "\n";
    }
    RunResult result{&scene, nullptr, engine.name,
                     is_standard_output(trajectory_out) ? std::nullopt
                                                        : std::optional(trajectory_out),
                     std::nullopt};
    const Trajectory trajectory = [&] {
        const Progress progress("run " + scene.name, progress_wanted(a.has_flag("--quiet")));
        EngineRun ran;
        try {
            ran = run_engine(engine, scene, overrides);
        } catch (const StoppedRun& stopped) {
            // What was simulated up to the stop, marked partial, so the user
            // can see (and render) the moment it stopped; still exit 2.
            result.trajectory = &stopped.trajectory();
            write_run(result, goldens, json_out, out);
            throw;
        }
        if (ran.outcome == EngineRun::Outcome::unsupported) {
            // Nothing to write: the engine does not model what the scene asks.
            throw InputError(scene.file, "", "unsupported by " + engine.name + ": " + ran.message);
        }
        return std::move(ran.trajectory);
    }();
    // The scene's declared answers are checked on every run, overrides included:
    // a coarser dt that breaks an exact answer is worth knowing.
    result.trajectory = &trajectory;
    result.expectations = evaluate_expectations(scene, trajectory);
    write_run(result, goldens, json_out, out);
    int failed = 0;
    for (const ExpectationResult& r : *result.expectations) {
        if (!r.passed) {
            ++failed;
            err << scene.file << ": " << expectation_message(r) << "\n";
        }
    }
    return failed > 0 ? exit_failed : exit_ok;
}

} // namespace impulse::harness::cli
