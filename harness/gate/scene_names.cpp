#include "scene_names.h"

#include <filesystem>

namespace impulse::harness {

std::string scene_stem(const std::string& path) {
    return std::filesystem::path(path).stem().string();
}

std::string lower_case(std::string text) {
    for (char& c : text) {
        if (c >= 'A' && c <= 'Z') {
            c = static_cast<char>(c - 'A' + 'a');
        }
    }
    return text;
}

const char* const case_clash_reason =
    "differ only in case: on a case-insensitive file system (macOS, "
    "Windows) they are one file and their goldens would overwrite each "
    "other; rename one";

} // namespace impulse::harness
