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

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness::cli {

namespace {

constexpr const char* render_help =
    R"(usage: impulse render SCENE|TRAJECTORY [--out FILE.svg] [--scene SCENE] [--root DIR] [--engine NAME | --engine-command CMD]

Draws an SVG picture of the motion: every dynamic body's path, its outline at
key frames (labelled with their times), each collision's contact point and
normal (its time beside it when there are at most 12, and in its tooltip), and
a legend. A partial trajectory (a run that stopped early) is marked where it
stopped: a red ring around each body at the last frame, its time and the
reason in the title and the legend.

The argument is a file or the name of a project scene (as for run and check);
the file's "schema" decides what it is:
  impulse/scene@1       the scene is simulated (as 'impulse run' would, in the
                        project's first engine or --engine NAME) and drawn
  impulse/trajectory@1  the recorded run is drawn, with the static bodies and
                        the shapes of its scene: --scene SCENE, or else the
                        scene of the trajectory's name in the project of --root
                        (or the current folder), then in the project the
                        trajectory's own folder lies in (found upwards); a scene
                        is used only when its sha256 is the trajectory's
                        scene_sha256. Without one: a note saying why, and only
                        paths, contact points and normals

  --out FILE.svg   write the picture here (atomically) instead of standard output
                   (a regular file, never one in goldens/; - is standard output)
  --scene SCENE    the scene a trajectory was recorded from (a file or a project
                   scene name); refused (exit 2) when its sha256 is not the
                   trajectory's scene_sha256
  --root DIR       the project's folder (default: the first impulse.json found
                   from the current folder upwards; without one, the scenes
                   are in ./harness/scenes/)
  --engine NAME    run a scene in the project's engine NAME (or the built-in
                   impulse, box2d or chipmunk)
  --engine-command 'PROGRAM ARGS'
                   run a scene in an engine that speaks docs/engine-protocol.md
  --quiet          no progress bar (drawn on standard error only when that is a
                   terminal, after about a second of work)

Exit 0 when the picture is written; 2 for bad input (nothing is written).
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

std::string mismatch_reason(const std::string& scene_file, const std::string& trajectory_file) {
    return scene_file + " has changed since " + trajectory_file +
           " was recorded, or is another scene (its sha256 differs from the trajectory's "
           "scene_sha256)";
}

// --scene SCENE: the user's choice, so a scene that does not load or is not
// the one recorded is refused (exit 2) rather than drawn with wrong shapes.
Scene given_scene(const Project& project, const std::string& argument, const Trajectory& trajectory,
                  const std::string& trajectory_file) {
    Scene scene = load_scene(scene_argument(project, argument));
    if (scene.sha256 != trajectory.scene_sha256) {
        throw InputError("--scene", "", mismatch_reason(scene.file, trajectory_file));
    }
    return scene;
}

// The scene the trajectory names, looked for in the project of --root (or
// the current folder) and then in the project the trajectory file lies in,
// taken only when its sha256 is the trajectory's scene_sha256. Otherwise
// empty, with why_not saying what was looked at.
std::optional<Scene> recorded_scene(const Project& project, const Trajectory& trajectory,
                                    const std::string& trajectory_file, std::string& why_not) {
    const std::string& name = trajectory.scene;
    if (name.empty() || name.find('/') != std::string::npos ||
        std::filesystem::path(name).extension() == ".json") {
        why_not = "the trajectory's scene name \"" + name + "\" is no project scene name";
        return std::nullopt;
    }
    std::vector<Project> projects{project};
    if (std::optional<Project> around = project_around(trajectory_file)) {
        projects.push_back(std::move(*around));
    }
    std::vector<std::string> looked_at;
    std::vector<std::string> reasons;
    for (const Project& p : projects) {
        std::string file;
        try {
            file = resolve_scene(p, name);
        } catch (const InputError& e) {
            reasons.push_back(std::string("the scenes of ") + p.origin() + " cannot be listed (" +
                              e.what() + ")");
            continue;
        }
        std::error_code error;
        const std::string key = std::filesystem::weakly_canonical(file, error).string();
        if (std::find(looked_at.begin(), looked_at.end(), key) != looked_at.end()) {
            continue;
        }
        looked_at.push_back(key);
        if (!std::filesystem::is_regular_file(file, error)) {
            reasons.push_back(file + " does not exist");
            continue;
        }
        try {
            Scene scene = load_scene(file);
            if (scene.sha256 == trajectory.scene_sha256) {
                return scene;
            }
            reasons.push_back(mismatch_reason(file, trajectory_file));
        } catch (const InputError& e) {
            reasons.push_back(std::string("the scene does not load (") + e.what() + ")");
        }
    }
    for (const std::string& reason : reasons) {
        why_not += (why_not.empty() ? "" : "; ") + reason;
    }
    return std::nullopt;
}

} // namespace

int render_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    const Arguments a =
        parse_arguments(args, {"--out", "--root", "--engine", "--engine-command", "--scene"},
                        {"--help", "--quiet"});
    if (a.has_flag("--help")) {
        out << render_help;
        return exit_ok;
    }
    if (a.positional.size() != 1) {
        throw UsageError("needs exactly one SCENE or TRAJECTORY, got " +
                         std::to_string(a.positional.size()));
    }
    const Project project = find_project(a.option("--root"));
    // A file, or the name of a project scene (as run and check take it).
    const std::string input = scene_argument(project, a.positional.front());
    const EngineSpec engine = chosen_engine(project, a);
    const std::vector<std::string> goldens = protected_folders(project);
    if (const auto path = a.option("--out")) {
        check_output_file("--out", *path, goldens);
        refuse_input_as_output("--out", *path, {input, a.option("--scene").value_or(input)});
    }
    const std::string text = read_trajectory_text(input, "a trajectory to draw");
    const std::string schema = schema_of(text, input);

    // Erased (reset) before anything is written.
    std::optional<Progress> progress;
    progress.emplace("render", progress_wanted(a.has_flag("--quiet")));
    std::string svg;
    if (starts_with(schema, "impulse/scene@")) {
        if (a.option("--scene")) {
            throw UsageError("--scene names the scene of a trajectory, but " + input +
                             " is a scene itself");
        }
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
        const std::optional<Scene> scene =
            a.option("--scene") ? std::optional<Scene>(
                                      given_scene(project, *a.option("--scene"), trajectory, input))
                                : recorded_scene(project, trajectory, input, why_not);
        if (scene) {
            svg = render_svg(*scene, trajectory);
        } else {
            progress->without_bar([&] {
                err << "note: " << why_not
                    << "; drawing paths, contact points and normals only (give the scene with "
                       "--scene)\n"
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
