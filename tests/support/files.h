// Files for the tests: a file's bytes, writing one, and a scratch directory
// that is gone when the scope ends.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <unistd.h>

namespace impulse::test {

// A file's bytes ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Writes `text` as the file's bytes. A missing parent folder is made first;
// where that cannot be done the write fails quietly, as it would anyway.
inline void spit(const std::filesystem::path& path, const std::string& text) {
    std::error_code ignored;
    std::filesystem::create_directories(path.parent_path(), ignored);
    std::ofstream(path, std::ios::binary) << text;
}

// Gives the owner every permission on `dir` and each folder below it, so that
// what a test made read-only (a goldens folder, say) can be removed.
inline void restore_owner_permissions(const std::filesystem::path& dir) {
    std::error_code ignored;
    std::filesystem::permissions(dir, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::add, ignored);
    std::error_code error;
    for (std::filesystem::directory_iterator it(dir, error), end; !error && it != end;
         it.increment(error)) {
        if (it->is_directory(ignored) && !it->is_symlink(ignored)) {
            restore_owner_permissions(it->path());
        }
    }
}

// A fresh directory, removed with all it holds when the scope ends (owner
// permissions given back first); named after the test process so that
// parallel runs never share one.
struct TempDir {
    std::filesystem::path dir;
    TempDir() {
        static int counter = 0;
        dir = std::filesystem::temp_directory_path() /
              ("impulse-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
    }
    ~TempDir() {
        restore_owner_permissions(dir);
        std::error_code ignored;
        std::filesystem::remove_all(dir, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
};

} // namespace impulse::test
