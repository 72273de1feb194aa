// Running the built `impulse` as a child process, without a shell, for the
// tests that check what the tool does as a program (exit codes, its output
// files, being killed half-way).
#pragma once

#include <catch2/catch.hpp>
#include <cerrno>
#include <fcntl.h>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <vector>

extern char** environ;

namespace impulse::test {

// Starts the built tool without a shell, its output going to the given files
// (or /dev/null). CI is taken out of the environment, so bless writes;
// `extra_env` adds to it ("CI=true").
inline pid_t start_tool(const std::vector<std::string>& args,
                        const std::vector<std::string>& extra_env = {},
                        const std::string& out_file = "/dev/null",
                        const std::string& err_file = "/dev/null") {
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
