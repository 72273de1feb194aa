#include "project.h"

#include "input_error.h"
#include "json_fields.h"

#include <filesystem>

namespace impulse::harness {

namespace fs = std::filesystem;

bool Project::built_with_box2d() {
#ifdef IMPULSE_WITH_BOX2D
    return true;
#else
    return false;
#endif
}

std::string Project::origin() const {
    return is_implicit() ? "the implicit project at " + root : file;
}

Project implicit_project(const std::string& root) {
    Project project;
    project.root = root;
    return project;
}

std::string goldens_dir(const Project& project) {
    return (fs::path(project.root) / project.goldens).string();
}

std::string golden_folder(const Project& project, const EngineSpec& engine) {
    if (project.engines.size() <= 1) {
        return goldens_dir(project);
    }
    return (fs::path(goldens_dir(project)) / engine.name).string();
}

std::string golden_path(const Project& project, const EngineSpec& engine,
                        const std::string& scene_name) {
    return (fs::path(golden_folder(project, engine)) / (scene_name + ".json")).string();
}

EngineSpec engine_named(const Project& project, const std::string& name, bool builtins_too) {
    std::vector<std::string> names;
    for (const EngineSpec& engine : project.engines) {
        if (engine.name == name) {
            return engine;
        }
        names.push_back(engine.name);
    }
    // A verb that runs one engine may also name a built-in one the project
    // does not list: `conform --engine box2d` scores Box2D in any repository.
    if (builtins_too && name == "impulse") {
        return impulse_engine();
    }
    if (builtins_too && name == "box2d" && Project::built_with_box2d()) {
        return box2d_engine();
    }
    // Always named: a build without Chipmunk2D says so when it runs.
    if (builtins_too && name == "chipmunk") {
        return chipmunk_engine();
    }
    std::string known = "the project's engines are " + json_fields::list_of(names);
    if (builtins_too) {
        known += Project::built_with_box2d() ? ", and the built-in impulse, box2d and chipmunk"
                                             : ", and the built-in impulse and chipmunk";
    }
    throw InputError(project.is_implicit() ? "--engine" : project.file,
                     project.is_implicit() ? "" : "engines",
                     "no engine is named '" + name + "' (--engine); " + known);
}

std::vector<EngineSpec> engines_chosen(const Project& project,
                                       const std::optional<std::string>& name) {
    if (name) {
        return {engine_named(project, *name, false)};
    }
    return project.engines;
}

} // namespace impulse::harness
