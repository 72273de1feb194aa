// The project's scene files: each entry of "scenes" is a folder (every
// NAME.json directly inside) or a glob whose file-name part has wildcards.
#include "input_error.h"
#include "project.h"
#include "strict_json.h"

#include <algorithm>
#include <filesystem>
#include <fnmatch.h>

namespace impulse::harness {

namespace fs = std::filesystem;

namespace {

bool is_pattern(const std::string& entry) {
    return fs::path(entry).filename().string().find_first_of("*?[") != std::string::npos;
}

// Where a message about scenes[i] points: the project file and the JSON path,
// or the folder itself for the implicit project (today's sentence).
[[noreturn]] void entry_failure(const Project& project, std::size_t i, const std::string& folder,
                                const std::string& message) {
    if (project.is_implicit()) {
        throw InputError(folder, "",
                         "no scene folder here; run from the repository root or give --root");
    }
    throw InputError(project.file, json_element_path("scenes", i),
                     "\"" + project.scenes[i] + "\" " + message);
}

// Every entry of `folder` whose name the entry selects: *.json for a folder,
// the pattern for a glob. Every such entry is a scene, whatever it is: one
// that cannot be read (a dangling symlink, a folder) is that scene's error
// when it is loaded, never skipped, and its golden is never pruned.
std::vector<std::string> expand(const Project& project, std::size_t i) {
    const std::string& entry = project.scenes[i];
    const bool pattern = is_pattern(entry);
    const fs::path folder =
        fs::path(project.root) / (pattern ? fs::path(entry).parent_path() : fs::path(entry));
    const std::string name_pattern = pattern ? fs::path(entry).filename().string() : "*.json";
    std::error_code error;
    if (!fs::is_directory(folder, error)) {
        entry_failure(project, i, folder.string(),
                      pattern ? "names a folder that does not exist: " + folder.string()
                              : "is not a folder (scenes lists folders of scenes or patterns "
                                "such as \"scenes/*.json\")");
    }
    const fs::path own_file = project.is_implicit() ? fs::path() : fs::path(project.file);
    std::vector<std::string> paths;
    std::error_code not_same; // the project file itself is never a scene
    for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
        const std::string name = it->path().filename().string();
        if (it->path().extension() == ".json" &&
            ::fnmatch(name_pattern.c_str(), name.c_str(), FNM_PERIOD) == 0 &&
            !(own_file.filename() == name && fs::equivalent(own_file, it->path(), not_same))) {
            paths.push_back(it->path().string());
        }
    }
    if (error) {
        entry_failure(project, i, folder.string(), "cannot be listed: " + error.message());
    }
    if (paths.empty() && !project.is_implicit()) {
        entry_failure(project, i, folder.string(),
                      pattern ? "matches no scene file (NAME.json)"
                              : "holds no scene file (NAME.json)");
    }
    return paths;
}

std::string stem(const std::string& path) {
    return fs::path(path).stem().string();
}

} // namespace

std::vector<std::string> project_scenes(const Project& project) {
    std::vector<std::string> paths;
    for (std::size_t i = 0; i < project.scenes.size(); ++i) {
        for (const std::string& path : expand(project, i)) {
            // One file reached by two entries (a folder and a glob) is one scene.
            if (std::find(paths.begin(), paths.end(), path) == paths.end()) {
                paths.push_back(path);
            }
        }
    }
    std::sort(paths.begin(), paths.end());
    for (std::size_t i = 0; i + 1 < paths.size(); ++i) {
        for (std::size_t j = i + 1; j < paths.size(); ++j) {
            if (stem(paths[i]) == stem(paths[j])) {
                throw InputError(paths[i], "",
                                 "and " + paths[j] +
                                     " have one name, so they would share one golden; rename one");
            }
        }
    }
    return paths;
}

std::string default_scene_folder(const Project& project) {
    const std::string& entry = project.scenes.front();
    return (fs::path(project.root) /
            (is_pattern(entry) ? fs::path(entry).parent_path() : fs::path(entry)))
        .string();
}

} // namespace impulse::harness
