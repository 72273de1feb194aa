// Reading impulse.json (docs/project-file.md) as strictly as a scene, with
// the scene loader's typed reads, so a mistake is worded as in a scene file.
#include "atomic_file.h"
#include "input_error.h"
#include "project.h"
#include "scene_reading.h"
#include "strict_json.h"
#include "text.h"
#include "trajectory_fields.h"

#include <algorithm>
#include <filesystem>

namespace impulse::harness {

namespace fs = std::filesystem;
using scene_reading::Node;

namespace {

constexpr std::size_t max_project_bytes = 1 << 20;

// A path of the project file must stay inside the project's folder: scenes
// and goldens travel with the repository, and bless writes only below it.
fs::path read_inside_path(const Node& node) {
    const std::string text = scene_reading::read_string(node);
    if (text.empty()) {
        node.fail("must not be empty");
    }
    const fs::path path(text);
    if (path.is_absolute()) {
        node.fail("must be relative to the project file's folder, got " +
                  scene_reading::shown(node) +
                  ": an absolute path would not travel with the repository");
    }
    for (const fs::path& part : path) {
        if (part == "..") {
            node.fail("must stay inside the project file's folder (no '..'), got " +
                      scene_reading::shown(node) +
                      ": scenes and goldens travel with the repository, and bless writes only "
                      "below it");
        }
    }
    fs::path normal = path.lexically_normal();
    if (!normal.empty() && normal.filename().empty()) {
        normal = normal.parent_path(); // "goldens/" is the folder "goldens"
    }
    return normal;
}

bool has_wildcard(const std::string& text) {
    return text.find_first_of("*?[") != std::string::npos;
}

std::vector<std::string> read_scenes(const Node& node) {
    scene_reading::require_array(node);
    if (node.json().empty()) {
        node.fail("must name at least one scene folder or pattern");
    }
    std::vector<std::string> scenes;
    for (std::size_t i = 0; i < node.json().size(); ++i) {
        const Node entry = node.element(i);
        const fs::path path = read_inside_path(entry);
        if (has_wildcard(path.parent_path().string())) {
            entry.fail("may have wildcards (*, ?, [...]) only in its file-name part, got " +
                       scene_reading::shown(entry));
        }
        scenes.push_back(path.string());
    }
    return scenes;
}

// The folder a scenes entry reads: itself, or a pattern's folder.
std::string folder_of(const std::string& entry) {
    return has_wildcard(fs::path(entry).filename().string())
               ? fs::path(entry).parent_path().string()
               : entry;
}

std::string read_goldens(const Node& node, const std::vector<std::string>& scenes) {
    const fs::path path = read_inside_path(node);
    const std::string goldens = path.string();
    if (goldens == "." || goldens.empty()) {
        node.fail("must be a folder below the project file's folder, not the folder itself: "
                  "bless --prune deletes the .json files there that are not goldens");
    }
    for (const std::string& entry : scenes) {
        const std::string folder = folder_of(entry);
        if (folder == goldens || (folder.empty() && goldens == ".")) {
            node.fail("is also a scenes folder (\"" + entry +
                      "\"): a golden NAME.json would overwrite its scene NAME.json");
        }
        if (lower_case(folder) == lower_case(goldens)) {
            node.fail("and the scenes folder \"" + folder +
                      "\" differ only in case: on a case-insensitive file system (macOS, "
                      "Windows) they are one folder and a golden NAME.json would overwrite its "
                      "scene NAME.json; name the goldens folder apart");
        }
    }
    return goldens;
}

// An engine's "skip": the names of scenes it is not asked to run (a
// scene it cannot model, in a project whose other engines run it).
std::vector<std::string> read_skip(const Node& engine) {
    std::vector<std::string> names;
    const auto list = scene_reading::optional_member(engine, "skip");
    if (!list) {
        return names;
    }
    scene_reading::require_array(*list);
    for (std::size_t i = 0; i < list->json().size(); ++i) {
        const Node element = list->element(i);
        std::string name = scene_reading::read_name(element);
        if (std::find(names.begin(), names.end(), name) != names.end()) {
            element.fail("repeats the scene name \"" + name + "\"");
        }
        names.push_back(std::move(name));
    }
    return names;
}

EngineSpec read_engine(const Node& node, const std::string& root, const std::string& file) {
    scene_reading::require_object(node);
    scene_reading::reject_unknown_keys(node, {"name", "builtin", "command", "time_limit", "skip"});
    EngineSpec engine;
    engine.name = scene_reading::read_name(scene_reading::required_member(node, "name"));
    engine.origin = printable_path(file) + ": " + node.path();
    engine.skip = read_skip(node);
    const bool builtin = node.has("builtin"), command = node.has("command");
    if (builtin == command) {
        node.fail("must have exactly one of \"builtin\" (\"impulse\", \"box2d\" or "
                  "\"chipmunk\") and "
                  "\"command\" (the program that speaks docs/engine-protocol.md)");
    }
    if (builtin) {
        const Node kind = node.member("builtin");
        const std::string name = scene_reading::read_string(kind);
        if (name != "impulse" && name != "box2d" && name != "chipmunk") {
            kind.fail("must be \"impulse\", \"box2d\" or \"chipmunk\", got " +
                      scene_reading::shown(kind));
        }
        if (node.has("time_limit")) {
            node.member("time_limit")
                .fail("applies to an engine with a \"command\"; a builtin engine runs in process");
        }
        engine.kind = name == "impulse" ? EngineSpec::Kind::impulse
                      : name == "box2d" ? EngineSpec::Kind::box2d
                                        : EngineSpec::Kind::chipmunk;
        return engine;
    }
    const Node list = node.member("command");
    scene_reading::require_array(list);
    if (list.json().empty()) {
        list.fail("must name the program to run, as [\"program\", \"argument\", ...]");
    }
    for (std::size_t i = 0; i < list.json().size(); ++i) {
        engine.command.push_back(scene_reading::read_string(list.element(i)));
    }
    if (engine.command.front().empty()) {
        list.element(0).fail("must name the program to run, got \"\"");
    }
    if (const auto limit = scene_reading::optional_member(node, "time_limit")) {
        engine.time_limit = scene_reading::read_positive(*limit);
    }
    engine.kind = EngineSpec::Kind::external;
    std::error_code error;
    const fs::path absolute = fs::absolute(root, error);
    engine.working_directory = error ? root : absolute.lexically_normal().string();
    return engine;
}

std::vector<EngineSpec> read_engines(const Node& node, const std::string& root,
                                     const std::string& file) {
    scene_reading::require_array(node);
    if (node.json().empty()) {
        node.fail("must name at least one engine");
    }
    std::vector<EngineSpec> engines;
    for (std::size_t i = 0; i < node.json().size(); ++i) {
        EngineSpec engine = read_engine(node.element(i), root, file);
        for (const EngineSpec& earlier : engines) {
            if (earlier.name == engine.name) {
                node.element(i).member("name").fail(
                    "repeats the engine name \"" + engine.name +
                    "\": each engine's goldens are goldens/ENGINE/, so names must be unique");
            }
        }
        engines.push_back(std::move(engine));
    }
    return engines;
}

Project read_project(const Node& top, const std::string& file, const std::string& root) {
    scene_reading::require_object(top);
    scene_reading::reject_unknown_keys(
        top, {"schema", "scenes", "goldens", "engines", "box2d", "regen"});
    const Node schema = scene_reading::required_member(top, "schema");
    if (!schema.json().is_string() || schema.json().get<std::string>() != project_schema) {
        schema.fail(std::string("must be \"") + project_schema + "\", got " +
                    scene_reading::shown(schema));
    }
    Project project;
    project.root = root;
    project.file = file;
    project.regen = "impulse regen";
    project.scenes = read_scenes(scene_reading::required_member(top, "scenes"));
    if (const auto goldens = scene_reading::optional_member(top, "goldens")) {
        project.goldens = read_goldens(*goldens, project.scenes);
    }
    if (const auto engines = scene_reading::optional_member(top, "engines")) {
        project.engines = read_engines(*engines, root, file);
    }
    if (const auto box2d = scene_reading::optional_member(top, "box2d")) {
        project.box2d = scene_reading::read_bool(*box2d);
    }
    if (const auto regen = scene_reading::optional_member(top, "regen")) {
        project.regen = scene_reading::read_string(*regen);
        if (project.regen.empty()) {
            regen->fail("must not be empty: it is the command hints tell you to run");
        }
        // Printed inside hints and tables: a newline or an escape sequence
        // would forge a line of check's table (an outside review's "ok drop").
        trajectory_fields::require_printable(project.regen, regen->path());
    }
    return project;
}

// A "skip" entry must name a scene of the project: a misspelt one would
// skip nothing, silently.
void refuse_unknown_skips(const Project& project, const std::vector<std::string>& scene_files) {
    std::vector<std::string> names;
    for (const std::string& path : scene_files) {
        names.push_back(fs::path(path).stem().string());
    }
    for (std::size_t e = 0; e < project.engines.size(); ++e) {
        const std::vector<std::string>& skip = project.engines[e].skip;
        for (std::size_t k = 0; k < skip.size(); ++k) {
            if (std::find(names.begin(), names.end(), skip[k]) == names.end()) {
                throw InputError(project.file,
                                 "engines[" + std::to_string(e) + "].skip[" + std::to_string(k) +
                                     "]",
                                 "names no scene of the project: \"" + skip[k] +
                                     "\" matches no file of \"scenes\"");
            }
        }
    }
}

// The folder a path of the project names on disk, through any symlink.
fs::path resolved(const fs::path& path) {
    std::error_code error;
    const fs::path canonical = fs::weakly_canonical(path, error);
    return error ? fs::absolute(path, error).lexically_normal() : canonical;
}

// The checks read_goldens makes on the text, made again on the disk: a
// goldens folder that is a symlink (or lies below one) to the project's own
// folder, to a scenes folder or out of the project would let bless overwrite
// scene files and --prune delete the project file (an outside review did
// both), whatever the text says.
void refuse_goldens_resolving_elsewhere(const Project& project) {
    const fs::path root = resolved(project.root);
    std::vector<fs::path> scene_folders;
    for (const std::string& entry : project.scenes) {
        scene_folders.push_back(resolved(fs::path(project.root) / folder_of(entry)));
    }
    std::vector<std::string> folders{goldens_dir(project)};
    if (project.engines.size() > 1) {
        for (const EngineSpec& engine : project.engines) {
            folders.push_back(golden_folder(project, engine));
        }
    }
    for (const std::string& folder : folders) {
        const fs::path where = resolved(folder);
        const fs::path inside = where.lexically_relative(root);
        std::string problem;
        if (inside.empty() || inside == "." || *inside.begin() == "..") {
            problem = "resolves on disk to " + printable_path(where.string()) +
                      (inside == "." ? ", the project's own folder (through a symbolic link): "
                                       "goldens need a folder of their own below it"
                                     : ", outside the project's folder (through a symbolic "
                                       "link): bless writes only below the project's folder");
        }
        for (std::size_t i = 0; problem.empty() && i < scene_folders.size(); ++i) {
            if (where == scene_folders[i]) {
                problem = "resolves on disk to " + printable_path(where.string()) +
                          ", the folder of scenes[" + std::to_string(i) +
                          "] (through a symbolic link): a golden NAME.json would overwrite its "
                          "scene NAME.json";
            }
        }
        if (!problem.empty()) {
            const bool top = folder == folders.front();
            throw InputError(project.file, "goldens",
                             (top ? "\"" + project.goldens + "\" "
                                  : "\"" +
                                        fs::path(folder).lexically_relative(project.root).string() +
                                        "\" (an engine's goldens) ") +
                                 problem);
        }
    }
}

} // namespace

Project parse_project(const std::string& text, const std::string& file, const std::string& root) {
    const nlohmann::json document = parse_strict_json<nlohmann::json>(text, file);
    try {
        return read_project(Node(document, ""), file, root);
    } catch (const json_fields::FieldError& error) {
        throw InputError(file, error.path, error.message);
    }
}

Project load_project(const std::string& file) {
    const std::string root = fs::path(file).parent_path().string();
    Project project =
        parse_project(read_file(file, max_project_bytes, "a project file is a few hundred bytes"),
                      file, root.empty() ? "." : root);
    // Every verb, even one that names its scene by path, refuses a project
    // whose scenes entry matches nothing: the mistake is said where it is made.
    refuse_unknown_skips(project, project_scenes(project));
    refuse_goldens_resolving_elsewhere(project);
    return project;
}

} // namespace impulse::harness
