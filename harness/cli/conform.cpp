// `impulse conform [--engine ENGINE]`: the conformance suite. Every shipped
// canonical scene whose answers are physics rather than one of this engine's
// solver choices (conformance.h) is run in ENGINE and scored expectation by
// expectation, with this engine and every reference engine on this machine
// (reference_engines.h) beside it for scale (scorecard.h).
#include "cli.h"
#include "conformance.h"
#include "engine.h"
#include "engine_option.h"
#include "input_error.h"
#include "output_path.h"
#include "progress.h"
#include "project_options.h"
#include "reference_option.h"
#include "scorecard.h"
#include "shipped_scenes.h"
#include "text.h"

#include <algorithm>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace impulse::harness::cli {

namespace {

constexpr const char* conform_help =
    R"(usage: impulse conform [--engine ENGINE | --engine-command CMD] [SCENE...] [options]

The conformance suite for 2D collision response: every shipped canonical
scene whose expectations are physics (exact answers, conservation laws) and
not one of the impulse engine's solver choices is run in ENGINE, and each
expectation is scored: the exact value, ENGINE's value, the absolute and
relative error, the scene's allowance, within it or not. The impulse engine
and every reference engine on this machine (box2d-2.4, box2d-3, chipmunk,
rapier: docs/references.md; scripts/setup installs them) are scored beside
it, for scale; a reference not on this machine is named with the command
that installs it. The rule that picks the
scenes, and the list, are in docs/conformance.md (and --list). With SCENE
names, only those conformance scenes.

  --engine ENGINE   the engine to score: one of the project's engines (default: its
                    first; impulse without a project file), or the built-in impulse
                    or box2d
  --engine-command 'PROGRAM ARGS'
                    score a program that speaks docs/engine-protocol.md, run in the
                    current folder, instead of an engine of impulse.json
  --root DIR        the project's folder (default: the first impulse.json found
                    from the current folder upwards)
  --json FILE       the scorecard as JSON (impulse/conformance@1); - writes it to
                    standard output (the table then goes to standard error)
  --junit FILE      JUnit XML for ENGINE: one testcase per check, <skipped> for a
                    scene it refused, <error> for one it failed to run; - as --json
  --list            the shipped scenes, each in or out of the suite and why; runs nothing
  --with LIST       the references beside it, comma-separated, or none (default:
                    every one on this machine); one not on this machine is exit 2
  --no-box2d        leave out the box2d-2.4 column (so does "box2d": false in impulse.json)
  -j N, --jobs N    score N scenes at once, N from 1 to 1024 (results
                    identical to -j 1)
  --quiet           no progress bar (drawn on standard error only when that is a
                    terminal, after about a second of work)

The shipped scenes are read from IMPULSE_SCENES_DIR when it is set, else from
the installed tool's PREFIX/share/impulse/scenes, else from the source tree
the tool was built from. Output files are regular files, never in goldens/.

Exit: 0 ENGINE's every check within its allowance on every scene it ran (a
scene it refuses as unsupported is a skip) and it ran at least one; 1 a check
outside its allowance, or no scene ran; 2 bad input, or ENGINE failed on a
scene (crashed, timed out, wrote what is not a valid trajectory): that scene's
row says how, and the other scenes are still scored.
)";

// Whether reference `r` is the engine under test itself (--engine box2d is
// Box2D 2.4.1; an external engine is another program even if named alike).
bool is_tested(const ReferenceEngine& r, const EngineSpec& tested) {
    return tested.kind != EngineSpec::Kind::external && tested.kind != EngineSpec::Kind::impulse &&
           r.spec.kind == tested.kind;
}

// The engine under test, then this engine and the chosen references for
// scale, none twice; a reference not on this machine becomes a note.
std::vector<EngineSpec> engines_for(const EngineSpec& tested, const ReferenceChoice& references,
                                    std::vector<std::string>& notes) {
    std::vector<EngineSpec> engines = {tested};
    if (tested.kind != EngineSpec::Kind::impulse) {
        engines.push_back(impulse_engine());
    }
    notes.insert(notes.end(), references.notes.begin(), references.notes.end());
    for (const ReferenceEngine& r : references.used) {
        if (!is_tested(r, tested)) {
            engines.push_back(r.spec);
        }
    }
    for (const ReferenceEngine& r : references.skipped) {
        notes.push_back(r.name + " not on this machine (" + r.missing +
                        "); install it with: " + r.install);
    }
    return engines;
}

void write_list(std::ostream& out, const std::string& dir, const std::vector<ShippedScene>& all) {
    std::size_t width = 4;
    std::size_t in = 0;
    for (const ShippedScene& s : all) {
        width = std::max(width, s.scene.name.size());
        in += s.exclusion ? 0 : 1;
    }
    out << "shipped scenes in " << printable_path(dir) << ":\n";
    for (const ShippedScene& s : all) {
        out << (s.exclusion ? "  out  " + padded(s.scene.name, width) + "  " + *s.exclusion
                            : "  in   " + s.scene.name)
            << "\n";
    }
    out << in << " of " << plural(all.size(), "scene is", "scenes are")
        << " in the conformance suite\n";
}

// The conformance scenes, or those of them named; a name that is not one is
// refused with the reason.
std::vector<Scene> chosen_scenes(const std::vector<ShippedScene>& all,
                                 const std::vector<std::string>& names) {
    std::vector<Scene> chosen;
    for (const ShippedScene& s : all) {
        const bool named = std::find(names.begin(), names.end(), s.scene.name) != names.end();
        if (named && s.exclusion) {
            throw UsageError(single_quoted(s.scene.name) +
                             " is not a conformance scene: " + *s.exclusion);
        }
        if (!s.exclusion && (names.empty() || named)) {
            chosen.push_back(s.scene);
        }
    }
    for (const std::string& name : names) {
        if (std::none_of(all.begin(), all.end(),
                         [&](const ShippedScene& s) { return s.scene.name == name; })) {
            throw UsageError("no shipped scene is named " + single_quoted(name) +
                             "; 'impulse conform --list' lists them");
        }
    }
    return chosen;
}

// score_scenes with the progress bar (scenes done of all, the one running),
// erased before the table is printed.
std::vector<SceneScore> score_with_progress(const std::vector<Scene>& scenes,
                                            const std::vector<EngineSpec>& engines, int jobs,
                                            bool quiet) {
    Progress progress("conform", progress_wanted(quiet));
    progress.set_total(scenes.size(), "scenes");
    ScoringOptions options;
    options.jobs = jobs;
    options.on_start = [&progress](const std::string& scene) { progress.set_item(scene); };
    options.on_done = [&progress] { progress.advance(); };
    return score_scenes(scenes, engines, options);
}

} // namespace

int conform_verb(const std::vector<std::string>& raw, std::ostream& out, std::ostream& err) {
    const Arguments a = parse_arguments(normalise_jobs(raw),
                                        {engine_option, engine_command_option, with_option,
                                         "--root", "--json", "--junit", "--jobs"},
                                        {"--help", "--list", "--no-box2d", "--quiet"});
    if (a.has_flag("--help")) {
        out << conform_help;
        return exit_ok;
    }
    if (a.has_flag("--list")) {
        const std::string dir = shipped_scenes_dir();
        write_list(out, dir, shipped_scenes(dir));
        return exit_ok;
    }
    const int jobs =
        a.option("--jobs") ? parse_count("--jobs", *a.option("--jobs"), 1, max_jobs) : 1;
    const Project project = find_project(a.option("--root"));
    const EngineSpec tested = chosen_engine(project, a);

    // Output paths are refused before anything runs.
    const std::vector<std::string> goldens = protected_folders(project);
    const std::optional<std::string> json = a.option("--json");
    const std::optional<std::string> junit = a.option("--junit");
    if (json && junit && is_standard_output(*json) && is_standard_output(*junit)) {
        throw UsageError("--json and --junit cannot both be standard output");
    }
    if (json && junit && same_output_file(*json, *junit)) {
        throw UsageError("--json and --junit name the same file, " + *junit +
                         ": one would replace the other");
    }
    for (const auto& [option, path] : {std::pair{"--json", json}, std::pair{"--junit", junit}}) {
        if (path) {
            check_output_file(option, *path, goldens);
        }
    }

    const std::string dir = shipped_scenes_dir();
    const std::vector<ShippedScene> all = shipped_scenes(dir);
    Scorecard card;
    card.engine = tested.name;
    card.scenes_dir = dir;
    const std::string box2d_off = !project.box2d
                                      ? printable_path(project.file) + " says \"box2d\": false"
                                  : a.has_flag("--no-box2d") ? "--no-box2d"
                                                             : "";
    const std::optional<ReferenceChoice> references =
        chosen_references(a.option(with_option), box2d_off, "conform", err);
    if (!references) {
        return exit_bad_input;
    }
    const std::vector<EngineSpec> engines = engines_for(tested, *references, card.notes);
    for (std::size_t e = 1; e < engines.size(); ++e) {
        card.references.push_back(engines[e].name);
    }
    const std::vector<Scene> scenes = chosen_scenes(all, a.positional);
    card.scenes = score_with_progress(scenes, engines, jobs, a.has_flag("--quiet"));

    const bool to_stdout =
        (json && is_standard_output(*json)) || (junit && is_standard_output(*junit));
    (to_stdout ? err : out) << scorecard_text(card);
    if (json) {
        write_output_file("--json", *json, scorecard_json(card), goldens, out);
    }
    if (junit) {
        write_output_file("--junit", *junit, scorecard_junit(card), goldens, out);
    }
    const ConformanceCounts counts = count_engine(card.scenes);
    return counts.errors > 0 ? exit_bad_input : conforms(counts) ? exit_ok : exit_failed;
}

} // namespace impulse::harness::cli
