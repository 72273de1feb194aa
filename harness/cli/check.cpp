// `impulse check [SCENE...]`: the gate.
#include "atomic_file.h"
#include "check_json.h"
#include "check_outcome.h"
#include "check_table.h"
#include "cli.h"
#include "comparison_run.h"
#include "gate.h"
#include "input_error.h"
#include "interruption.h"
#include "junit.h"
#include "output_path.h"
#include "progress.h"
#include "project_options.h"
#include "reference_option.h"
#include "report.h"
#include "text.h"
#include "tolerance.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <ostream>
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
SKIPPED: neither a pass nor a failure; if the scene has a golden of that
engine (it ran the scene when blessed), the refusal FAILED.

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
  --json FILE       the results as JSON (impulse/check@1, docs/formats.md): per
                    scene its status, first divergence, per-channel differences,
                    failed expectations and error sentence, the totals, the
                    exit code and the accept command; - writes it to standard
                    output (the table then goes to standard error)
  --junit FILE      JUnit XML: one testcase per scene, <failure> for a physics
                    mismatch, <error> for a broken input or golden (type
                    "input error") or an engine that failed ("engine error");
                    - writes it to standard output (the table then goes to
                    standard error);
                    with --compare a second testsuite, impulse.compare
  --compare[=LIST]  after the gate, what impulse compare --summary runs over
                    the same scenes: each in the reference engines of LIST
                    (as compare's --with; default every reference on this
                    machine), box2d-2.4 judged against the scene's box2d block.
                    Its summary lines follow the table, it is in --json and
                    --junit, and the exit code is the worse of the two
  --report DIR      summary.md (for a pull request) and index.html with pictures
  -j N, --jobs N    check N scenes at once, N from 1 to 1024 (results
                    identical to -j 1)
  --shard K/N       only the scenes of shard K of N (a scene's shard depends on
                    its name alone); a shard that holds none or only some of
                    the scenes given says so and where the others are, and
                    exits 0 when nothing it holds failed
  --quiet           for a CI log: only the row of each scene that failed or
                    could not be checked and the totals line (no header, no
                    passing rows, no details: --report and --json hold them),
                    the comparison's summary only when it failed, and no
                    progress bar (it is drawn on standard error only when that
                    is a terminal, after about a second of work)

CI mode (CI set to anything but empty, 0 or false): a golden without a scene
fails too. check never writes to goldens/: --json, --junit and --report are refused
there, as is any path that is not a regular file (a link, FIFO, device).
The golden's engine and solver block are compared too: other settings or
another engine fail; another version of the same engine is a warning.
Exit: 0 all held, 1 a diff, a stale golden, other settings, a failed
expectation or (--compare) a box2d-2.4 row outside tolerance, 2 a broken or
unreadable scene or golden, a bad option, a scene that could not be checked
(it ran out of memory: its row says so), or a reference of --compare that is
not on this machine or failed on a scene.
)";

std::pair<int, int> parse_shard(const std::string& text) {
    const std::size_t slash = text.find('/');
    if (slash == std::string::npos || text.find('/', slash + 1) != std::string::npos) {
        throw UsageError("--shard must be K/N, two whole numbers and one '/', got '" + text + "'");
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
            const std::string reason = unreferenced_reason(project, golden);
            orphan.message = printable_path(golden) + ": unreferenced golden: " +
                             (reason == "no scene of that name"
                                  ? "no scene of the project is named '" + orphan.name + "'"
                                  : reason) +
                             "; delete it with " + project.regen + " --prune";
            checks.push_back(orphan);
        } else {
            err << "warning: " << printable_path(golden) << ": unreferenced golden ("
                << unreferenced_reason(project, golden) << "); " << project.regen
                << " --prune deletes it, CI fails on it\n";
        }
    }
}

// Notes that never change a scene's status: the scene's own (a polygon
// recentred) and the golden's (recorded by another version).
void print_warnings(const std::vector<SceneCheck>& checks, std::ostream& err) {
    for (const SceneCheck& c : checks) {
        for (const std::string& warning : c.scene_warnings) {
            err << "warning: " << warning << "\n";
        }
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

// --compare[=LIST] is a flag with an optional value: the bare flag becomes
// "--compare=" (every reference), so it never takes the next argument, a
// scene, for its list.
std::vector<std::string> normalise_compare(const std::vector<std::string>& raw) {
    std::vector<std::string> out;
    for (const std::string& arg : raw) {
        out.push_back(arg == "--compare" ? "--compare=" : arg);
    }
    return out;
}

// The references --compare asks for, or nullopt (exit 2, said on err) when
// one is not on this machine. Chosen before any scene runs.
std::optional<ReferenceChoice> compare_references(const Project& project, const std::string& list,
                                                  std::ostream& err) {
    const std::string box2d_off =
        project.box2d ? "" : printable_path(project.file) + " says \"box2d\": false";
    try {
        return chosen_references(list.empty() ? std::nullopt : std::optional<std::string>(list),
                                 box2d_off, "check --compare", err);
    } catch (const UsageError& e) {
        // chosen_references names compare's option; here the user wrote --compare.
        std::string message = e.what();
        if (message.rfind(with_option, 0) == 0) {
            message = "--compare" + message.substr(std::string(with_option).size());
        }
        throw UsageError(message);
    }
}

// What impulse compare --summary runs, over the gate's scenes, in the first
// engine checked. An engine that fails on a scene is `failure`, its sentence.
std::optional<ComparisonReport> run_reference_comparison(const std::vector<std::string>& paths,
                                                         const EngineSpec& engine,
                                                         const ReferenceChoice& choice, bool quiet,
                                                         std::string& failure) {
    ComparisonRequest request;
    request.options.engine = engine;
    request.references = choice.used;
    request.skipped = choice.skipped;
    request.notes = choice.notes;
    Progress progress("compare", progress_wanted(quiet));
    progress.set_total(paths.size(), "scenes");
    request.on_start = [&progress](const std::string& path) {
        progress.set_item(std::filesystem::path(path).stem().string());
    };
    request.on_done = [&progress] { progress.advance(); };
    try {
        return run_comparison(paths, request);
    } catch (const std::exception& e) {
        failure = e.what();
        return std::nullopt;
    }
}

// "shard 1/3 holds none of the 1 scene given (drop-box is in shard 2/3)":
// said when the shard leaves out scenes named on the command line, so a CI
// job that ran nothing says why. Empty when it holds them all.
std::string shard_note(const std::vector<std::string>& given, const std::vector<std::string>& held,
                       int k, int n) {
    std::string elsewhere;
    for (const std::string& path : given) {
        if (std::find(held.begin(), held.end(), path) != held.end()) {
            continue;
        }
        for (int j = 1; j <= n; ++j) {
            if (!shard({path}, j, n).empty()) {
                elsewhere += std::string(elsewhere.empty() ? "" : ", ") +
                             printable_path(std::filesystem::path(path).stem().string()) +
                             " is in shard " + std::to_string(j) + "/" + std::to_string(n);
            }
        }
    }
    if (elsewhere.empty()) {
        return "";
    }
    const std::string shard_name = "shard " + std::to_string(k) + "/" + std::to_string(n);
    const std::string count = held.empty() ? "none" : std::to_string(held.size());
    return shard_name + " holds " + count + " of the " +
           plural(given.size(), "scene given", "scenes given") + " (" + elsewhere + ")";
}

// The command line, read and checked before any scene runs.
struct CheckRequest {
    CheckOptions options;
    std::vector<EngineSpec> engines;
    std::vector<std::string> paths;
    bool all = false;
    bool quiet = false;
    std::optional<std::string> json, junit, report, shard_spec;
    std::string shard_note;
    std::optional<ReferenceChoice> compare; // --compare's references
    std::vector<std::string> goldens;       // folders no output may go into
};

CheckOptions gate_options(const Arguments& a) {
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
        options.jobs = parse_count("--jobs", *jobs, 1, max_jobs);
    }
    return options;
}

// A report file that --json or --junit also names: one would replace the other.
void refuse_report_clash(const CheckRequest& r, const std::string& report_file) {
    for (const auto& [option, path] :
         {std::pair{"--json", r.json}, std::pair{"--junit", r.junit}}) {
        if (path && same_output_file(*path, report_file)) {
            throw UsageError(std::string(option) + " names " + printable_path(*path) +
                             ", a file of the --report " + "folder: one would replace the other");
        }
    }
}

// Output paths are refused before any scene runs; at most one output is
// standard output.
void check_outputs(const CheckRequest& r) {
    if (r.json && r.junit && is_standard_output(*r.json) && is_standard_output(*r.junit)) {
        throw UsageError("--json and --junit cannot both be standard output (-)");
    }
    if (r.json && r.junit && same_output_file(*r.json, *r.junit)) {
        throw UsageError("--json and --junit name the same file, " + *r.junit +
                         ": one would replace the other");
    }
    if (r.json) {
        check_output_file("--json", *r.json, r.goldens);
    }
    if (r.junit) {
        check_output_file("--junit", *r.junit, r.goldens);
    }
    if (r.report) {
        check_output_folder("--report", *r.report, r.goldens);
        for (const std::string& file : report_fixed_files(*r.report)) {
            refuse_report_clash(r, file);
            if (std::filesystem::is_directory(*r.report)) {
                check_output_file("--report", file, r.goldens);
            }
        }
    }
}

// Nullopt when a reference of --compare is not on this machine (said on err).
std::optional<CheckRequest> read_request(const Project& project, const Arguments& a,
                                         std::ostream& err) {
    CheckRequest r;
    r.options = gate_options(a);
    // Every option is read before an engine is looked for: a bad --shard is
    // said as such, not hidden behind an engine that cannot start.
    r.shard_spec = a.option("--shard");
    const std::optional<std::pair<int, int>> shard_of =
        r.shard_spec ? std::optional(parse_shard(*r.shard_spec)) : std::nullopt;
    r.engines = engines_chosen(project, a.option("--engine"));
    for (const EngineSpec& engine : r.engines) {
        require_startable(engine);
    }
    r.goldens = protected_folders(project);
    r.json = a.option("--json");
    r.junit = a.option("--junit");
    r.report = a.option("--report");
    r.quiet = a.has_flag("--quiet");
    check_outputs(r);
    if (const auto list = a.option("--compare")) {
        r.compare = compare_references(project, *list, err);
        if (!r.compare) {
            return std::nullopt;
        }
    }
    r.all = a.positional.empty();
    r.paths = scenes_named(project, a.positional);
    if (shard_of) {
        const auto [k, n] = *shard_of;
        const std::vector<std::string> given = r.paths;
        r.paths = shard(given, k, n);
        if (!r.all) {
            r.shard_note = shard_note(given, r.paths, k, n);
        }
    }
    return r;
}

// "check: 3 scenes in a, b, exact, CI mode", after the shard's note.
void print_header(std::ostream& table, const Project& project, const CheckRequest& r, bool ci) {
    if (!r.shard_note.empty()) {
        table << "check: " << r.shard_note << "\n";
    }
    if (r.quiet) {
        return;
    }
    table << "check: " << plural(r.paths.size(), "scene", "scenes")
          << (r.shard_spec ? " (shard " + *r.shard_spec + ")" : "")
          << (project.engines.size() > 1 ? " in " + engine_names(r.engines) : "") << ", "
          << (r.options.tolerance_mode ? "within tolerances" : "exact") << (ci ? ", CI mode" : "")
          << "\n";
}

int gate_exit_code(const std::vector<SceneCheck>& checks) {
    const CheckCounts c = count_checks(checks);
    return c.errors > 0 ? exit_bad_input : c.failed > 0 ? exit_failed : exit_ok;
}

// The gate's table, then the comparison's summary lines (or why it could
// not run); returns the worse of the two exit codes.
int print_results(std::ostream& table, const CheckRequest& r, const std::vector<SceneCheck>& checks,
                  const std::optional<ComparisonReport>& comparison,
                  const std::string& comparison_failure) {
    table << check_table(checks, r.quiet);
    int code = gate_exit_code(checks);
    if (!comparison_failure.empty()) {
        table << "\ncheck --compare: " << comparison_failure << "\n";
        return exit_bad_input;
    }
    if (comparison) {
        const bool passed = comparison_passed(*comparison);
        if (!r.quiet || !passed) {
            table << "\n" << comparison_text(*comparison, true);
        }
        code = std::max(code, passed ? exit_ok : exit_failed);
    }
    return code;
}

// --junit, --json and --report, each written whole or not at all; every path
// of the report (its pictures are known only now) is checked before any
// output is written, so a refused one leaves the others as they were.
void write_outputs(const CheckRequest& r, const std::vector<SceneCheck>& checks,
                   const std::optional<ComparisonReport>& comparison, CheckRun run,
                   std::ostream& out, std::ostream& table) {
    // The outputs are one set: an interrupt that arrives once they are being
    // written takes effect after the last (an outside review interrupted
    // check between --json and --report and found the JSON alone).
    const HeldInterrupts whole_set;
    std::vector<std::pair<std::string, std::string>> report;
    if (r.report) {
        report = report_files(*r.report, checks);
        for (const auto& [path, content] : report) {
            refuse_report_clash(r, path);
            require_regular_or_missing(path);
        }
    }
    if (r.junit) {
        write_output_file("--junit", *r.junit,
                          comparison ? junit_xml(checks, *comparison) : junit_xml(checks),
                          r.goldens, out);
    }
    if (r.json) {
        run.comparison = comparison;
        write_output_file("--json", *r.json, check_json(checks, run), r.goldens, out);
    }
    if (r.report) {
        write_report(*r.report, report);
        if (!r.quiet) {
            const std::filesystem::path folder(*r.report);
            table << "report: " << printable_path((folder / "summary.md").string()) << ", "
                  << printable_path((folder / "index.html").string()) << "\n";
        }
    }
}

} // namespace

int check_verb(const std::vector<std::string>& raw, std::ostream& out, std::ostream& err) {
    const Arguments a =
        parse_arguments(normalise_compare(normalise_jobs(raw)),
                        {"--root", "--engine", "--atol", "--rtol", "--ulp", "--junit", "--json",
                         "--report", "--jobs", "--shard", "--compare"},
                        {"--help", "--tolerance", "--quiet"});
    if (a.has_flag("--help")) {
        out << check_help;
        return exit_ok;
    }
    const Project project = find_project(a.option("--root"));
    const std::optional<CheckRequest> request = read_request(project, a, err);
    if (!request) {
        return exit_bad_input;
    }
    const CheckRequest& r = *request;
    // With --junit - or --json -, standard output is that document alone.
    const bool document_to_stdout =
        (r.junit && is_standard_output(*r.junit)) || (r.json && is_standard_output(*r.json));
    std::ostream& table = document_to_stdout ? err : out;
    const bool ci = ci_mode();
    print_header(table, project, r, ci);
    std::vector<SceneCheck> checks =
        check_with_progress(project, r.engines, r.paths, r.options, r.quiet);
    std::string comparison_failure;
    std::optional<ComparisonReport> comparison;
    if (r.compare) {
        comparison = run_reference_comparison(r.paths, r.engines.front(), *r.compare, r.quiet,
                                              comparison_failure);
    }
    if (r.all) {
        add_unreferenced_goldens(project, ci, checks, err);
    }
    print_warnings(checks, err);
    if (comparison) {
        for (const EngineComparison& c : comparison->scenes) {
            for (const std::string& warning : c.warnings) {
                err << "warning: " << warning << "\n";
            }
        }
    }
    CheckRun run;
    run.tolerance_mode = r.options.tolerance_mode;
    run.ci = ci;
    run.engine = r.engines.front().name;
    run.shard = r.shard_spec;
    if (!r.shard_note.empty()) {
        run.shard_notes.push_back(r.shard_note);
    }
    run.comparison_error = comparison_failure;
    run.exit_code = print_results(table, r, checks, comparison, comparison_failure);
    write_outputs(r, checks, comparison, run, out, table);
    return run.exit_code;
}

} // namespace impulse::harness::cli
