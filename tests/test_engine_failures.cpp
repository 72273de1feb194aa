// Every way an engine behind the protocol can fail (docs/engine-protocol.md),
// as a user meets it: through the real binary, in a project whose impulse.json
// names the engine. check, bless and run each give one sentence naming the
// engine, the scene and the engine's own message, exit 2 (0 for a refusal,
// which is a skip), no stack trace, no golden written or destroyed, and the
// project's other scenes still checked.
#include "support/files.h"
#include "support/outcome.h"
#include "support/tool.h"
#include "support/tool_in_folder.h"

#include <catch2/catch.hpp>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

const std::string engines_dir = IMPULSE_TEST_ENGINES_DIR;
const std::string fake_engine = engines_dir + "/fake_engine.py";

// One dynamic ball far above a floor it never reaches: 10 steps of 0.01 s.
std::string fall_scene(const std::string& name) {
    return R"({"schema": "impulse/scene@1", "name": ")" + name + R"(", "dt": 0.01, "duration": 0.1,
  "bodies": [{"name": "ball", "shape": {"circle": 0.5}, "position": [0, 10], "velocity": [1, 0]},
             {"name": "floor", "static": true, "shape": {"box": [5, 1]}, "position": [0, -100]}]})";
}

// A word for sh, single-quoted (the test's paths hold no single quote).
std::string quoted(const std::string& word) {
    return "'" + word + "'";
}

std::string words(const std::vector<std::string>& command) {
    std::string line;
    for (const std::string& w : command) {
        line += (line.empty() ? "" : " ") + quoted(w);
    }
    return line;
}

// What a crash of the tool itself or of Python would leave on its output.
void require_no_stack_trace(const Outcome& o) {
    for (const char* trace :
         {"Traceback", "terminate called", "what():", "Aborted", "core dumped"}) {
        INFO(trace);
        CHECK_FALSE(has(o.out + o.err, trace));
    }
}

bool process_gone(const std::string& pid_text) {
    REQUIRE(!pid_text.empty());
    const pid_t pid = static_cast<pid_t>(std::stol(pid_text));
    return ::kill(pid, 0) == -1 && errno == ESRCH;
}

// A project with two scenes, `fall` and `victim`, run by one engine `fake`
// (engine.sh): it replays a correct trajectory of each scene (recorded by
// the built-in impulse engine) until the test makes `victim` fail. Both
// goldens are blessed from the correct engine first.
struct FakeProject {
    TempDir temp;
    fs::path dir = temp.dir / "project";
    std::string victim_file = "./scenes/victim.json"; // as the tool names it from `dir`

    explicit FakeProject(double time_limit = 30.0) {
        spit(dir / "impulse.json",
             R"({"schema": "impulse/project@1", "scenes": ["scenes"],
                 "engines": [{"name": "fake", "command": ["sh", "engine.sh"], "time_limit": )" +
                 std::to_string(time_limit) + "}]}");
        for (const char* name : {"fall", "victim"}) {
            const std::string scene = std::string("scenes/") + name + ".json";
            spit(dir / scene, fall_scene(name));
            spit(dir / "prepared" / (std::string(name) + ".json"), "");
            require_exit(run_tool_in(dir, {"run", scene, "--engine", "impulse", "--out",
                                           "prepared/" + std::string(name) + ".json"}),
                         0);
        }
        victim_replays(dir / "prepared" / "victim.json");
        require_exit(run_tool_in(dir, {"bless"}), 0);
        REQUIRE(fs::is_regular_file(golden("fall")));
        REQUIRE(fs::is_regular_file(golden("victim")));
    }

    fs::path golden(const std::string& name) const { return dir / "goldens" / (name + ".json"); }

    // The victim scene runs `command`, with the scene's path appended unless
    // it replays a file; the other scenes replay.
    void victim_runs(const std::vector<std::string>& command) const {
        victim_script(words(command) + " \"$scene\"");
    }
    void victim_replays(const fs::path& trajectory) const {
        victim_script(words({"cat", trajectory.string()}));
    }
    void victim_script(const std::string& line) const {
        spit(dir / "engine.sh", "# the harness appends the scene's path\n"
                                "for scene; do :; done\n"
                                "case \"$scene\" in\n"
                                "  */victim.json) exec " +
                                    line +
                                    " ;;\n"
                                    "  *) exec cat \"prepared/${scene##*/}\" ;;\n"
                                    "esac\n");
    }

    // A trajectory of the victim scene as a correct engine writes it, edited.
    fs::path edited_victim(const std::function<void(nlohmann::json&)>& edit) const {
        nlohmann::json t = nlohmann::json::parse(slurp(dir / "prepared" / "victim.json"));
        edit(t);
        const fs::path file = temp.dir / "edited.json";
        spit(file, t.dump());
        return file;
    }
};

// check, bless and run with the victim failing: `sentence` is the message
// naming engine, scene and what went wrong (a sentence the tool may go on
// after, as the JSON reader's position in garbage).
void require_failure_everywhere(const FakeProject& p, const std::string& sentence,
                                const std::vector<std::string>& env = {}) {
    const std::string fall_golden = slurp(p.golden("fall"));
    const std::string victim_golden = slurp(p.golden("victim"));

    const Outcome checked =
        run_tool_in(p.dir, {"check", "--junit", "junit.xml", "--json", "check.json"}, env);
    require_exit(checked, 2);
    require_no_stack_trace(checked);
    INFO(checked.out);
    CHECK(has(checked.out, "ERROR  victim  " + sentence));
    CHECK(has(checked.out, "  ok     fall "));
    CHECK(has(checked.out, "2 scenes: 1 passed, 0 failed, 1 error"));
    // A CI report says whose the error is: the engine's, not the scene's.
    CHECK(has(slurp(p.dir / "junit.xml"), "type=\"engine error\""));
    CHECK_FALSE(has(slurp(p.dir / "junit.xml"), "input error"));
    const nlohmann::json report = nlohmann::json::parse(slurp(p.dir / "check.json"));
    for (const nlohmann::json& scene : report["scenes"]) {
        CHECK(scene["failure"] == (scene["name"] == "victim" ? nlohmann::json("engine error")
                                                             : nlohmann::json(nullptr)));
    }

    // bless neither overwrites the victim's golden nor writes a missing one.
    const Outcome blessed = run_tool_in(p.dir, {"bless"}, env);
    require_exit(blessed, 2);
    require_no_stack_trace(blessed);
    CHECK(has(blessed.err, sentence));
    CHECK(slurp(p.golden("victim")) == victim_golden);
    CHECK(slurp(p.golden("fall")) == fall_golden);
    fs::remove(p.golden("victim"));
    require_exit(run_tool_in(p.dir, {"bless"}, env), 2);
    CHECK_FALSE(fs::exists(p.golden("victim")));
    CHECK(slurp(p.golden("fall")) == fall_golden);

    // run writes no output file, and says the same sentence.
    const Outcome ran =
        run_tool_in(p.dir, {"run", "scenes/victim.json", "--out", "victim-run.json"}, env);
    require_exit(ran, 2);
    require_no_stack_trace(ran);
    CHECK(has(ran.err, sentence.substr(sentence.find(": ") + 2)));
    CHECK(has(ran.err, "engine 'fake'"));
    CHECK(has(ran.err, "scenes/victim.json"));
    CHECK_FALSE(fs::exists(p.dir / "victim-run.json"));
}

} // namespace

TEST_CASE("An engine that crashes by a signal is an error naming the signal and its message",
          "[engine-failures]") {
    FakeProject p;
    p.victim_runs({"python3", fake_engine, "crash"});
    require_failure_everywhere(p, "engine 'fake' failed on " + p.victim_file + ": signal 11 (" +
                                      ::strsignal(SIGSEGV) + "): about to crash");
}

TEST_CASE("An engine that exits 1 is an error with the last line of its standard error",
          "[engine-failures]") {
    FakeProject p;
    p.victim_runs({"python3", fake_engine, "fail", "the narrow phase lost a contact"});
    require_failure_everywhere(p, "engine 'fake' failed on " + p.victim_file +
                                      ": exit status 1: the narrow phase lost a contact");
}

TEST_CASE("An engine that hangs is killed at the project's time limit with its process group",
          "[engine-failures]") {
    FakeProject p(1.0);
    const fs::path pid_file = p.temp.dir / "grandchild.pid";
    p.victim_runs({"sh", engines_dir + "/hang.sh", pid_file.string()});
    const std::string sentence = "engine 'fake' failed on " + p.victim_file +
                                 ": did not finish within 1 s; its process group was killed "
                                 "(raise its time_limit at impulse.json: engines[0]): "
                                 "(nothing on standard error)";
    const Outcome checked = run_tool_in(p.dir, {"check"});
    require_exit(checked, 2);
    require_no_stack_trace(checked);
    CHECK(has(checked.out, "ERROR  victim  " + sentence));
    CHECK(has(checked.out, "  ok     fall "));
    // The helper hang.sh started (a grandchild of the tool) died with the group.
    CHECK(process_gone(slurp(pid_file)));

    const std::string golden = slurp(p.golden("victim"));
    const Outcome blessed = run_tool_in(p.dir, {"bless"});
    require_exit(blessed, 2);
    CHECK(has(blessed.err, sentence));
    CHECK(slurp(p.golden("victim")) == golden);
    CHECK(process_gone(slurp(pid_file)));
}

TEST_CASE("An engine whose output is not a trajectory is an error naming the JSON path",
          "[engine-failures]") {
    FakeProject p;
    const std::string output = "engine 'fake' on " + p.victim_file + ": output";
    SECTION("garbage") {
        p.victim_runs({"python3", fake_engine, "garbage"});
        require_failure_everywhere(p, output + ": begins with \"Segmentation fault? no: this is "
                                               "not JSON\", not with a trajectory's \"{\"");
    }
    SECTION("a wrong column") {
        const fs::path file =
            p.edited_victim([](nlohmann::json& t) { t["columns"][4] = "ball.vz"; });
        p.victim_replays(file);
        require_failure_everywhere(p, output + " columns[4]: must be \"ball.vx\", got \"ball.vz\"");
    }
    SECTION("a NaN") {
        p.victim_runs({"python3", fake_engine, "nan"});
        require_failure_everywhere(p, output + " frames[3][2]: NaN is not a finite number");
    }
    SECTION("a frame too few") {
        const fs::path file = p.edited_victim([](nlohmann::json& t) { t["frames"].erase(10); });
        p.victim_replays(file);
        // The scene: duration 0.1 s in steps of 0.01 s, and the frame at t = 0.
        require_failure_everywhere(p, output + " frames: has 10 frames; the scene's 10 steps "
                                               "(duration 0.1 s, dt 0.01 s) make 11");
    }
}

TEST_CASE("An engine that writes more than the trajectory limit is killed and reported",
          "[engine-failures]") {
    FakeProject p;
    // 2 MiB of spaces, then it waits to be killed: 1 MiB is the limit.
    p.victim_runs({"python3", fake_engine, "flood", "2"});
    require_failure_everywhere(
        p, "engine 'fake' failed on " + p.victim_file + ": wrote more than 1 MiB",
        {"IMPULSE_MAX_TRAJECTORY_MIB=1"});
}

TEST_CASE("An engine that refuses a scene it was blessed on fails the gate, naming the golden",
          "[engine-failures]") {
    // Found by an outside review: an engine that refused every scene passed
    // check (each a SKIPPED row, exit 0) although every scene had a golden.
    FakeProject p;
    p.victim_runs({"python3", fake_engine, "refuse", "balls are not modelled"});
    const Outcome checked = run_tool_in(p.dir, {"check", "--junit", "junit.xml"});
    require_exit(checked, 1);
    require_no_stack_trace(checked);
    CHECK(has(checked.out, "unsupported by fake: balls are not modelled, but its golden "));
    CHECK(has(checked.out, "delete the golden if fake no longer models this scene"));
    CHECK(has(checked.out, "2 scenes: 1 passed, 1 failed, 0 errors"));
    CHECK(has(slurp(p.dir / "junit.xml"), "<failure"));
    CHECK(fs::exists(p.golden("victim")));

    // Blessing cannot make that gate pass, so it refuses, writes nothing and
    // says what would (found by a helper: bless said "1 skipped", exit 0,
    // and check stayed red).
    const std::string golden = slurp(p.golden("victim"));
    const Outcome blessed = run_tool_in(p.dir, {"bless"});
    require_exit(blessed, 1);
    CHECK(has(blessed.out, "REFUSED    victim: unsupported by fake: balls are not modelled, but "
                           "its golden "));
    CHECK(has(blessed.out, "delete the golden if fake no longer models this scene"));
    CHECK(slurp(p.golden("victim")) == golden);
    fs::remove(p.golden("victim"));
    require_exit(run_tool_in(p.dir, {"bless"}), 0);
    require_exit(run_tool_in(p.dir, {"check"}), 0);
}

TEST_CASE("An engine that refuses a scene with no golden is a SKIPPED row, exit 0, a JUnit skip "
          "and no golden",
          "[engine-failures]") {
    FakeProject p;
    p.victim_runs({"python3", fake_engine, "refuse", "balls are not modelled"});
    fs::remove(p.golden("victim"));
    const std::string skip = "unsupported by fake: balls are not modelled";
    const Outcome checked = run_tool_in(p.dir, {"check", "--junit", "junit.xml"});
    require_exit(checked, 0);
    require_no_stack_trace(checked);
    // The names line up: with a SKIPPED row the status column is one wider.
    CHECK(has(checked.out, "  SKIPPED victim  " + skip));
    CHECK(has(checked.out, "  ok      fall    "));
    CHECK(has(checked.out, "2 scenes: 1 passed, 0 failed, 0 errors, 1 skipped"));
    const std::string xml = slurp(p.dir / "junit.xml");
    CHECK(has(xml, "<skipped message=\"" + skip + "\"/>"));
    CHECK(has(xml, "skipped=\"1\""));
    CHECK_FALSE(has(xml, "<failure"));
    CHECK_FALSE(has(xml, "<error"));

    const Outcome blessed = run_tool_in(p.dir, {"bless"});
    require_exit(blessed, 0);
    CHECK(has(blessed.out, skip));
    CHECK_FALSE(fs::exists(p.golden("victim")));
    CHECK(fs::exists(p.golden("fall")));
}

TEST_CASE("An engine whose program does not exist is one sentence naming the project file's "
          "command, before any scene runs",
          "[engine-failures]") {
    // Not one error row per scene (the same sentence each time), and no
    // golden written for the project's other engine either: the project
    // file is wrong, so nothing runs until it is fixed.
    TempDir temp;
    const fs::path dir = temp.dir / "project";
    spit(dir / "impulse.json", R"({"schema": "impulse/project@1", "scenes": ["scenes"],
        "engines": [{"name": "impulse", "builtin": "impulse"},
                    {"name": "ghost", "command": ["./no-such-engine"]}]})");
    spit(dir / "scenes" / "fall.json", fall_scene("fall"));
    spit(dir / "scenes" / "drop.json", fall_scene("drop"));
    require_exit(run_tool_in(dir, {"bless", "--engine", "impulse"}), 0);
    const std::string sentence =
        "impulse.json: engines[1].command[0]: cannot start './no-such-engine': No such file or "
        "directory (engine 'ghost'; no scene was run)\n";

    const Outcome checked = run_tool_in(dir, {"check"});
    require_exit(checked, 2);
    require_no_stack_trace(checked);
    CHECK(checked.err == sentence);
    CHECK(checked.out.empty());
    // The engine that is there still checks on its own.
    require_exit(run_tool_in(dir, {"check", "--engine", "impulse"}), 0);

    const fs::path golden = dir / "goldens" / "impulse" / "fall.json";
    const auto before = fs::last_write_time(golden);
    const Outcome blessed = run_tool_in(dir, {"bless"});
    require_exit(blessed, 2);
    CHECK(blessed.err == sentence);
    CHECK_FALSE(fs::exists(dir / "goldens" / "ghost"));
    CHECK(fs::last_write_time(golden) == before);

    const Outcome ran = run_tool_in(dir, {"run", "scenes/fall.json", "--engine", "ghost"});
    require_exit(ran, 2);
    CHECK(ran.err == sentence);
    CHECK(ran.out.empty());

    // A folder where the program should be is not a program either.
    fs::create_directories(dir / "no-such-engine");
    CHECK(has(run_tool_in(dir, {"check"}).err,
              "cannot start './no-such-engine': it is a folder, not a program"));
}
