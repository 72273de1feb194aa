// Running the built `impulse` as a child process, without a shell, for the
// tests that check what the tool does as a program (exit codes, its output
// files, being killed half-way).
#pragma once

#include <catch2/catch.hpp>
#include <cerrno>
#include <csignal>
#include <fcntl.h>
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

// Resource limits for the child, set between fork and exec, so the test
// process itself is never limited.
struct ChildLimits {
    std::optional<rlim_t> address_space_bytes; // RLIMIT_AS: allocations past it fail
    // RLIMIT_FSIZE, with SIGXFSZ ignored: a write past it fails with EFBIG, as
    // on a full disk, instead of killing the tool.
    std::optional<rlim_t> file_size_bytes;
};

// The tool's argv and environment: the test's environment without CI (so
// bless writes), plus `extra_env` ("CI=true"). The pointers point into the
// strings held here, so they live as long as the command.
struct ToolCommand {
    std::vector<std::string> arguments;
    std::vector<std::string> environment;
    std::vector<char*> argv;
    std::vector<char*> envp;

    ToolCommand(const std::vector<std::string>& args, const std::vector<std::string>& extra_env) {
        for (char** entry = environ; *entry != nullptr; ++entry) {
            if (std::string(*entry).rfind("CI=", 0) != 0) {
                environment.emplace_back(*entry);
            }
        }
        environment.insert(environment.end(), extra_env.begin(), extra_env.end());
        arguments = {IMPULSE_BINARY};
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
    ToolCommand(const ToolCommand&) = delete;
    ToolCommand& operator=(const ToolCommand&) = delete;
};

// Starts the built tool without a shell, its output going to the given files
// (or /dev/null). CI is taken out of the environment, so bless writes;
// `extra_env` adds to it ("CI=true").
inline pid_t start_tool(const std::vector<std::string>& args,
                        const std::vector<std::string>& extra_env = {},
                        const std::string& out_file = "/dev/null",
                        const std::string& err_file = "/dev/null") {
    ToolCommand command(args, extra_env);
    std::vector<char*>& argv = command.argv;
    std::vector<char*>& envp = command.envp;

    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 1, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0600);
    posix_spawn_file_actions_addopen(&files, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0600);
    pid_t pid = 0;
    const int spawned =
        posix_spawn(&pid, IMPULSE_BINARY, &files, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&files);
    REQUIRE(spawned == 0);
    return pid;
}

// As start_tool, under `limits`. fork and exec instead of posix_spawn, which
// cannot set resource limits; only async-signal-safe calls in the child.
inline pid_t start_tool_limited(const std::vector<std::string>& args, const ChildLimits& limits,
                                const std::string& out_file = "/dev/null",
                                const std::string& err_file = "/dev/null",
                                const std::vector<std::string>& extra_env = {}) {
    ToolCommand command(args, extra_env);
    std::vector<char*>& argv = command.argv;
    std::vector<char*>& envp = command.envp;
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
        ::execve(IMPULSE_BINARY, argv.data(), envp.data());
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

} // namespace impulse::test
