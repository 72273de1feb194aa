// Running a program other than the tool (an engine script under its
// interpreter, cmake, an installed copy of the tool) as the harness runs an
// engine: for the tests of engines that live outside this one
// (test_python_seed.cpp, test_reference_engines.cpp) and of the installed
// package (test_install.cpp).
#pragma once

#include "files.h"
#include "tool.h"

#include <catch2/catch.hpp>
#include <fcntl.h>
#include <filesystem>
#include <spawn.h>
#include <string>
#include <vector>

namespace impulse::test {

// Runs another program to the end, as the harness runs an engine: without a
// shell, stdin from /dev/null, the test's environment, stdout and stderr to
// files. `words` are its argv; the first is the program, looked up in PATH
// when it has no slash.
inline Outcome run_program(std::vector<std::string> words) {
    const TempDir capture;
    const std::filesystem::path out = capture.dir / "stdout", err = capture.dir / "stderr";
    std::vector<char*> argv;
    for (std::string& word : words) {
        argv.push_back(word.data());
    }
    argv.push_back(nullptr);
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&files, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, argv[0], &files, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&files);
    REQUIRE(spawned == 0);
    return outcome_of(wait_for(pid), out, err);
}

} // namespace impulse::test
