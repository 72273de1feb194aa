// `impulse render SCENE|TRAJECTORY`: an SVG picture of the motion.
#include "render.h"

#include "atomic_file.h"
#include "cli.h"
#include "engine.h"
#include "engine_option.h"
#include "gate.h"
#include "input_error.h"
#include "output_path.h"
#include "progress.h"
#include "project_options.h"
#include "run.h"

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>

namespace impulse::harness::cli {

namespace {

constexpr const char* render_help =
    R"(usage: impulse render SCENE|TRAJECTORY [--out FILE.svg] [--root DIR] [--engine NAME | --engine-command CMD]

Draws an SVG picture of the motion: every dynamic body's path, its outline at
key frames, each collision's contact point and normal, and a legend.

The file's "schema" decides what it is:
  impulse/scene@1       the scene is simulated (as 'impulse run' would, in the
                        project's first engine or --engine NAME) and drawn
  impulse/trajectory@1  the recorded run is drawn; the bodies' shapes come from
                        the project's scene NAME when that scene is the one
                        the trajectory was recorded from (same scene_sha256),
                        otherwise only paths, contact points and normals

  --out FILE.svg   write the picture here (atomically) instead of standard output
                   (a regular file, never one in goldens/; - is standard output)
  --root DIR       the project's folder (default: the first impulse.json found
                   from the current folder upwards; without one, the scenes
                   are in ./harness/scenes/)
  --engine NAME    run a scene in the project's engine NAME (or the built-in
                   impulse, box2d or chipmunk)
  --engine-command 'PROGRAM ARGS'
                   run a scene in an engine that speaks docs/engine-protocol.md
  --quiet          no progress bar (drawn on standard error only when that is a
                   terminal, after about a second of work)
)";

// The top-level "schema" string, or "" when there is none; throws InputError
// for text that is not JSON. Only that one value is kept while parsing.
std::string schema_of(const std::string& text, const std::string& file) {
    using Json = nlohmann::json;
    Json top;
    try {
        top = Json::parse(text, [](int depth, Json::parse_event_t event, Json& parsed) {
            if (event == Json::parse_event_t::key && depth == 1) {
                return parsed.is_string() && parsed.get<std::string>() == "schema";
            }
            return true;
        });
    } catch (const Json::exception&) {
        // The readers below give the exact message (line, column, merge markers).
        return "";
    }
    if (!top.is_object()) {
        throw InputError(
            file, "", "is neither a scene nor a trajectory: the top level must be a JSON object");
    }
    const auto it = top.find("schema");
    const std::string expected = std::string("a scene declares \"") + scene_schema +
                                 "\", a trajectory \"" + trajectory_schema + "\"";
    if (it == top.end()) {
        throw InputError(file, "schema", "is required but missing: " + expected);
    }
    if (!it->is_string()) {
        throw InputError(file, "schema", "must be a string: " + expected);
    }
    return it->get<std::string>();
}

bool starts_with(const std::string& text, const std::string& prefix) {
    return text.rfind(prefix, 0) == 0;
}

} // namespace

int render_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    const Arguments a = parse_arguments(args, {"--out", "--root", "--engine", "--engine-command"},
                                        {"--help", "--quiet"});
    if (a.has_flag("--help")) {
        out << render_help;
        return exit_ok;
    }
    if (a.positional.size() != 1) {
        throw UsageError("needs exactly one SCENE or TRAJECTORY, got " +
                         std::to_string(a.positional.size()));
    }
    const std::string& input = a.positional.front();
    const Project project = find_project(a.option("--root"));
    const EngineSpec engine = chosen_engine(project, a);
    const std::vector<std::string> goldens = protected_folders(project);
    if (const auto path = a.option("--out")) {
        check_output_file("--out", *path, goldens);
    }
    const std::string text = read_trajectory_text(input, "a trajectory to draw");
    const std::string schema = schema_of(text, input);

    // Erased (reset) before anything is written.
    std::optional<Progress> progress;
    progress.emplace("render", progress_wanted(a.has_flag("--quiet")));
    std::string svg;
    if (starts_with(schema, "impulse/scene@")) {
        const Scene scene = load_scene(input);
        progress->without_bar([&] {
            for (const std::string& warning : scene.warnings) {
                err << "warning: " << warning << "\n";
            }
            err.flush();
        });
        progress->set_item(scene.name);
        EngineRun ran = run_engine(engine, scene);
        if (ran.outcome == EngineRun::Outcome::unsupported) {
            throw InputError(scene.file, "", "unsupported by " + engine.name + ": " + ran.message);
        }
        svg = render_svg(scene, ran.trajectory);
    } else if (schema.empty() || starts_with(schema, "impulse/trajectory@")) {
        // An empty schema here means the text is not JSON: the trajectory
        // reader says where.
        const Trajectory trajectory = read_trajectory(text, input);
        std::string why_not;
        std::string scene_file;
        try {
            scene_file = resolve_scene(project, trajectory.scene);
        } catch (const InputError& e) {
            why_not = std::string("the project's scenes cannot be listed (") + e.what() + ")";
        }
        std::error_code error;
        if (!why_not.empty()) {
            // drawn without shapes, as below
        } else if (!std::filesystem::is_regular_file(scene_file, error)) {
            why_not = scene_file + " does not exist";
        } else {
            try {
                const Scene scene = load_scene(scene_file);
                if (scene.sha256 == trajectory.scene_sha256) {
                    svg = render_svg(scene, trajectory);
                } else {
                    why_not = scene_file + " has changed since the trajectory was recorded " +
                              "(its sha256 differs from the trajectory's scene_sha256)";
                }
            } catch (const InputError& e) {
                why_not = std::string("the scene does not load (") + e.what() + ")";
            }
        }
        if (!why_not.empty()) {
            progress->without_bar([&] {
                err << "note: " << why_not << "; drawing paths, contact points and normals only\n"
                    << std::flush;
            });
            svg = render_svg(trajectory);
        }
    } else {
        throw InputError(input, "schema",
                         "is \"" + schema + "\": render draws a scene (\"" + scene_schema +
                             "\") or a trajectory (\"" + trajectory_schema + "\")");
    }

    progress.reset();
    write_output_file("--out", a.option("--out").value_or(standard_output), svg, goldens, out);
    return exit_ok;
}

} // namespace impulse::harness::cli
