#include "scene_names.h"

#include <filesystem>

namespace impulse::harness {

std::string scene_stem(const std::string& path) {
    return std::filesystem::path(path).stem().string();
}

const char* const case_clash_reason =
    "differ only in case: on a case-insensitive file system (macOS, "
    "Windows) they are one file and their goldens would overwrite each "
    "other; rename one";

} // namespace impulse::harness
