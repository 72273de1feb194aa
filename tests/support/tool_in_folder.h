// Running the built `impulse` from a given folder, as a user does when the
// tool finds its project from the current folder (impulse.json upwards).
#pragma once

#include "tool.h"

#include <spawn.h>

namespace impulse::test {

// As run_tool, with `folder` as the tool's current folder (the test process
// never changes its own).
inline Outcome run_tool_in(const std::filesystem::path& folder,
                           const std::vector<std::string>& args,
                           const std::vector<std::string>& extra_env = {}) {
    const TempDir capture;
    const std::filesystem::path out = capture.dir / "stdout", err = capture.dir / "stderr";
    ToolCommand command(args, extra_env);
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    // glibc >= 2.29 (Debian 12 has 2.36): the child changes folder before exec.
    posix_spawn_file_actions_addchdir_np(&files, folder.c_str());
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, command.binary(), &files, nullptr, command.argv.data(),
                                    command.envp.data());
    posix_spawn_file_actions_destroy(&files);
    REQUIRE(spawned == 0);
    return outcome_of(wait_for(pid), out, err);
}

} // namespace impulse::test
