// An interrupted harness leaves nothing behind (harness/format/interruption.h,
// docs/engine-protocol.md, "Processes"): an engine runs in its own process
// group, so a Ctrl-C (SIGINT), a CI cancel (SIGTERM) or a closed terminal
// (SIGHUP) reaches the harness alone; before it ends as signalled, the
// harness kills the engine's group and removes the private folder of its
// scene. Found by an outside review: the engine kept running with parent 1
// and /tmp/impulse-engine-XXXXXX/SCENE.json stayed behind.
#include "atomic_file.h"
#include "interruption.h"
#include "support/files.h"
#include "support/tool.h"

#include <catch2/catch.hpp>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

// The tool with INT, TERM and HUP at their default actions, whatever the test
// runner's are (a background CI shell ignores SIGINT, and a child inherits it).
pid_t start_with_default_signals(const std::vector<std::string>& args) {
    ToolCommand command(args, {});
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&files, 2, "/dev/null", O_WRONLY, 0);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t defaults;
    sigemptyset(&defaults);
    for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
        sigaddset(&defaults, signal);
    }
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    sigset_t none;
    sigemptyset(&none);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, command.binary(), &files, &attributes,
                                    command.argv.data(), command.envp.data());
    posix_spawn_file_actions_destroy(&files);
    posix_spawnattr_destroy(&attributes);
    REQUIRE(spawned == 0);
    return pid;
}

// Gone, or a zombie its new parent has not reaped yet: either way not running.
bool running(pid_t pid) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string pid_field, name, state;
    if (!(stat >> pid_field >> name >> state)) {
        return false;
    }
    return state != "Z" && state != "X";
}

} // namespace

TEST_CASE("an interrupted run kills its engine's process group and removes the scene's folder",
          "[engine-protocol][interruption]") {
    for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
        const TempDir tmp;
        const fs::path marker = tmp.dir / "started";
        const fs::path engine = tmp.dir / "engine.sh";
        // Says where it is (its pid, once it is sleep's, and its scene), then waits.
        spit(engine, "#!/bin/sh\necho \"$$ $1\" > " + marker.string() + ".part && mv " +
                         marker.string() + ".part " + marker.string() + "\nexec sleep 300\n");
        fs::permissions(engine, fs::perms::owner_all);
        const fs::path out = tmp.dir / "out.json";
        const pid_t tool = start_with_default_signals(
            {"run", (fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes" / "stack.json").string(),
             "--engine-command", engine.string(), "--out", out.string()});
        int status = 0;
        bool exited_early = false;
        while (!fs::exists(marker)) {
            if (::waitpid(tool, &status, WNOHANG) == tool) {
                exited_early = true;
                break;
            }
            ::usleep(10000);
        }
        REQUIRE_FALSE(exited_early);
        pid_t engine_pid = 0;
        std::string scene_file;
        std::ifstream(marker) >> engine_pid >> scene_file;
        REQUIRE(engine_pid > 0);
        REQUIRE(fs::exists(scene_file));
        REQUIRE(running(engine_pid));

        REQUIRE(::kill(tool, signal) == 0);
        REQUIRE(::waitpid(tool, &status, 0) == tool);
        INFO("signal " << signal);
        CHECK(WIFSIGNALED(status)); // it ends as the signal ends it (a shell's 128 + N)
        CHECK(WTERMSIG(status) == signal);
        CHECK_FALSE(running(engine_pid));
        CHECK_FALSE(fs::exists(fs::path(scene_file).parent_path()));
        CHECK_FALSE(fs::exists(out));
        if (running(engine_pid)) {
            ::kill(engine_pid, SIGKILL); // not left for the next test
        }
    }
}

namespace {

// The status of a forked child that sets `signal` to its default action (or
// to a handler of its own that exits 7), registers `file` as a half-written
// temporary file, and is then sent the signal.
int child_interrupted_holding(const fs::path& file, int signal, bool own_handler) {
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        struct sigaction action {};
        action.sa_handler = own_handler ? [](int) { ::_exit(7); } : SIG_DFL;
        sigemptyset(&action.sa_mask);
        ::sigaction(signal, &action, nullptr);
        sigset_t none;
        sigemptyset(&none);
        ::sigprocmask(SIG_SETMASK, &none, nullptr);
        const impulse::harness::InterruptibleFile removed_if_interrupted(file.string());
        ::raise(signal);
        ::_exit(0); // not reached when the signal ends it
    }
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    return status;
}

} // namespace

TEST_CASE("an interrupt while a file is written removes the temporary file, and ends as signalled",
          "[interruption]") {
    // Found by an outside review: a SIGTERM while run --out or bless wrote
    // left NAME.tmp-XXXXXX (up to 69 MB) beside the target, in goldens/ too.
    for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
        INFO("signal " << signal);
        const TempDir tmp;
        const fs::path temp = tmp.dir / "run.json.tmp-abcdef";
        spit(temp, "half a trajecto");
        const int status = child_interrupted_holding(temp, signal, false);
        CHECK(WIFSIGNALED(status));
        CHECK(WTERMSIG(status) == signal);
        CHECK_FALSE(fs::exists(temp));
    }
}

TEST_CASE("a program with its own interrupt handler keeps it", "[interruption]") {
    // impulse::protocol links this library: its handler must not replace a user's.
    const TempDir tmp;
    const fs::path temp = tmp.dir / "kept.tmp";
    spit(temp, "theirs");
    const int status = child_interrupted_holding(temp, SIGTERM, true);
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 7);
    CHECK(fs::exists(temp));
}

TEST_CASE("a finished atomic write leaves no temporary file to remove", "[interruption]") {
    const TempDir tmp;
    const fs::path target = tmp.dir / "out.json";
    impulse::harness::write_file_atomically(target.string(), "whole");
    CHECK(slurp(target) == "whole");
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(tmp.dir)) {
        ++entries;
    }
    CHECK(entries == 1);
}

TEST_CASE("an interrupt during a set of writes is held until the last is written",
          "[interruption]") {
    // bless, regen and check write their outputs as one set (docs/reliability.md,
    // "A verb's outputs are one set"): found by an outside review, a SIGTERM
    // between two renames left 1 of 6 changed goldens written. The child here
    // is signalled before the first of three writes, inside the verbs' guard.
    for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
        INFO("signal " << signal);
        const TempDir tmp;
        const std::vector<fs::path> files{tmp.dir / "a.json", tmp.dir / "b.json",
                                          tmp.dir / "c.json"};
        for (const fs::path& file : files) {
            spit(file, "old");
        }
        const pid_t pid = ::fork();
        REQUIRE(pid >= 0);
        if (pid == 0) {
            struct sigaction action {};
            action.sa_handler = SIG_DFL;
            sigemptyset(&action.sa_mask);
            ::sigaction(signal, &action, nullptr);
            sigset_t none;
            sigemptyset(&none);
            ::sigprocmask(SIG_SETMASK, &none, nullptr);
            {
                const impulse::harness::HeldInterrupts whole_set;
                ::raise(signal);
                for (const fs::path& file : files) {
                    impulse::harness::write_file_atomically(file.string(), "new");
                }
            }
            ::_exit(0); // not reached: the held signal is delivered above
        }
        int status = 0;
        REQUIRE(::waitpid(pid, &status, 0) == pid);
        CHECK(WIFSIGNALED(status));
        CHECK(WTERMSIG(status) == signal);
        for (const fs::path& file : files) {
            CHECK(slurp(file) == "new");
        }
        std::size_t entries = 0; // no temporary file left beside them
        for ([[maybe_unused]] const auto& entry : fs::directory_iterator(tmp.dir)) {
            ++entries;
        }
        CHECK(entries == files.size());
    }
}
