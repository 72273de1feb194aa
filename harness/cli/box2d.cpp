// `impulse box2d [SCENE...]`: the second reference. Runs each scene in the
// impulse engine and in Box2D with friction off (box2d_simulator.h) and
// compares the observables the scene's "box2d" block names (observables.h),
// each against the exact answer of docs/physics.md where there is one.
#include "atomic_file.h"
#include "box2d_simulator.h"
#include "cli.h"
#include "engine_comparison.h"
#include "engine_option.h"
#include "gate.h"
#include "input_error.h"
#include "observables.h"
#include "output_path.h"
#include "progress.h"
#include "project_options.h"
#include "reference_comparison.h"
#include "run.h"
#include "simulator.h"
#include "single_precision.h"
#include "tunnelling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness::cli {

namespace {

constexpr const char* box2d_help =
    R"(usage: impulse box2d [SCENE...] [options]

Runs each scene in the impulse engine and in Box2D 2.4.1 (friction 0,
restitution equal to the scene's e, restitution threshold 0, no sleeping, no
damping, polygons shrunk by Box2D's skin) and compares the observables the
scene's "box2d" block names: impact times, apex heights and ratios,
post-impact velocities, the restitution residual, momentum, angular momentum
and energy. Each row shows the exact answer of docs/physics.md where there is one,
both runs' values and errors, and whether |Box2D - impulse| is within the
observable's atol + rtol |impulse|. With no SCENE, every canonical scene in
ROOT/harness/scenes/. A SCENE is a name or a path.

The impulse engine integrates with symplectic-euler, Box2D's own integrator,
so the difference that remains is the collision model's. Symplectic Euler's
bounces die out sooner than the scene's own integrator's: when the impulse
engine stops on a Zeno cascade or a resting contact inside the scene, both
runs are compared up to its last complete step, and the output says so.

  --root DIR                   the project's folder (default: the first impulse.json
                               found from the current folder upwards; without one,
                               the scenes are in ./harness/scenes/)
  --json                       the comparison as JSON, for scripts
  --out DIR                    also write both runs as trajectories, DIR/NAME.impulse.json
                               and DIR/NAME.box2d.json, for impulse diff and render (with
                               --engine, NAME.ENGINE.json for the engine's run)
                               (regular files only; never into goldens/)
  --dt S                       time step of both runs, in seconds
  --substeps N                 Box2D steps per scene step (scene's box2d.substeps, default 1)
  --velocity-iterations N      Box2D's velocity iterations (default 8)
  --position-iterations N      Box2D's position iterations (default 3)
  --scene-integrator           run the impulse engine with the scene's own integrator
  --engine NAME                the engine compared with Box2D (default: the project's
                               first engine, impulse without a project file); it gets
                               the scene with --dt and solver.integrator symplectic-euler
                               (unless --scene-integrator), which it may ignore; a scene
                               whose settings it refuses (exit 3) is skipped and listed
  --quiet                      no progress bar (drawn on standard error only when that
                               is a terminal, after about a second of work)

Exit: 0 every observable within its tolerance, 1 one is not, 2 bad input (a
broken scene, a bad option, a shape Box2D cannot take, a build without Box2D).
)";

#ifdef IMPULSE_WITH_BOX2D
// About six significant digits: a table is read, not parsed.
std::string short_number(std::optional<double> value) {
    if (!value) {
        return "-";
    }
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", *value);
    return buffer;
}

std::optional<double> difference(std::optional<double> a, std::optional<double> b) {
    if (!a || !b) {
        return std::nullopt;
    }
    return *a - *b;
}

void write_table(std::ostream& out, const ReferenceComparison& c) {
    const std::vector<std::string> header = {
        "observable",          "exact",     c.engine, "Box2D", c.engine + " err", "Box2D err",
        "Box2D - " + c.engine, "tolerance", "within"};
    std::vector<std::vector<std::string>> cells = {header};
    for (const ObservableRow& r : c.rows) {
        cells.push_back({r.name, short_number(r.exact), short_number(r.impulse),
                         short_number(r.box2d), short_number(difference(r.impulse, r.exact)),
                         short_number(difference(r.box2d, r.exact)),
                         short_number(difference(r.box2d, r.impulse)), short_number(r.tolerance),
                         r.within ? "yes" : "NO"});
    }
    std::vector<std::size_t> width(header.size(), 0);
    for (const auto& line : cells) {
        for (std::size_t i = 0; i < line.size(); ++i) {
            width[i] = std::max(width[i], line[i].size());
        }
    }
    for (const auto& line : cells) {
        std::string text = "  ";
        for (std::size_t i = 0; i < line.size(); ++i) {
            // The name column reads left to right; numbers line up on the right.
            const std::string pad(width[i] - line[i].size(), ' ');
            text += i == 0 ? line[i] + pad : pad + line[i];
            text += i + 1 < line.size() ? "  " : "";
        }
        out << text << "\n";
    }
    for (const ObservableRow& r : c.rows) {
        if (!r.note.empty()) {
            out << "  note: " << r.path << ", " << r.name << ": " << r.note << "\n";
        }
    }
}

constexpr const char* legend =
    R"(What the differences mean (docs/physics.md, "Box2D, the second reference"):
  timing       Box2D finds a contact only once the bodies overlap at the end of a
               step and resolves it in the next step: its impact times lag the exact
               ones by one to two steps, its bounce starts from inside the ground at
               the speed of the longer fall, and it applies restitution after that
               step's gravity kick, so a rebound leaves faster by about e g dt (its
               restitution residual is e g dt / |vn|). At 30 to 60 Hz this puts its
               apex heights 10 to 20% above the exact ones.
  skin         Box2D's polygons carry a skin of b2_polygonRadius = 0.01 m, so their
               contacts would start that far early; the adapter shrinks every polygon
               by it, so the skin surface is the true surface, but corners are rounded
               with that radius and a corner's contact point moves by up to 0.01 m.
  iterations   Box2D solves contacts by sequential impulses, 8 velocity and 3 position
               iterations per step unless the scene or an option says otherwise: a
               contact of several points converges only as far as the iterations go.
  position     Box2D's position correction (Baumgarte-style pushes out of overlap)
               moves bodies without changing their velocities: it raises apex heights
               and potential energy, not post-impact velocities.
  precision    Box2D computes in single precision: about 1e-7 relative per operation,
               so conserved quantities drift by about that much per step.
  errors       impulse err and Box2D err are each run's value minus the exact answer;
               impulse err is mostly symplectic Euler's own error at this dt (each
               flight loses about g dt of speed). within: |Box2D - impulse| <= atol +
               rtol |impulse|, from the scene's box2d block.
)";

// The legend's last paragraph for an engine other than impulse, whose error
// this tool cannot explain.
std::string engine_errors_legend(const std::string& engine) {
    return "  errors       " + engine +
           " err and Box2D err are each run's value minus the exact "
           "answer.\n               within: |Box2D - " +
           engine + "| <= atol + rtol |" + engine + "|, from the scene's box2d block.\n";
}

// The first line: what the engine under study integrates with.
std::string integrator_sentence(const std::string& engine, const ReferenceOptions& options) {
    if (options.engine.kind == EngineSpec::Kind::impulse) {
        return options.scene_integrator
                   ? "the impulse engine integrates with each scene's own integrator "
                     "(--scene-integrator), so the differences include the integrators'"
                   : "the impulse engine integrates with symplectic-euler, Box2D's own "
                     "integrator, so the difference that remains is the collision model's";
    }
    return options.scene_integrator
               ? engine + " is given each scene's own solver.integrator (--scene-integrator)"
               : engine + " is given solver.integrator symplectic-euler, Box2D's own "
                          "integrator (an engine without integrators ignores it)";
}

void write_text(std::ostream& out, const std::vector<ReferenceComparison>& comparisons,
                const ReferenceOptions& options) {
    out << "box2d: " << comparisons.size() << " scene" << (comparisons.size() == 1 ? "" : "s")
        << "; " << integrator_sentence(options.engine.name, options) << "\n";
    for (const ReferenceComparison& c : comparisons) {
        out << "\n" << c.name << " (" << c.file << ")";
        if (!c.skipped.empty()) {
            out << ": skipped, " << c.skipped << "\n";
            continue;
        }
        if (c.box2d.observables.empty()) {
            out << ": no observables declared\n";
            continue;
        }
        out << ": dt " << short_number(c.dt) << " s; " << c.impulse_engine << ", " << c.integrator
            << (c.integrator == c.scene_integrator ? ""
                                                   : " (the scene's: " + c.scene_integrator + ")")
            << "; " << c.box2d_engine << ", " << c.box2d.substeps << " substep"
            << (c.box2d.substeps == 1 ? "" : "s") << ", " << c.box2d.velocity_iterations
            << " velocity / " << c.box2d.position_iterations << " position iterations\n";
        if (!c.stopped.empty()) {
            out << "  " << c.stopped << "\n";
        }
        write_table(out, c);
    }
    out << "\n";
    std::size_t width = 4;
    for (const ReferenceComparison& c : comparisons) {
        width = std::max(width, c.name.size());
    }
    std::size_t passed = 0, failed = 0, skipped = 0, none = 0;
    for (const ReferenceComparison& c : comparisons) {
        const std::string pad(width - c.name.size(), ' ');
        if (!c.skipped.empty()) {
            ++skipped;
            out << "  skipped " << c.name << pad << "  " << c.skipped << "\n";
        } else if (c.rows.empty()) {
            // Nothing compared: neither a pass nor a failure.
            ++none;
            out << "  none    " << c.name << pad << "  no observables declared, nothing compared\n";
        } else if (c.passed()) {
            ++passed;
            out << "  ok      " << c.name << pad << "  all " << c.rows.size()
                << " rows within tolerance\n";
        } else {
            ++failed;
            out << "  FAILED  " << c.name << pad << "  " << c.outside() << " of " << c.rows.size()
                << " rows outside tolerance\n";
        }
    }
    out << scene_totals(comparisons.size(), passed, failed, skipped, none) << "\n\n";
    if (options.engine.kind == EngineSpec::Kind::impulse) {
        out << legend;
    } else {
        const std::string text = legend;
        out << text.substr(0, text.find("  errors")) << engine_errors_legend(options.engine.name);
    }
}

// ---------------------------------------------------------------- JSON

nlohmann::json optional_number(std::optional<double> value) {
    return value && std::isfinite(*value) ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

// For an engine other than impulse, the keys that name the impulse engine
// name the engine under study instead: "engine" (with its "name") for
// "impulse", "engine_error" for "impulse_error", "engine_integrator" for
// "impulse_integrator"; a skipped scene has "passed": null and "skipped", one
// with no observables "passed": null and "note"; "status" says which.
std::string write_json(const std::vector<ReferenceComparison>& comparisons,
                       const ReferenceOptions& options) {
    const bool own = options.engine.kind == EngineSpec::Kind::impulse;
    const std::string key = own ? "impulse" : "engine";
    nlohmann::ordered_json scenes = nlohmann::ordered_json::array();
    for (const ReferenceComparison& c : comparisons) {
        nlohmann::ordered_json scene;
        scene["name"] = c.name;
        scene["file"] = c.file;
        const bool none = c.skipped.empty() && c.rows.empty();
        scene["status"] = !c.skipped.empty() ? "skipped"
                          : none             ? "no observables"
                          : c.passed()       ? "passed"
                                             : "failed";
        // Neither a pass nor a failure: nothing ran, or nothing was compared.
        scene["passed"] = c.skipped.empty() && !none ? nlohmann::ordered_json(c.passed()) : nullptr;
        if (!c.skipped.empty()) {
            scene["skipped"] = c.skipped;
        } else if (none) {
            scene["note"] = no_observables_sentence;
        } else {
            scene["dt"] = c.dt;
            if (!own) {
                scene[key]["name"] = c.engine;
            }
            scene[key]["engine"] = c.impulse_engine;
            scene[key]["integrator"] = c.integrator;
            scene["box2d"] = {{"engine", c.box2d_engine},
                              {"substeps", c.box2d.substeps},
                              {"velocity_iterations", c.box2d.velocity_iterations},
                              {"position_iterations", c.box2d.position_iterations}};
        }
        scene["warnings"] = c.warnings;
        scene["stopped"] =
            c.stopped.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(c.stopped);
        nlohmann::ordered_json rows = nlohmann::ordered_json::array();
        for (const ObservableRow& r : c.rows) {
            nlohmann::ordered_json row;
            row["path"] = r.path;
            row["name"] = r.name;
            row["exact"] = optional_number(r.exact);
            row[key] = optional_number(r.impulse);
            row["box2d"] = optional_number(r.box2d);
            row[key + "_error"] = optional_number(difference(r.impulse, r.exact));
            row["box2d_error"] = optional_number(difference(r.box2d, r.exact));
            row["difference"] = optional_number(difference(r.box2d, r.impulse));
            row["tolerance"] = optional_number(r.tolerance);
            row["within"] = r.within;
            row["note"] = r.note;
            rows.push_back(std::move(row));
        }
        scene["rows"] = std::move(rows);
        scenes.push_back(std::move(scene));
    }
    nlohmann::ordered_json document;
    document["schema"] = "impulse/box2d-comparison@1";
    if (!own) {
        document["engine"] = options.engine.name;
    }
    document[key + "_integrator"] = options.scene_integrator ? "scene" : "symplectic-euler";
    document["scenes"] = std::move(scenes);
    return document.dump(2) + "\n";
}

// Both runs of every scene into dir; nothing is written when one of the
// paths is refused (a link, a FIFO), so the folder is never half new.
void write_runs(const std::string& dir, const std::vector<ReferenceComparison>& comparisons) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    std::vector<std::pair<std::string, std::string>> files;
    for (const ReferenceComparison& c : comparisons) {
        if (c.impulse_run && c.box2d_run) {
            const std::string base = (std::filesystem::path(dir) / c.name).string();
            files.emplace_back(base + "." + c.engine + ".json", write_trajectory(*c.impulse_run));
            files.emplace_back(base + ".box2d.json", write_trajectory(*c.box2d_run));
        }
    }
    for (const auto& [path, content] : files) {
        require_regular_or_missing(path);
    }
    for (const auto& [path, content] : files) {
        write_file_atomically(path, content);
    }
}
#endif // IMPULSE_WITH_BOX2D

} // namespace

int box2d_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    const Arguments a =
        parse_arguments(args,
                        {"--root", "--out", "--dt", "--substeps", "--velocity-iterations",
                         "--position-iterations", engine_option, engine_command_option},
                        {"--help", "--json", "--scene-integrator", "--quiet"});
    if (a.has_flag("--help")) {
        out << box2d_help;
        return exit_ok;
    }
    ReferenceOptions options;
    if (const auto dt = a.option("--dt")) {
        options.dt = positive_seconds("--dt", *dt);
    }
    if (const auto n = a.option("--substeps")) {
        options.substeps = parse_count("--substeps", *n, 1, 1000);
    }
    if (const auto n = a.option("--velocity-iterations")) {
        options.velocity_iterations = parse_count("--velocity-iterations", *n, 1, 1000);
    }
    if (const auto n = a.option("--position-iterations")) {
        options.position_iterations = parse_count("--position-iterations", *n, 1, 1000);
    }
    options.scene_integrator = a.has_flag("--scene-integrator");
#ifndef IMPULSE_WITH_BOX2D
    (void)out;
    err << "impulse box2d: this build has no Box2D (configured with IMPULSE_WITH_BOX2D=OFF); "
           "install libbox2d-dev and configure with -DIMPULSE_WITH_BOX2D=ON to use it\n";
    return exit_bad_input;
#else
    const Project project = find_project(a.option("--root"));
    if (!project.box2d) {
        throw InputError(project.file, "box2d",
                         "is false: this project turns the Box2D comparison off");
    }
    options.engine = chosen_engine(project, a);
    if (const auto dir = a.option("--out")) {
        check_output_folder("--out", *dir, protected_folders(project));
    }
    std::vector<std::string> paths = scenes_named(project, a.positional);
    // Everything is computed before anything is written: a bad scene or a
    // shape Box2D cannot take is one sentence on stderr, with no half output.
    std::vector<ReferenceComparison> comparisons;
    {
        Progress progress("box2d", progress_wanted(a.has_flag("--quiet")));
        progress.set_total(paths.size(), "scenes");
        for (const std::string& path : paths) {
            progress.set_item(std::filesystem::path(path).stem().string());
            comparisons.push_back(compare_with_box2d(path, options));
            progress.advance();
        }
    }
    for (const ReferenceComparison& c : comparisons) {
        for (const std::string& warning : c.warnings) {
            err << "warning: " << warning << "\n";
        }
    }
    if (const auto dir = a.option("--out")) {
        write_runs(*dir, comparisons);
    }
    if (a.has_flag("--json")) {
        out << write_json(comparisons, options);
    } else {
        write_text(out, comparisons, options);
    }
    const bool all_passed = std::all_of(comparisons.begin(), comparisons.end(),
                                        [](const ReferenceComparison& c) { return c.passed(); });
    return all_passed ? exit_ok : exit_failed;
#endif
}

} // namespace impulse::harness::cli
