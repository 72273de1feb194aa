#include "project_options.h"

#include "output_path.h"

namespace impulse::harness::cli {

std::vector<std::string> protected_folders(const Project& project) {
    std::vector<std::string> folders = goldens_folders(project.root);
    folders.push_back(goldens_dir(project));
    return folders;
}

std::string engine_names(const std::vector<EngineSpec>& engines) {
    std::string names;
    for (const EngineSpec& engine : engines) {
        names += (names.empty() ? "" : ", ") + engine.name;
    }
    return names;
}

} // namespace impulse::harness::cli
