// Running the built `impulse` as a child process, without a shell, and
// collecting what it did (exit, stdout, stderr): for the tests that check
// what the tool does as a program (exit codes, its output files, being
// killed half-way, its refusals, its progress on a terminal).
//
// IMPULSE_TOOL_UNDER_TEST, when set, names another build of the tool to run
// instead (an older one, to watch a new test fail against it).
#pragma once

#include "files.h"

#include <catch2/catch.hpp>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <optional>
#include <spawn.h>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

// AddressSanitizer reserves terabytes of address space for its shadow memory,
// so an address-space limit kills an ASan build at start-up: tests that need
// one skip themselves there (gcc defines the macro, clang has the feature).
#if defined(__SANITIZE_ADDRESS__)
#define IMPULSE_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define IMPULSE_TEST_UNDER_ASAN 1
#endif
#endif

extern char** environ;

namespace impulse::test {

#ifdef IMPULSE_TEST_UNDER_ASAN
inline constexpr bool under_address_sanitizer = true;
#else
inline constexpr bool under_address_sanitizer = false;
#endif

// What a run of the tool did. In-process runs of a verb fill it too, with
// `exited` true.
struct Outcome {
    bool exited = false; // false: ended by a signal (an abort, a crash)
    int exit_code = -1;  // -1 when ended by a signal
    std::string out;
    std::string err;
};

// Resource limits for the child, set between fork and exec, so the test
// process itself is never limited.
struct ChildLimits {
    std::optional<rlim_t> address_space_bytes; // RLIMIT_AS: allocations past it fail
    // RLIMIT_FSIZE, with SIGXFSZ ignored: a write past it fails with EFBIG, as
    // on a full disk, instead of killing the tool.
    std::optional<rlim_t> file_size_bytes;
};

inline std::string tool_under_test() {
    const char* other = std::getenv("IMPULSE_TOOL_UNDER_TEST");
    return other != nullptr && *other != '\0' ? other : IMPULSE_BINARY;
}

// The tool's argv and environment: the test's environment without CI (so
// bless writes and check is not in CI mode) and without the progress
// variables (so an outer setting cannot change what a test sees), plus
// `extra_env` ("CI=true"). The pointers point into the strings held here, so
// they live as long as the command.
struct ToolCommand {
    std::vector<std::string> arguments;
    std::vector<std::string> environment;
    std::vector<char*> argv;
    std::vector<char*> envp;

    ToolCommand(const std::vector<std::string>& args, const std::vector<std::string>& extra_env) {
        for (char** entry = environ; *entry != nullptr; ++entry) {
            const std::string e(*entry);
            if (e.rfind("CI=", 0) != 0 && e.rfind("IMPULSE_PROGRESS", 0) != 0) {
                environment.push_back(e);
            }
        }
        environment.insert(environment.end(), extra_env.begin(), extra_env.end());
        arguments = {tool_under_test()};
        arguments.insert(arguments.end(), args.begin(), args.end());
        for (std::string& a : arguments) {
            argv.push_back(a.data());
        }
        argv.push_back(nullptr);
        for (std::string& e : environment) {
            envp.push_back(e.data());
        }
        envp.push_back(nullptr);
    }
    const char* binary() const { return arguments.front().c_str(); }
    ToolCommand(const ToolCommand&) = delete;
    ToolCommand& operator=(const ToolCommand&) = delete;
};

// Starts the tool with stdout to `out_file` and stderr to `err_file`, or to
// the open descriptor `err_fd` when it is not -1 (a terminal).
inline pid_t spawn_tool(const std::vector<std::string>& args,
                        const std::vector<std::string>& extra_env, const std::string& out_file,
                        const std::string& err_file, int err_fd = -1) {
    ToolCommand command(args, extra_env);
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 1, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0600);
    if (err_fd >= 0) {
        posix_spawn_file_actions_adddup2(&files, err_fd, 2);
    } else {
        posix_spawn_file_actions_addopen(&files, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                         0600);
    }
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, command.binary(), &files, nullptr, command.argv.data(),
                                    command.envp.data());
    posix_spawn_file_actions_destroy(&files);
    REQUIRE(spawned == 0);
    return pid;
}

// Starts the built tool, its output going to the given files (or /dev/null).
inline pid_t start_tool(const std::vector<std::string>& args,
                        const std::vector<std::string>& extra_env = {},
                        const std::string& out_file = "/dev/null",
                        const std::string& err_file = "/dev/null") {
    return spawn_tool(args, extra_env, out_file, err_file);
}

// As start_tool, under `limits`. fork and exec instead of posix_spawn, which
// cannot set resource limits; only async-signal-safe calls in the child.
inline pid_t start_tool_limited(const std::vector<std::string>& args, const ChildLimits& limits,
                                const std::string& out_file = "/dev/null",
                                const std::string& err_file = "/dev/null",
                                const std::vector<std::string>& extra_env = {}) {
    ToolCommand command(args, extra_env);
    const struct rlimit address_space = {limits.address_space_bytes.value_or(RLIM_INFINITY),
                                         limits.address_space_bytes.value_or(RLIM_INFINITY)};
    const struct rlimit file_size = {limits.file_size_bytes.value_or(RLIM_INFINITY),
                                     limits.file_size_bytes.value_or(RLIM_INFINITY)};

    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int out_fd = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        const int err_fd = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (out_fd < 0 || err_fd < 0 || ::dup2(out_fd, 1) < 0 || ::dup2(err_fd, 2) < 0) {
            ::_exit(126);
        }
        if (limits.file_size_bytes && (std::signal(SIGXFSZ, SIG_IGN) == SIG_ERR ||
                                       ::setrlimit(RLIMIT_FSIZE, &file_size) != 0)) {
            ::_exit(126);
        }
        if (limits.address_space_bytes && ::setrlimit(RLIMIT_AS, &address_space) != 0) {
            ::_exit(126);
        }
        ::execve(command.binary(), command.argv.data(), command.envp.data());
        ::_exit(127);
    }
    return pid;
}

inline int wait_for(pid_t pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return status;
}

// The outcome of a wait status, with what the run wrote to its files.
inline Outcome outcome_of(int status, const std::filesystem::path& out_file,
                          const std::filesystem::path& err_file) {
    Outcome o;
    o.exited = WIFEXITED(status);
    o.exit_code = o.exited ? WEXITSTATUS(status) : -1;
    o.out = slurp(out_file);
    o.err = slurp(err_file);
    return o;
}

// Runs the tool to the end with stdout and stderr going to files.
inline Outcome run_tool(const std::vector<std::string>& args,
                        const std::vector<std::string>& extra_env = {}) {
    const TempDir capture;
    const std::filesystem::path out = capture.dir / "stdout", err = capture.dir / "stderr";
    return outcome_of(wait_for(start_tool(args, extra_env, out.string(), err.string())), out, err);
}

// As run_tool, under `limits`.
inline Outcome run_tool_limited(const std::vector<std::string>& args, const ChildLimits& limits,
                                const std::vector<std::string>& extra_env = {}) {
    const TempDir capture;
    const std::filesystem::path out = capture.dir / "stdout", err = capture.dir / "stderr";
    return outcome_of(
        wait_for(start_tool_limited(args, limits, out.string(), err.string(), extra_env)), out,
        err);
}

} // namespace impulse::test
