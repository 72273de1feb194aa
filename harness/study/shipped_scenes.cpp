#include "shipped_scenes.h"

#include "input_error.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace impulse::harness {

namespace fs = std::filesystem;

namespace {

bool is_folder(const fs::path& path) {
    std::error_code error;
    return fs::is_directory(path, error);
}

// Where an installed tool keeps them, beside its bin/ folder; empty when the
// executable cannot be found (/proc not mounted).
fs::path installed_scenes_dir() {
    std::error_code error;
    const fs::path exe = fs::read_symlink("/proc/self/exe", error);
    if (error || exe.empty()) {
        return {};
    }
    return exe.parent_path().parent_path() / "share" / "impulse" / "scenes";
}

} // namespace

std::string shipped_scenes_dir() {
    const char* set = std::getenv("IMPULSE_SCENES_DIR");
    if (set != nullptr && *set != '\0') {
        if (!is_folder(set)) {
            throw InputError(set, "",
                             "IMPULSE_SCENES_DIR names this, which is not a folder of scenes");
        }
        return set;
    }
    const fs::path installed = installed_scenes_dir();
    if (!installed.empty() && is_folder(installed)) {
        return installed.lexically_normal().string();
    }
    // The build's own source tree: a tool run from its build folder.
    const fs::path source = fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes";
    if (is_folder(source)) {
        return source.string();
    }
    throw InputError(installed.empty() ? source.string() : installed.string(), "",
                     "no shipped scenes here, nor in " + source.string() +
                         "; install impulse (cmake --install) or set IMPULSE_SCENES_DIR");
}

} // namespace impulse::harness
