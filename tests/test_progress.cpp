// Progress on a terminal (issue item 11), through the real tool with its
// standard error on a pseudo-terminal: the bar appears there with the
// simulated time (or items done), never when standard error is a file or
// --quiet is given, and standard output is the same with and without it.
// IMPULSE_PROGRESS_DELAY_MS=0 makes the bar appear without the usual second
// of waiting (and at least once, however quick the work).
#include "support/files.h"
#include "support/tool.h"

#include <catch2/catch.hpp>
#include <fcntl.h>
#include <filesystem>
#include <poll.h>
#include <pty.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

const std::vector<std::string> no_delay = {"IMPULSE_PROGRESS_DELAY_MS=0"};

// Runs the tool with standard error on a new pseudo-terminal (standard output
// to a file) and returns what reached the terminal as `err`.
Outcome run_on_terminal(const std::vector<std::string>& args,
                        const std::vector<std::string>& env = no_delay) {
    int master = -1;
    int slave = -1;
    REQUIRE(::openpty(&master, &slave, nullptr, nullptr, nullptr) == 0);
    const TempDir capture;
    const std::string out_file = (capture.dir / "stdout").string();
    const pid_t pid = spawn_tool(args, env, out_file, "", slave);
    ::close(slave); // the child holds it now: the master sees EOF (EIO) when it exits
    std::string seen;
    char buffer[4096];
    for (;;) {
        pollfd p{master, POLLIN, 0};
        if (::poll(&p, 1, -1) < 0) {
            continue;
        }
        const ssize_t n = ::read(master, buffer, sizeof buffer);
        if (n <= 0) {
            break;
        }
        seen.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(master);
    Outcome o = outcome_of(wait_for(pid), out_file, "/dev/null");
    o.err = seen;
    return o;
}

// A ball dropped onto the ground for 0.5 s, 50 steps.
std::string drop_scene(const std::string& name) {
    return R"({"schema":"impulse/scene@1","name":")" + name +
           R"(","dt":0.01,"duration":0.5,"restitution":0.5,"solver":{"integrator":"verlet"},"bodies":[{"name":"ground","static":true,"shape":{"box":[5,0.5]},"position":[0,-0.5]},{"name":"ball","shape":{"circle":0.5},"mass":1,"position":[0,1]}],"box2d":{"observables":[{"kind":"energy","atol":100}]}})";
}

} // namespace

TEST_CASE("run draws a bar with the simulated time on a terminal and erases it", "[progress]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "drop.json";
    spit(scene, drop_scene("drop"));
    const Outcome o = run_on_terminal({"run", scene.string()});
    INFO(o.err);
    CHECK(o.exit_code == 0);
    CHECK(o.err.find("run drop") != std::string::npos);
    // The run's duration as the scene gives it; the time reached is at most that.
    CHECK(o.err.find("/0.5 s") != std::string::npos);
    CHECK(o.err.find('[') != std::string::npos);
    // Erased at the end: the last thing written is "back to the start, clear the line".
    const std::string erase = "\r\x1b[K";
    REQUIRE(o.err.size() >= erase.size());
    CHECK(o.err.compare(o.err.size() - erase.size(), erase.size(), erase) == 0);

    SECTION("standard output is the same with the bar, without it, and with --quiet") {
        const Outcome to_file = run_tool({"run", scene.string()}, no_delay);
        CHECK(to_file.out == o.out);
        CHECK_FALSE(o.out.empty());
    }
}

TEST_CASE("no bar when standard error is a file", "[progress]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "drop.json";
    spit(scene, drop_scene("drop"));
    const Outcome o = run_tool({"run", scene.string()}, no_delay);
    CHECK(o.exit_code == 0);
    CHECK(o.err.empty());
}

TEST_CASE("no bar with --quiet, even on a terminal", "[progress]") {
    const TempDir tmp;
    const fs::path scene = tmp.dir / "drop.json";
    spit(scene, drop_scene("drop"));
    const Outcome quiet = run_on_terminal({"run", scene.string(), "--quiet"});
    CHECK(quiet.exit_code == 0);
    CHECK(quiet.err.empty());
    const Outcome loud = run_on_terminal({"run", scene.string()});
    CHECK(quiet.out == loud.out);
}

TEST_CASE("no bar when the work ends before the delay", "[progress]") {
    // The default delay is about a second; this run takes milliseconds.
    const TempDir tmp;
    const fs::path scene = tmp.dir / "drop.json";
    spit(scene, drop_scene("drop"));
    const Outcome o = run_on_terminal({"run", scene.string()}, {"IMPULSE_PROGRESS_DELAY_MS=60000"});
    CHECK(o.exit_code == 0);
    CHECK(o.err.empty());
}

TEST_CASE("every long verb counts its items on a terminal, and --quiet silences it", "[progress]") {
    const TempDir root;
    spit(root.dir / "harness" / "scenes" / "drop.json", drop_scene("drop"));
    fs::create_directories(root.dir / "goldens");
    const std::string r = root.dir.string();
    const std::string scene = (root.dir / "harness" / "scenes" / "drop.json").string();
    // Blessed once first, so bless says "unchanged" with the bar and without.
    REQUIRE(run_tool({"bless", "--root", r}).exit_code == 0);
    struct Verb {
        std::vector<std::string> args;
        std::string shows;
    };
    const std::vector<Verb> verbs = {
        {{"bless", "--root", r}, "bless 1/1 scenes drop"},
        {{"check", "--root", r}, "check 1/1 scenes drop"},
        {{"box2d", "--root", r, "drop"}, "box2d 1/1 scenes drop"},
        {{"render", scene, "--out", (root.dir / "drop.svg").string()},
         "render drop t 0.5/0.5 s drawn 1/1 paths"},
        {{"render", (root.dir / "goldens" / "drop.json").string(), "--root", r, "--out",
          (root.dir / "drop.svg").string()},
         "render drawn 1/1 paths"},
        {{"sweep", scene, "--dt", "0.01", "--integrator", "verlet", "--toi", "secant",
          "--toi-tolerance", "1e-9", "--no-box2d", "--repeats", "1"},
         "sweep drop 1/1 points"},
        {{"stress", "--case", "size-50"}, "stress 1/1 cases size-50"},
    };
    for (const Verb& v : verbs) {
        const Outcome shown = run_on_terminal(v.args);
        INFO(v.args.front() << ": " << shown.err);
        CHECK(shown.exit_code == 0);
        CHECK(shown.err.find(v.shows) != std::string::npos);

        std::vector<std::string> quiet_args = v.args;
        quiet_args.push_back("--quiet");
        const Outcome quiet = run_on_terminal(quiet_args);
        CHECK(quiet.exit_code == 0);
        CHECK(quiet.err.find(v.shows) == std::string::npos);
        CHECK(quiet.err.find('\r') == std::string::npos);
        if (v.args.front() != "sweep" && v.args.front() != "stress" && v.args.front() != "check") {
            // sweep, stress and check (each scene's seconds) print measured
            // wall times, which differ between two runs
            CHECK(quiet.out == shown.out);
        }
    }
}
