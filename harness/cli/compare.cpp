// `impulse compare [SCENE...] [--with LIST]`: impulse box2d generalised to
// every reference engine (reference_engines.h): each scene run in the engine
// under study and in each reference, the observables its "box2d" block names
// in one column per engine beside the exact answer (engine_comparison.h).
#include "atomic_file.h"
#include "cli.h"
#include "comparison_run.h"
#include "engine_comparison.h"
#include "engine_option.h"
#include "gate.h"
#include "input_error.h"
#include "output_path.h"
#include "progress.h"
#include "project_options.h"
#include "reference_comparison.h"
#include "reference_engines.h"
#include "reference_option.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness::cli {

namespace {

constexpr const char* compare_help =
    R"(usage: impulse compare [SCENE...] [--with LIST] [options]

Runs each scene in the engine under study (the impulse engine unless --engine
says otherwise) and in every reference engine on this machine, and shows the
observables the scene's "box2d" block names (impact times, apex heights and
ratios, post-impact velocities, the restitution residual, momentum, angular
momentum and energy) in one column per engine beside the exact answer of
docs/physics.md, with each engine's error against it. With no SCENE, every
canonical scene; a SCENE is a name or a path.

The references (docs/references.md), each as fair as it allows (friction 0,
restitution e, no sleeping, no damping) with every setting printed:
  box2d-2.4   Box2D 2.4.1, built in (as impulse box2d runs it)
  box2d-3     Box2D v3 (npm box2d3-wasm 5.2.0), a Node program, 4 sub-steps
  chipmunk    Chipmunk2D 7.0.3, built in
  rapier      Rapier2D (npm @dimforge/rapier2d-deterministic-compat 0.20.0), a Node program
scripts/setup installs them all. The Node ones are looked for in
IMPULSE_REFERENCES_DIR when it is set, else PREFIX/share/impulse/references
beside an installed tool, else the source tree's references/.

The engine under study integrates with symplectic-euler, Box2D's own, unless
--scene-integrator; the references integrate as they do. When the impulse
engine stops (a Zeno cascade, a resting contact), every run is compared up to
its last complete step. Only box2d-2.4 is judged, against the tolerances of
the scene's box2d block (they were measured for it); the other references are
there for scale and never fail a comparison. A reference that refuses a scene
shows "unsupported" in its column.

  --with LIST          the references, comma-separated, or none (default: every one
                       on this machine; the others are listed as skipped with the
                       command that installs them); one not on this machine is exit 2
  --root DIR           the project's folder (as impulse box2d)
  --engine NAME        the engine under study (as impulse box2d)
  --engine-command 'PROGRAM ARGS'
                       an engine speaking docs/engine-protocol.md as the engine under study
  --dt S               the time step of every run
  --box2d-3-substeps N Box2D v3's sub-steps per step (default 4, its own default;
                       given to its program as --substeps N, so printed in its command)
  --scene-integrator   the engine under study uses the scene's own integrator
  --json               the comparison as JSON (impulse/engine-comparison@1)
  --junit FILE         JUnit XML: a testcase per scene and engine (- is standard
                       output; the table then goes to standard error)
  --out DIR            every run as a trajectory, DIR/SCENE.ENGINE.json, for impulse
                       diff and render (regular files only, never in goldens/)
  --summary            only the summary lines, no tables (scripts/gate)
  --quiet              no progress bar

Exit: 0 box2d-2.4 within tolerance on every scene (or not asked for), 1 a row
outside it, 2 bad input, a requested reference not on this machine, or an engine
that failed on a scene (crashed, timed out, wrote what is not a trajectory).
)";

// Every run of every scene into dir; nothing is written when one of the
// paths is refused (a link, a FIFO), so the folder is never half new.
void write_runs(const std::string& dir, const std::vector<EngineComparison>& comparisons,
                const std::optional<std::string>& junit) {
    std::vector<std::pair<std::string, std::string>> files;
    for (const EngineComparison& c : comparisons) {
        for (const EngineColumn& e : c.engines) {
            if (e.run) {
                const std::string base = (std::filesystem::path(dir) / c.name).string();
                files.emplace_back(base + "." + e.name + ".json", write_trajectory(*e.run));
            }
        }
    }
    for (const auto& [path, content] : files) {
        require_regular_or_missing(path);
        if (junit && same_output_file(*junit, path)) {
            throw UsageError("--junit names " + printable_path(*junit) +
                             ", a run --out writes: one would "
                             "replace the other");
        }
    }
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    for (const auto& [path, content] : files) {
        write_file_atomically(path, content);
    }
}

} // namespace

int compare_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    const Arguments a =
        parse_arguments(args,
                        {with_option, "--root", "--out", "--junit", "--dt", "--box2d-3-substeps",
                         engine_option, engine_command_option},
                        {"--help", "--json", "--summary", "--scene-integrator", "--quiet"});
    if (a.has_flag("--help")) {
        out << compare_help;
        return exit_ok;
    }
    CompareOptions options;
    if (const auto dt = a.option("--dt")) {
        options.dt = positive_seconds("--dt", *dt);
    }
    options.scene_integrator = a.has_flag("--scene-integrator");
    const Project project = find_project(a.option("--root"));
    options.engine = chosen_engine(project, a);
    const std::vector<std::string> goldens = protected_folders(project);
    if (const auto dir = a.option("--out")) {
        check_output_folder("--out", *dir, goldens);
    }
    if (const auto junit = a.option("--junit")) {
        if (is_standard_output(*junit) && a.has_flag("--json")) {
            throw UsageError("--json and --junit - cannot both be standard output");
        }
        check_output_file("--junit", *junit, goldens);
    }
    const std::string box2d_off =
        project.box2d ? "" : printable_path(project.file) + " says \"box2d\": false";
    const std::optional<ReferenceChoice> chosen =
        chosen_references(a.option(with_option), box2d_off, "compare", err);
    if (!chosen) {
        return exit_bad_input;
    }
    ComparisonRequest request;
    request.options = options;
    request.references = chosen->used;
    request.skipped = chosen->skipped;
    request.notes = chosen->notes;
    if (const auto n = a.option("--box2d-3-substeps")) {
        request.box2d_3_substeps = parse_count("--box2d-3-substeps", *n, 1);
    }
    const std::vector<std::string> paths = scenes_named(project, a.positional);
    // Everything is computed before anything is written: a bad scene or a
    // failing engine is one sentence on stderr, with no half output.
    const ComparisonReport report = [&] {
        Progress progress("compare", progress_wanted(a.has_flag("--quiet")));
        progress.set_total(paths.size(), "scenes");
        request.on_start = [&progress](const std::string& path) {
            progress.set_item(std::filesystem::path(path).stem().string());
        };
        request.on_done = [&progress] { progress.advance(); };
        return run_comparison(paths, request);
    }();
    for (const EngineComparison& c : report.scenes) {
        for (const std::string& warning : c.warnings) {
            err << "warning: " << warning << "\n";
        }
    }
    if (const auto dir = a.option("--out")) {
        write_runs(*dir, report.scenes, a.option("--junit"));
    }
    if (const auto junit = a.option("--junit")) {
        write_output_file("--junit", *junit, comparison_junit(report), goldens, out);
    }
    // JUnit on standard output sends the table to standard error, as conform does.
    const bool junit_out = a.option("--junit") && is_standard_output(*a.option("--junit"));
    (junit_out ? err : out) << (a.has_flag("--json")
                                    ? comparison_json(report)
                                    : comparison_text(report, a.has_flag("--summary")));
    return comparison_passed(report) ? exit_ok : exit_failed;
}

} // namespace impulse::harness::cli
