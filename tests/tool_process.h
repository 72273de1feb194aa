// Running the built `impulse` as a child process, without a shell, for the
// tests that check what the tool does as a program (exit codes, its output
// files, being killed half-way).
#pragma once

#include <catch2/catch.hpp>
#include <cerrno>
#include <cstddef>
#include <fcntl.h>
#include <spawn.h>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace impulse::test {

// Whether RLIMIT_AS can cap the tool: AddressSanitizer reserves terabytes of
// shadow address space, so under it a cap would only break the start.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool address_space_can_be_capped = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool address_space_can_be_capped = false;
#else
inline constexpr bool address_space_can_be_capped = true;
#endif
#else
inline constexpr bool address_space_can_be_capped = true;
#endif

// fork and exec, so the limit is set in the child alone (posix_spawn cannot
// set one). Everything the child needs is made before the fork.
inline pid_t start_capped(const std::vector<char*>& argv, const std::vector<char*>& envp,
                          const std::string& out_file, const std::string& err_file,
                          std::size_t address_space_bytes) {
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const rlimit limit{address_space_bytes, address_space_bytes};
        const int out = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        const int err = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (out < 0 || err < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0 ||
            ::setrlimit(RLIMIT_AS, &limit) != 0) {
            ::_exit(127);
        }
        ::execve(IMPULSE_BINARY, argv.data(), envp.data());
        ::_exit(127);
    }
    return pid;
}

// Starts the built tool without a shell, its output going to the given files
// (or /dev/null). CI is taken out of the environment, so bless writes;
// `extra_env` adds to it ("CI=true"). `address_space_bytes` > 0 caps the
// tool's address space (RLIMIT_AS, as `ulimit -v` does), unless
// address_space_can_be_capped is false.
inline pid_t start_tool(const std::vector<std::string>& args,
                        const std::vector<std::string>& extra_env = {},
                        const std::string& out_file = "/dev/null",
                        const std::string& err_file = "/dev/null",
                        std::size_t address_space_bytes = 0) {
    std::vector<std::string> env;
    for (char** entry = environ; *entry != nullptr; ++entry) {
        if (std::string(*entry).rfind("CI=", 0) != 0) {
            env.emplace_back(*entry);
        }
    }
    env.insert(env.end(), extra_env.begin(), extra_env.end());
    std::vector<std::string> arguments = {IMPULSE_BINARY};
    arguments.insert(arguments.end(), args.begin(), args.end());
    std::vector<char*> argv, envp;
    for (std::string& a : arguments) {
        argv.push_back(a.data());
    }
    argv.push_back(nullptr);
    for (std::string& e : env) {
        envp.push_back(e.data());
    }
    envp.push_back(nullptr);

    if (address_space_bytes > 0 && address_space_can_be_capped) {
        return start_capped(argv, envp, out_file, err_file, address_space_bytes);
    }
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

inline int wait_for(pid_t pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return status;
}

} // namespace impulse::test
