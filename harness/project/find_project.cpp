// Finding the project of a verb: --root DIR, or the first impulse.json above
// the current folder.
#include "input_error.h"
#include "project.h"

#include <filesystem>

namespace impulse::harness {

namespace fs = std::filesystem;

namespace {

// Whether anything is at `path` (a broken project file is read and refused
// with its sentence, never passed over for the implicit project).
bool entry_exists(const fs::path& path) {
    std::error_code error;
    return fs::symlink_status(path, error).type() != fs::file_type::not_found;
}

// `dir` relative to the current folder ("." or "../.."), so the paths in
// messages stay as short as the ones a user typed; absolute when that fails.
std::string shortest(const fs::path& dir, const fs::path& cwd) {
    std::error_code error;
    const fs::path relative = fs::relative(dir, cwd, error);
    if (error || relative.empty()) {
        return dir.string();
    }
    return relative.string();
}

// --root names the project's folder: one that is missing or is a file is
// said as such, not as "no scene folder here" below it.
void require_root_folder(const std::string& root) {
    std::error_code error;
    const fs::file_status status = fs::status(root, error);
    if (!fs::exists(status)) {
        throw InputError(root, "--root", "does not exist; give the project's folder");
    }
    if (!fs::is_directory(status)) {
        throw InputError(root, "--root", "is not a folder; give the project's folder");
    }
}

} // namespace

Project find_project(const std::optional<std::string>& root_option) {
    if (root_option) {
        require_root_folder(*root_option);
        const fs::path file = fs::path(*root_option) / project_file_name;
        if (entry_exists(file)) {
            Project project = load_project(file.string());
            project.root = *root_option;
            return project;
        }
        return implicit_project(*root_option);
    }
    std::error_code error;
    const fs::path cwd = fs::current_path(error);
    if (error) {
        return implicit_project(".");
    }
    for (fs::path dir = cwd;; dir = dir.parent_path()) {
        const fs::path file = dir / project_file_name;
        if (entry_exists(file)) {
            const std::string root = shortest(dir, cwd);
            Project project =
                load_project(root == "." ? std::string(project_file_name)
                                         : (fs::path(root) / project_file_name).string());
            project.root = root;
            return project;
        }
        if (dir == dir.root_path() || dir.parent_path() == dir) {
            break;
        }
    }
    return implicit_project(".");
}

} // namespace impulse::harness
