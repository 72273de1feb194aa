// What is at a path, for the tests that an output path is never destroyed
// (test_output_paths.cpp, and fuzz/fuzz_output_path.cpp, which includes this
// file from the tests' support): two equal states mean untouched.
#pragma once

#include "files.h"

#include <filesystem>
#include <string>
#include <sys/stat.h>

namespace impulse::test {

// What is at a path, as lstat sees it, with a file's bytes, a link's target
// or a folder's entries: equal before and after means untouched.
inline std::string state_of(const std::filesystem::path& path) {
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0) {
        return "missing";
    }
    if (S_ISLNK(info.st_mode)) {
        return "link to " + std::filesystem::read_symlink(path).string();
    }
    if (S_ISREG(info.st_mode)) {
        return "file " + slurp(path);
    }
    if (S_ISDIR(info.st_mode)) {
        std::string entries = "folder";
        for (const std::filesystem::directory_entry& e :
             std::filesystem::directory_iterator(path)) {
            entries += " " + e.path().filename().string();
        }
        return entries;
    }
    if (S_ISFIFO(info.st_mode)) {
        return "fifo";
    }
    if (S_ISCHR(info.st_mode)) {
        return "character device " + std::to_string(info.st_rdev);
    }
    return "other";
}

} // namespace impulse::test
