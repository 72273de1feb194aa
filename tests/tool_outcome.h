// Running the built `impulse` and collecting what it did (exit, stdout,
// stderr), for the tests of test_refusals.cpp and test_progress.cpp.
//
// IMPULSE_TOOL_UNDER_TEST, when set, names another build of the tool to run
// instead (an older one, to watch a new test fail against it).
#pragma once

#include <catch2/catch.hpp>
#include <cerrno>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <spawn.h>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace impulse::test {

inline std::string slurp_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

// A fresh directory, removed with all it holds when the scope ends.
struct ScratchDir {
    std::filesystem::path dir;
    ScratchDir() {
        static int counter = 0;
        dir = std::filesystem::temp_directory_path() /
              ("impulse-refs-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
    }
    ~ScratchDir() {
        std::error_code ignored;
        std::filesystem::remove_all(dir, ignored);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
};

inline std::string tool_under_test() {
    const char* other = std::getenv("IMPULSE_TOOL_UNDER_TEST");
    return other != nullptr && *other != '\0' ? other : IMPULSE_BINARY;
}

// The environment for the tool: the test's own without CI and without the
// progress variables (so an outer setting cannot change what a test sees),
// plus `extra`.
inline std::vector<std::string> tool_environment(const std::vector<std::string>& extra) {
    std::vector<std::string> env;
    for (char** entry = environ; *entry != nullptr; ++entry) {
        const std::string e(*entry);
        if (e.rfind("CI=", 0) != 0 && e.rfind("IMPULSE_PROGRESS", 0) != 0) {
            env.push_back(e);
        }
    }
    env.insert(env.end(), extra.begin(), extra.end());
    return env;
}

// Starts the tool with stdout to `out_file` and stderr to the open descriptor
// `err_fd` (a file or a terminal), without a shell.
inline pid_t spawn_tool(const std::vector<std::string>& args, const std::vector<std::string>& extra,
                        const std::string& out_file, int err_fd) {
    const std::string binary = tool_under_test();
    std::vector<std::string> arguments = {binary};
    arguments.insert(arguments.end(), args.begin(), args.end());
    std::vector<std::string> env = tool_environment(extra);
    std::vector<char*> argv, envp;
    for (std::string& a : arguments) {
        argv.push_back(a.data());
    }
    argv.push_back(nullptr);
    for (std::string& e : env) {
        envp.push_back(e.data());
    }
    envp.push_back(nullptr);
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 1, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0600);
    posix_spawn_file_actions_adddup2(&files, err_fd, 2);
    pid_t pid = 0;
    const int spawned =
        posix_spawn(&pid, binary.c_str(), &files, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&files);
    REQUIRE(spawned == 0);
    return pid;
}

struct ToolOutcome {
    bool exited = false; // false: ended by a signal (an abort, a crash)
    int exit_code = -1;
    std::string out;
    std::string err;
};

inline ToolOutcome finish_tool(pid_t pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    ToolOutcome o;
    o.exited = WIFEXITED(status);
    o.exit_code = o.exited ? WEXITSTATUS(status) : -1;
    return o;
}

// Runs the tool to the end with stdout and stderr going to files.
inline ToolOutcome run_tool(const std::vector<std::string>& args,
                            const std::vector<std::string>& extra_env = {}) {
    const ScratchDir capture;
    const std::string out_file = (capture.dir / "stdout").string();
    const std::string err_file = (capture.dir / "stderr").string();
    const int err_fd = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    REQUIRE(err_fd >= 0);
    const pid_t pid = spawn_tool(args, extra_env, out_file, err_fd);
    ::close(err_fd);
    ToolOutcome o = finish_tool(pid);
    o.out = slurp_file(out_file);
    o.err = slurp_file(err_file);
    return o;
}

} // namespace impulse::test
