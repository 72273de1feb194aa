// A project (docs/project-file.md): where a repository's scenes and goldens
// are and which engines run them. Read from impulse.json, or implicit: this
// repository's layout (ROOT/harness/scenes, ROOT/goldens, the impulse engine)
// when there is no project file, so a tree without one behaves as before.
#pragma once

#include "engine.h"

#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

inline constexpr const char* project_schema = "impulse/project@1";
inline constexpr const char* project_file_name = "impulse.json";

struct Project {
    // The folder every path below is relative to: the project file's folder.
    std::string root = ".";
    // The project file; empty for the implicit project.
    std::string file;
    // Scene folders (every *.json directly inside) or glob patterns (wildcards
    // in the file-name part only), relative to root.
    std::vector<std::string> scenes{"harness/scenes"};
    std::string goldens = "goldens";
    // At least one; the first is the one run and render use.
    std::vector<EngineSpec> engines{impulse_engine()};
    // Whether `impulse box2d` and the report compare with Box2D.
    bool box2d = built_with_box2d();
    // The command hints name for regenerating goldens.
    std::string regen = "scripts/regen-goldens";

    bool is_implicit() const { return file.empty(); }
    // Where a message says the project comes from: the file, or "the implicit project".
    std::string origin() const;

    static bool built_with_box2d();
};

// The implicit project rooted at `root`.
Project implicit_project(const std::string& root);

// Reads a project file strictly: an unknown key, a duplicate key, a wrong type,
// a bad value or a scenes entry that matches nothing throws InputError naming
// the file and the JSON path.
Project load_project(const std::string& file);
Project parse_project(const std::string& text, const std::string& file, const std::string& root);

// The project of a verb: with --root DIR, DIR/impulse.json when present, else
// the implicit project at DIR; without it, the first impulse.json found
// walking up from the current folder (as git finds .git), else the implicit
// project at ".".
Project find_project(const std::optional<std::string>& root_option);

// ROOT/GOLDENS.
std::string goldens_dir(const Project& project);
// Where an engine's goldens go: ROOT/GOLDENS with one engine,
// ROOT/GOLDENS/ENGINE with several.
std::string golden_folder(const Project& project, const EngineSpec& engine);
std::string golden_path(const Project& project, const EngineSpec& engine,
                        const std::string& scene_name);

// The engine named `name` (--engine NAME): the project's engine of that name;
// with `builtins_too` (verbs that run one engine and write no golden: run,
// render, box2d, sweep, conform) also the built-in impulse, box2d or chipmunk. Else
// InputError listing the names there are.
EngineSpec engine_named(const Project& project, const std::string& name, bool builtins_too);
// Every engine, or the one --engine names.
std::vector<EngineSpec> engines_chosen(const Project& project,
                                       const std::optional<std::string>& name);

// The scene files of the project, sorted: every entry of `scenes` expanded.
// Throws InputError naming the project file and scenes[i] for an entry that
// matches nothing, and naming both files for two scenes that would share a
// golden (one name in two folders, or names differing only in case).
std::vector<std::string> project_scenes(const Project& project);
// The folder a scene NAME is looked for in when no project scene has that
// name: the first entry's folder.
std::string default_scene_folder(const Project& project);

} // namespace impulse::harness
