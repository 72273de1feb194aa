// `impulse check [SCENE...]`: the gate.
#include "cli.h"
#include "first_divergence.h"
#include "gate.h"
#include "input_error.h"
#include "number_format.h"
#include "output_path.h"
#include "progress.h"
#include "project_options.h"
#include "report.h"
#include "tolerance.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace impulse::harness::cli {

namespace {

constexpr const char* check_help = R"(usage: impulse check [SCENE...] [options]

The gate: simulates scenes again and compares each with its golden
(GOLDENS/NAME.json, or GOLDENS/ENGINE/NAME.json when the project has several
engines), exactly by default: every double bit-identical, -0.0 and +0.0 told
apart. With no SCENE, every scene of the project (impulse.json's "scenes";
without a project file, ROOT/harness/scenes/), in every engine of the
project. A SCENE is a name or a path to one of the project's scenes. Every
scene's declared expectations are checked too; a scene that breaks one fails
even when its golden matches. A scene an engine refuses as unsupported is
SKIPPED: neither a pass nor a failure.

  --root DIR        the project's folder: DIR/impulse.json, or without one
                    DIR/harness/scenes/ and DIR/goldens/ (default: the first
                    impulse.json found from the current folder upwards, else .)
  --engine NAME     only the project's engine NAME
  --tolerance       compare within per-channel tolerances instead of exactly:
                    |new - gold| <= atol + rtol |gold|, or at most `ulp` ULPs apart;
                    from the scene's "tolerance" block and these options
  --atol SPEC       SPEC is a number for every channel, or CHANNEL=V[,CHANNEL=V...]
  --rtol SPEC       channels: position, angle, velocity, angular_velocity,
  --ulp SPEC          impulse, event_time
  --junit FILE      JUnit XML: one testcase per scene, <failure> for a physics
                    mismatch, <error> for a broken input or golden; - writes it
                    to standard output (the table then goes to standard error)
  --report DIR      summary.md (for a pull request) and index.html with pictures
  -j N, --jobs N    check N scenes at once (results identical to -j 1)
  --shard K/N       only the scenes of shard K of N (a scene's shard depends on
                    its name alone)
  --quiet           no progress bar (it is drawn on standard error only when that
                    is a terminal, after about a second of work)

CI mode (CI set to anything but empty, 0 or false): a golden without a scene
fails too. check never writes to goldens/: --junit and --report are refused
there, as is any path that is not a regular file (a link, FIFO, device).
The golden's engine and solver block are compared too: other settings or
another engine fail; another version of the same engine is a warning.
Exit: 0 all held, 1 a diff, a stale golden, other settings or a failed
expectation, 2 a broken or unreadable scene or golden, a bad option, or a
scene that could not be checked (it ran out of memory: its row says so).
)";

const char* status_word(SceneCheck::Status status) {
    switch (status) {
    case SceneCheck::Status::passed:
        return "ok";
    case SceneCheck::Status::failed:
        return "FAILED";
    case SceneCheck::Status::error:
        return "ERROR";
    case SceneCheck::Status::skipped:
        return "SKIPPED";
    }
    return "?";
}

// "ENGINE/NAME" when the project has several engines, else the scene's name.
std::string row_name(const SceneCheck& check) {
    return check.engine.empty() ? check.name : check.engine + "/" + check.name;
}

std::pair<int, int> parse_shard(const std::string& text) {
    const std::size_t slash = text.find('/');
    if (slash == std::string::npos) {
        throw UsageError("--shard must be K/N, got '" + text + "'");
    }
    const int k = parse_count("--shard K", text.substr(0, slash), 1);
    const int n = parse_count("--shard N", text.substr(slash + 1), 1);
    if (k > n) {
        throw UsageError("--shard K/N needs K <= N, got '" + text + "'");
    }
    return {k, n};
}

// Checked once, before any scene runs: a bad value is one usage error, not
// the same ERROR row for every scene. A value's validity does not depend on
// the scene's own tolerances it is applied over.
void validate_tolerance_options(const CheckOptions& options) {
    for (const auto& [name, spec] :
         {std::pair{"--atol", options.atol}, std::pair{"--rtol", options.rtol},
          std::pair{"--ulp", options.ulp}}) {
        if (spec) {
            try {
                parse_tolerance_option(name, *spec, Tolerances{});
            } catch (const std::invalid_argument& e) {
                throw UsageError(e.what());
            }
        }
    }
}

// Goldens without a scene: a failed row each in CI mode, a warning otherwise.
void add_unreferenced_goldens(const Project& project, bool ci, std::vector<SceneCheck>& checks,
                              std::ostream& err) {
    for (const std::string& golden : unreferenced_goldens(project)) {
        if (ci) {
            SceneCheck orphan;
            orphan.name = std::filesystem::path(golden).stem().string();
            orphan.golden_file = golden;
            orphan.status = SceneCheck::Status::failed;
            orphan.message = printable_path(golden) +
                             ": unreferenced golden: no canonical scene is named '" + orphan.name +
                             "'; delete it with " + project.regen + " --prune";
            checks.push_back(orphan);
        } else {
            err << "warning: " << printable_path(golden)
                << ": unreferenced golden (no scene of that name); " << project.regen
                << " --prune deletes it, CI fails on it\n";
        }
    }
}

// Notes that never change a scene's status (a golden from another version).
void print_warnings(const std::vector<SceneCheck>& checks, std::ostream& err) {
    for (const SceneCheck& c : checks) {
        for (const std::string& warning : c.warnings) {
            err << "warning: " << printable_path(c.golden_file) << ": " << warning << "\n";
        }
    }
}

// check_scenes with the progress bar (scenes done of all, the one running),
// erased before the table is printed.
std::vector<SceneCheck> check_with_progress(const Project& project,
                                            const std::vector<EngineSpec>& engines,
                                            const std::vector<std::string>& paths,
                                            CheckOptions options, bool quiet) {
    Progress progress("check", progress_wanted(quiet));
    progress.set_total(paths.size() * engines.size(), "scenes");
    options.on_start = [&progress](const std::string& path) {
        progress.set_item(std::filesystem::path(path).stem().string());
    };
    options.on_done = [&progress] { progress.advance(); };
    return check_scenes(project, engines, paths, options);
}

// The table (one row per scene), the details of each failure, the counts;
// returns the exit code they mean.
int print_table(std::ostream& out, const std::vector<SceneCheck>& checks) {
    std::size_t width = 4;
    for (const SceneCheck& c : checks) {
        width = std::max(width, row_name(c).size());
    }
    int passed = 0, failed = 0, errors = 0, skipped = 0;
    for (const SceneCheck& c : checks) {
        // SKIPPED is the one word longer than the column: one space still parts it.
        out << "  " << std::left << std::setw(7) << status_word(c.status)
            << (c.status == SceneCheck::Status::skipped ? " " : "")
            << std::setw(static_cast<int>(width) + 2) << printable_path(row_name(c));
        if (c.status == SceneCheck::Status::skipped) {
            ++skipped;
            out << c.message << "\n";
        } else if (c.status == SceneCheck::Status::passed) {
            ++passed;
            out << std::fixed << std::setprecision(3) << c.seconds << " s\n";
            out.unsetf(std::ios::fixed);
        } else {
            (c.status == SceneCheck::Status::failed ? failed : errors) += 1;
            out << c.message << "\n";
        }
    }
    for (const SceneCheck& c : checks) {
        if (!c.details.empty()) {
            out << "\n"
                << printable_path(row_name(c)) << " (" << printable_path(c.scene_file) << " vs "
                << printable_path(c.golden_file) << "):\n"
                << c.details;
        }
    }
    // Scenes that start diverging at the same cause, said once for all.
    for (const std::string& line : shared_causes(checks)) {
        out << line << "\n";
    }
    out << checks.size() << " scene" << (checks.size() == 1 ? "" : "s") << ": " << passed
        << " passed, " << failed << " failed, " << errors << " error" << (errors == 1 ? "" : "s")
        << (skipped > 0 ? ", " + std::to_string(skipped) + " skipped" : "") << "\n";
    return errors > 0 ? exit_bad_input : failed > 0 ? exit_failed : exit_ok;
}

} // namespace

int check_verb(const std::vector<std::string>& raw, std::ostream& out, std::ostream& err) {
    const Arguments a = parse_arguments(normalise_jobs(raw),
                                        {"--root", "--engine", "--atol", "--rtol", "--ulp",
                                         "--junit", "--report", "--jobs", "--shard"},
                                        {"--help", "--tolerance", "--quiet"});
    if (a.has_flag("--help")) {
        out << check_help;
        return exit_ok;
    }
    const Project project = find_project(a.option("--root"));
    const std::vector<EngineSpec> engines = engines_chosen(project, a.option("--engine"));
    CheckOptions options;
    options.tolerance_mode = a.has_flag("--tolerance");
    options.atol = a.option("--atol");
    options.rtol = a.option("--rtol");
    options.ulp = a.option("--ulp");
    if (!options.tolerance_mode && (options.atol || options.rtol || options.ulp)) {
        throw UsageError("--atol, --rtol and --ulp apply in tolerance mode: add --tolerance");
    }
    validate_tolerance_options(options);
    if (const auto jobs = a.option("--jobs")) {
        options.jobs = parse_count("--jobs", *jobs, 1);
    }
    // Output paths are refused before any scene runs.
    const std::vector<std::string> goldens = protected_folders(project);
    const std::optional<std::string> junit = a.option("--junit");
    if (junit) {
        check_output_file("--junit", *junit, goldens);
    }
    if (const auto dir = a.option("--report")) {
        check_output_folder("--report", *dir, goldens);
    }
    const bool junit_to_stdout = junit && is_standard_output(*junit);
    const bool all = a.positional.empty();
    std::vector<std::string> paths = scenes_named(project, a.positional);
    if (const auto spec = a.option("--shard")) {
        const auto [k, n] = parse_shard(*spec);
        paths = shard(paths, k, n);
    }

    // With --junit -, standard output is the XML alone.
    std::ostream& table = junit_to_stdout ? err : out;
    const bool ci = ci_mode();
    table << "check: " << paths.size() << " scene" << (paths.size() == 1 ? "" : "s")
          << (project.engines.size() > 1 ? " in " + engine_names(engines) : "") << ", "
          << (options.tolerance_mode ? "within tolerances" : "exact") << (ci ? ", CI mode" : "")
          << "\n";
    std::vector<SceneCheck> checks =
        check_with_progress(project, engines, paths, options, a.has_flag("--quiet"));

    if (all) {
        add_unreferenced_goldens(project, ci, checks, err);
    }
    print_warnings(checks, err);

    const int code = print_table(table, checks);
    if (junit) {
        write_output_file("--junit", *junit, junit_xml(checks), goldens, out);
    }
    if (const auto dir = a.option("--report")) {
        write_report(*dir, checks);
        table << "report: " << printable_path(*dir) << "/summary.md, " << printable_path(*dir)
              << "/index.html\n";
    }
    return code;
}

} // namespace impulse::harness::cli
