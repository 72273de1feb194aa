// Output paths that never destroy, inputs that are regular files
// (docs/reliability.md, "Output paths and input files"), through the real tool:
//
// - every output option refuses a FIFO, a symbolic link, a directory and a
//   character device at its path, and leaves it exactly as it was;
// - no verb but bless writes into the goldens folder, CI mode or not;
// - "-" is standard output;
// - a FIFO given as a scene, golden or trajectory is refused without being
//   opened, so nothing waits on it;
// - a file name that is not UTF-8 is escaped in the message.
//
// The FIFO cases hold a writer open on the FIFO with one byte in it while the
// tool runs, and close it once the tool has taken the byte: a tool that opens
// the FIFO (the defect) then reads a one-byte file and says something else,
// instead of hanging the test. No clock is involved.
#include "support/files.h"
#include "support/path_state.h"
#include "support/roots.h"
#include "support/tool.h"
#include "support/tool_in_folder.h"
#include "support/utf8.h"

#include <catch2/catch.hpp>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

const fs::path source_dir = IMPULSE_SOURCE_DIR;

// The tool run with a writer held on `fifo` and one byte waiting in it (see
// the top of the file). O_RDWR on a FIFO never blocks on Linux.
Outcome run_tool_feeding(const fs::path& fifo, const std::vector<std::string>& args,
                         const std::vector<std::string>& extra_env = {}) {
    const int fd = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
    REQUIRE(fd >= 0);
    REQUIRE(::write(fd, "x", 1) == 1);
    const TempDir capture;
    const fs::path out_file = capture.dir / "stdout", err_file = capture.dir / "stderr";
    const pid_t pid = start_tool(args, extra_env, out_file.string(), err_file.string());
    int status = 0;
    bool ended = false;
    for (;;) {
        if (::waitpid(pid, &status, WNOHANG) == pid) {
            ended = true;
            break;
        }
        int queued = 0;
        if (::ioctl(fd, FIONREAD, &queued) != 0 || queued == 0) {
            break; // the tool took the byte: give it end of file
        }
        ::usleep(1000);
    }
    ::close(fd);
    if (!ended) {
        status = wait_for(pid);
    }
    return outcome_of(status, out_file, err_file);
}

// Refused as bad input: exit 2, one line on stderr naming the path and the words.
void check_refused(const Outcome& o, const std::string& path, const std::string& words) {
    INFO("stdout: " << o.out << "\nstderr: " << o.err);
    CHECK(o.exited);
    CHECK(o.exit_code == 2);
    CHECK(o.err.rfind(path + ": ", 0) == 0);
    CHECK(o.err.find(words) != std::string::npos);
    CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
    CHECK(valid_utf8(o.err));
}

// The arguments of every verb's single-file output, writing to `target`.
struct FileOutput {
    std::string name;
    std::vector<std::string> args;
};

std::vector<FileOutput> file_outputs(const fs::path& root, const std::string& target) {
    const std::string scene = (root / "harness" / "scenes" / "drop-box.json").string();
    return {
        {"run --out", {"run", scene, "--out", target}},
        {"render --out", {"render", scene, "--out", target, "--root", root.string()}},
        {"check --junit", {"check", "drop-box", "--root", root.string(), "--junit", target}},
        // The smallest grid, should the path be taken.
        {"sweep --svg",
         {"sweep", scene, "--svg", target, "--dt", "0.01", "--integrator", "verlet", "--toi",
          "secant", "--toi-tolerance", "1e-9", "--no-box2d", "--repeats", "1", "--root",
          root.string()}},
    };
}

} // namespace

TEST_CASE("Every single-file output refuses a FIFO, a symbolic link and a directory, untouched",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const fs::path outside = dir.dir / "outside.txt";
    spit(outside, "a file outside, not to be touched\n");
    const std::vector<std::pair<std::string, std::string>> kinds = {
        {"fifo", "is a FIFO"},
        {"link", "is a symbolic link"},
        {"dangling-link", "is a symbolic link"},
        {"folder", "is a directory"}};
    for (const auto& [kind, words] : kinds) {
        const fs::path target = dir.dir / ("target-" + kind);
        if (kind == "fifo") {
            REQUIRE(::mkfifo(target.c_str(), 0600) == 0);
        } else if (kind == "link") {
            fs::create_symlink(outside, target);
        } else if (kind == "dangling-link") {
            fs::create_symlink(dir.dir / "nowhere", target);
        } else {
            fs::create_directories(target / "inside");
        }
        for (const FileOutput& output : file_outputs(root, target.string())) {
            INFO(output.name << " onto a " << kind);
            const std::string before = state_of(target);
            check_refused(run_tool(output.args), target.string(), words);
            CHECK(state_of(target) == before);
            CHECK(state_of(outside) == "file a file outside, not to be touched\n");
            CHECK(state_of(dir.dir / "nowhere") == "missing");
        }
    }
    // Nothing half-written beside them either: no temporary file is left.
    for (const fs::directory_entry& e : fs::directory_iterator(dir.dir)) {
        CHECK(e.path().filename().string().find(".tmp-") == std::string::npos);
    }
}

TEST_CASE("An output at /dev/null is refused and /dev/null stays a character device",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    struct stat info {};
    REQUIRE(::lstat("/dev/null", &info) == 0);
    REQUIRE(S_ISCHR(info.st_mode)); // never created here, only looked at
    const std::string before = state_of("/dev/null");
    for (const FileOutput& output : file_outputs(root, "/dev/null")) {
        INFO(output.name);
        check_refused(run_tool(output.args), "/dev/null", "is a character device");
        CHECK(state_of("/dev/null") == before);
    }
}

TEST_CASE("A path that is a regular file or missing is written whole", "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const fs::path fresh = dir.dir / "fresh.json", old = dir.dir / "old.json";
    spit(old, "old bytes");
    const std::string scene = (root / "harness" / "scenes" / "drop-box.json").string();
    const Outcome to_stdout = run_tool({"run", scene});
    REQUIRE(to_stdout.exit_code == 0);
    for (const fs::path& target : {fresh, old}) {
        const Outcome o = run_tool({"run", scene, "--out", target.string()});
        CHECK(o.exit_code == 0);
        CHECK(state_of(target) == "file " + to_stdout.out);
    }
}

TEST_CASE("An output whose folder is missing or is a file is refused before the run, and the "
          "other output keeps its bytes",
          "[unit][output-paths]") {
    // Found by an outside review: run --out keep.json --json nodir/r.json
    // replaced keep.json with the trajectory, then failed on --json.
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const std::string scene = (root / "harness" / "scenes" / "drop-box.json").string();
    const fs::path keep = dir.dir / "keep.json", a_file = dir.dir / "a-file";
    spit(keep, "an earlier run's bytes");
    spit(a_file, "not a folder");
    const std::string missing_folder = (dir.dir / "no-such-folder" / "r.json").string();
    const std::string under_a_file = (a_file / "r.json").string();
    for (const std::string& bad : {missing_folder, under_a_file}) {
        for (const bool bad_is_json : {true, false}) {
            const std::vector<std::string> args =
                bad_is_json
                    ? std::vector<std::string>{"run", scene, "--out", keep.string(), "--json", bad}
                    : std::vector<std::string>{"run", scene, "--json", keep.string(), "--out", bad};
            const Outcome o = run_tool(args);
            INFO(o.err);
            CHECK(o.exit_code == 2);
            CHECK(o.err.rfind(bad + (bad_is_json ? ": --json: " : ": --out: "), 0) == 0);
            CHECK(o.err.find("cannot be written") != std::string::npos);
            CHECK(o.err.find('\n') == o.err.size() - 1);
            CHECK(state_of(keep) == "file an earlier run's bytes");
            CHECK_FALSE(fs::exists(bad));
        }
    }
    CHECK(state_of(a_file) == "file not a folder");
}

TEST_CASE("The path - writes an output to standard output", "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const std::string scene = (root / "harness" / "scenes" / "drop-box.json").string();
    const Outcome plain = run_tool({"run", scene});
    const Outcome dash = run_tool({"run", scene, "--out", "-"});
    CHECK(dash.exit_code == 0);
    CHECK(dash.out == plain.out);
    CHECK(dash.out.rfind("{\n  \"schema\": \"impulse/trajectory@1\"", 0) == 0);
    CHECK_FALSE(fs::exists("-"));

    const Outcome svg = run_tool({"render", scene, "--out", "-", "--root", root.string()});
    CHECK(svg.exit_code == 0);
    CHECK(svg.out.find("<svg") != std::string::npos);

    // Standard output is the XML alone; the table moves to standard error.
    const Outcome junit = run_tool({"check", "drop-box", "--root", root.string(), "--junit", "-"});
    INFO("stdout: " << junit.out << "\nstderr: " << junit.err);
    CHECK(junit.exit_code == 0);
    CHECK(junit.out.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites", 0) == 0);
    CHECK(junit.out.find("check: ") == std::string::npos);
    CHECK(junit.err.find("1 scene: 1 passed, 0 failed, 0 errors") != std::string::npos);

    // The smallest grid; its table moves to standard error.
    const std::vector<std::string> sweep = {"sweep", scene,          "--dt",
                                            "0.01",  "--integrator", "verlet",
                                            "--toi", "secant",       "--toi-tolerance",
                                            "1e-9",  "--no-box2d",   "--repeats",
                                            "1",     "--svg",        "-"};
    const Outcome plot = run_tool(sweep);
    CHECK(plot.exit_code == 0);
    CHECK(plot.out.find("<svg") != std::string::npos);
    CHECK(plot.out.find("grid points") == std::string::npos);
    CHECK(plot.err.find("1 point measured") != std::string::npos);
    std::vector<std::string> both = sweep;
    both.push_back("--json");
    CHECK(run_tool(both).exit_code == 2); // two outputs cannot share standard output

    // A folder is no stream.
    check_refused(run_tool({"check", "drop-box", "--root", root.string(), "--report", "-"}), "-",
                  "--report");
}

TEST_CASE("CI mode: check --junit and --report into goldens/ are refused, the golden intact",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const fs::path goldens = root / "goldens";
    const fs::path golden = goldens / "drop-box.json";
    const std::string golden_bytes = slurp(source_dir / "goldens" / "drop-box.json");
    fs::create_directory_symlink(goldens, dir.dir / "goldens-link");
    fs::create_directories(root / "elsewhere");
    const std::vector<std::string> ci = {"CI=true"};
    const std::vector<std::string> file_targets = {
        golden.string(), (goldens / "new.xml").string(),
        (root / "elsewhere" / ".." / "goldens" / "new.xml").string(),
        (dir.dir / "goldens-link" / "new.xml").string()};
    for (const std::string& target : file_targets) {
        INFO("--junit " << target);
        const Outcome o =
            run_tool({"check", "drop-box", "--root", root.string(), "--junit", target}, ci);
        check_refused(o, target, "is in the goldens folder");
        CHECK(o.out.empty()); // refused before any scene ran
    }
    for (const std::string& folder :
         {goldens.string(), (goldens / "report").string(), (dir.dir / "goldens-link").string()}) {
        INFO("--report " << folder);
        check_refused(
            run_tool({"check", "drop-box", "--root", root.string(), "--report", folder}, ci),
            folder, "is in the goldens folder");
    }
    // Every verb's file output, not only in CI mode.
    for (const FileOutput& output : file_outputs(root, (goldens / "new.out").string())) {
        INFO(output.name);
        check_refused(run_tool(output.args), (goldens / "new.out").string(),
                      "is in the goldens folder");
    }
    CHECK(state_of(golden) == "file " + golden_bytes);
    CHECK(state_of(goldens) == "folder drop-box.json");
}

TEST_CASE("A project's goldens are refused as an output from outside the project too",
          "[unit][output-paths]") {
    // Two user projects beside a third folder the tool runs in: one names its
    // goldens folder, one takes the default, and a broken project file still
    // protects the default. None of them is the verb's project.
    const TempDir dir;
    const fs::path named = dir.dir / "app", plain = dir.dir / "lib", broken = dir.dir / "old";
    const fs::path outside = dir.dir / "work";
    for (const fs::path& folder :
         {named / "expected", plain / "goldens", broken / "goldens", named / "results", outside}) {
        fs::create_directories(folder);
    }
    spit(named / "impulse.json", R"({"schema": "impulse/project@1", "goldens": "expected"})");
    spit(plain / "impulse.json", R"({"schema": "impulse/project@1"})");
    spit(broken / "impulse.json", R"({"schema": "impulse/project@1", "goldens": )");
    spit(named / "expected" / "drop.json", "golden bytes");
    const std::string scene = (source_dir / "harness" / "scenes" / "drop-box.json").string();
    const std::vector<std::string> targets = {
        "../app/expected/drop.json", "../app/expected/new.json",
        "../app/results/../expected/new.json", "../lib/goldens/new.json",
        "../old/goldens/sub/../new.json"};
    for (const std::string& target : targets) {
        INFO("run --out " << target);
        check_refused(run_tool_in(outside, {"run", scene, "--out", target}), target,
                      "is in the goldens folder");
    }
    CHECK(slurp(named / "expected" / "drop.json") == "golden bytes");
    CHECK(!fs::exists(named / "expected" / "new.json"));
    CHECK(!fs::exists(plain / "goldens" / "new.json"));
    CHECK(!fs::exists(broken / "goldens" / "new.json"));
    // A project's other folders take outputs: only its goldens are protected.
    const Outcome written =
        run_tool_in(outside, {"run", scene, "--out", "../app/results/drop.json", "--quiet"});
    INFO(written.err);
    CHECK(written.exit_code == 0);
    CHECK(fs::is_regular_file(named / "results" / "drop.json"));
}

TEST_CASE("check --report refuses a FIFO where a report file goes, and writes none of them",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const fs::path report = dir.dir / "report";
    fs::create_directories(report);
    REQUIRE(::mkfifo((report / "index.html").c_str(), 0600) == 0);
    const Outcome o =
        run_tool({"check", "drop-box", "--root", root.string(), "--report", report.string()});
    INFO("stdout: " << o.out << "\nstderr: " << o.err);
    CHECK(o.exit_code == 2);
    CHECK(o.err.find((report / "index.html").string() + ": --report: is a FIFO") == 0);
    CHECK(state_of(report) == "folder index.html");
    CHECK(state_of(report / "index.html") == "fifo");

    const fs::path fifo_folder = dir.dir / "fifo-folder";
    REQUIRE(::mkfifo(fifo_folder.c_str(), 0600) == 0);
    check_refused(
        run_tool({"check", "drop-box", "--root", root.string(), "--report", fifo_folder.string()}),
        fifo_folder.string(), "is not a folder");
    CHECK(state_of(fifo_folder) == "fifo");
}

#ifdef IMPULSE_WITH_BOX2D
TEST_CASE("box2d --out refuses a link where a trajectory goes, and writes neither run",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const fs::path out = dir.dir / "runs";
    const fs::path outside = dir.dir / "outside.json";
    spit(outside, "outside\n");
    fs::create_directories(out);
    fs::create_symlink(outside, out / "drop-box.impulse.json");
    const Outcome o =
        run_tool({"box2d", "drop-box", "--root", root.string(), "--out", out.string()});
    INFO("stdout: " << o.out << "\nstderr: " << o.err);
    CHECK(o.exit_code == 2);
    CHECK(o.err.find("cannot be written (it is a symbolic link") != std::string::npos);
    CHECK(state_of(out) == "folder drop-box.impulse.json");
    CHECK(state_of(outside) == "file outside\n");
    check_refused(run_tool({"box2d", "drop-box", "--root", root.string(), "--out",
                            (root / "goldens").string()}),
                  (root / "goldens").string(), "is in the goldens folder");
}
#endif

TEST_CASE("A FIFO golden ends check and bless at once with an ERROR naming it",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const fs::path golden = root / "goldens" / "drop-box.json";
    fs::remove(golden);
    REQUIRE(::mkfifo(golden.c_str(), 0600) == 0);
    const std::string words = golden.string() + ": cannot be read (it is a FIFO";

    const Outcome check = run_tool_feeding(golden, {"check", "--root", root.string()});
    INFO("stdout: " << check.out << "\nstderr: " << check.err);
    CHECK(check.exit_code == 2);
    CHECK(check.out.find("  ERROR  drop-box  " + words) != std::string::npos);
    CHECK(state_of(golden) == "fifo");

    const Outcome bless = run_tool_feeding(golden, {"bless", "--root", root.string()});
    INFO("bless stdout: " << bless.out << "\nstderr: " << bless.err);
    CHECK(bless.exit_code == 2);
    CHECK(bless.err.find(golden.string() + ": cannot be written (it is a FIFO") == 0);
    CHECK(state_of(golden) == "fifo");
}

TEST_CASE("A FIFO scene or trajectory is refused by run, bless, render and diff",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const fs::path fifo = root / "harness" / "scenes" / "piped.json";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    const std::string golden = (root / "goldens" / "drop-box.json").string();
    const std::vector<std::vector<std::string>> commands = {
        {"run", fifo.string()},
        {"bless", "piped", "--root", root.string()},
        {"render", fifo.string()},
        {"diff", fifo.string(), golden},
        {"diff", golden, fifo.string()}};
    for (const std::vector<std::string>& args : commands) {
        INFO(args.front() << " " << args.at(1));
        check_refused(run_tool_feeding(fifo, args), fifo.string(),
                      "cannot be read (it is a FIFO; impulse reads only regular files)");
        CHECK(state_of(fifo) == "fifo");
    }
    // In the canonical list it is an ERROR row, not a scene left out.
    const Outcome check = run_tool_feeding(fifo, {"check", "--root", root.string()});
    CHECK(check.exit_code == 2);
    CHECK(check.out.find("  ERROR  piped     " + fifo.string() +
                         ": cannot be read (it is a FIFO") != std::string::npos);
    CHECK(check.out.find("  ok     drop-box") != std::string::npos);
    // A symbolic link to a regular scene is still a scene.
    const fs::path link = dir.dir / "linked.json";
    fs::create_symlink(root / "harness" / "scenes" / "drop-box.json", link);
    CHECK(run_tool({"run", link.string()}).exit_code == 0);
}

TEST_CASE("A file name that is not UTF-8 is escaped in the message", "[unit][output-paths]") {
    const TempDir dir;
    const std::string name = "bad\xff\x01name\xc3\xa9.json"; // 0xff, a control byte, then é
    const fs::path scene = dir.dir / name;
    spit(scene, "{");
    const Outcome o = run_tool({"run", scene.string()});
    const std::string shown = (dir.dir / "bad\\xff\\x01name\xc3\xa9.json").string();
    check_refused(o, shown, "not valid JSON");

    // The same name in check's table.
    const Outcome check = run_tool({"check", scene.string(), "--root", dir.dir.string()});
    INFO("stdout: " << check.out);
    CHECK(check.exit_code == 2);
    CHECK(valid_utf8(check.out));
    CHECK(check.out.find("bad\\xff\\x01name\xc3\xa9") != std::string::npos);
}

TEST_CASE("No output replaces a scene, a project file or the verb's own input",
          "[unit][output-paths]") {
    // Found by an outside review: run a.json --out a.json, run --json, render
    // --out and check --junit over the project's scene all replaced it, exit 0.
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const fs::path scene = root / "harness" / "scenes" / "drop-box.json";
    const std::string before = slurp(scene);
    const std::string s = scene.string();
    for (const FileOutput& output : file_outputs(root, s)) {
        INFO(output.name);
        check_refused(run_tool(output.args), s, "is a scene file (schema impulse/scene@1)");
        CHECK(slurp(scene) == before);
    }
    check_refused(run_tool({"run", s, "--json", s, "--out", (dir.dir / "t.json").string()}), s,
                  "is a scene file");
    CHECK_FALSE(fs::exists(dir.dir / "t.json"));
    CHECK(slurp(scene) == before);

    // A project file, whatever its name.
    const fs::path project = dir.dir / "project.json";
    spit(project, R"({"schema": "impulse/project@1", "scenes": ["s"], "goldens": "g"})");
    check_refused(run_tool({"run", s, "--out", project.string()}), project.string(),
                  "is a project file");

    // The trajectory render draws, which is neither.
    const fs::path trajectory = dir.dir / "run.json";
    REQUIRE(run_tool({"run", s, "--out", trajectory.string()}).exit_code == 0);
    const std::string drawn = slurp(trajectory);
    check_refused(
        run_tool({"render", trajectory.string(), "--scene", s, "--out", trajectory.string()}),
        trajectory.string(), "which this command reads");
    CHECK(slurp(trajectory) == drawn);
    // Replacing an earlier trajectory (not an input) is what --out is for.
    CHECK(run_tool({"run", s, "--out", trajectory.string()}).exit_code == 0);
}

TEST_CASE("An empty or over-long output path is refused before the work, the other output kept",
          "[unit][output-paths]") {
    // Found by an outside review: --out '' ran the whole scene and then
    // failed naming "<input>"; --json '' replaced --out's file first.
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const std::string scene = (root / "harness" / "scenes" / "drop-box.json").string();
    const fs::path keep = dir.dir / "keep.json";
    spit(keep, "an earlier run's bytes");
    const std::string long_name = (dir.dir / std::string(300, 'x')).string();
    for (const std::string& option : {std::string("--out"), std::string("--json")}) {
        const std::string other = option == "--out" ? "--json" : "--out";
        const Outcome empty = run_tool({"run", scene, other, keep.string(), option, ""});
        check_refused(empty, option, "is empty; give a file name");
        const Outcome too_long = run_tool({"run", scene, other, keep.string(), option, long_name});
        check_refused(too_long, long_name, "has a file name of 300 bytes");
        CHECK(state_of(keep) == "file an earlier run's bytes");
    }
    for (const FileOutput& output : file_outputs(root, "")) {
        INFO(output.name);
        check_refused(run_tool(output.args), output.name.substr(output.name.find(' ') + 1),
                      "is empty");
    }
    check_refused(run_tool({"check", "--root", root.string(), "--report", ""}), "--report",
                  "is empty; give a folder");
    check_refused(run_tool({"box2d", scene, "--out", ""}), "--out", "is empty; give a folder");
}

// Two outputs of one verb on one file: the second would replace the first,
// however the path is spelt (an outside review lost a trajectory to
// `--out a.json --json ./a.json`).
TEST_CASE("Two outputs naming one file are refused before the run, however spelt",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const std::string scene = (root / "harness" / "scenes" / "drop-box.json").string();
    fs::create_directories(dir.dir / "sub");
    const fs::path file = dir.dir / "a.json";
    spit(file, "old bytes");
    for (const std::string& other : {std::string("./a.json"), std::string(".//a.json"),
                                     std::string("sub/../a.json"), file.string()}) {
        INFO(other);
        const Outcome run =
            run_tool_in(dir.dir, {"run", scene, "--out", "a.json", "--json", other});
        CHECK(run.exit_code == 2);
        CHECK(run.err.find("--json and --out name the same file") != std::string::npos);
        const Outcome check = run_tool_in(
            dir.dir, {"check", "--root", root.string(), "--json", "a.json", "--junit", other});
        CHECK(check.exit_code == 2);
        CHECK(check.err.find("--json and --junit name the same file") != std::string::npos);
        CHECK(state_of(file) == "file old bytes");
    }
}

TEST_CASE("A bad report file is refused before the run: no JUnit or JSON is written",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const fs::path report = dir.dir / "report";
    fs::create_directories(report / "index.html");
    const fs::path junit = dir.dir / "j.xml", json = dir.dir / "j.json";
    const Outcome o = run_tool({"check", "--root", root.string(), "--report", report.string(),
                                "--junit", junit.string(), "--json", json.string()});
    INFO("stdout: " << o.out << "\nstderr: " << o.err);
    CHECK(o.exit_code == 2);
    CHECK(o.err.find((report / "index.html").string() + ": --report: is a directory") == 0);
    CHECK(o.out.find("passed") == std::string::npos); // no scene ran
    CHECK(state_of(junit) == "missing");
    CHECK(state_of(json) == "missing");
}

TEST_CASE("A --json or --junit naming a file of the --report folder is refused, the file kept",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const fs::path report = dir.dir / "report";
    fs::create_directories(report);
    spit(report / "summary.md", "old summary");
    for (const std::string& option : {std::string("--json"), std::string("--junit")}) {
        INFO(option);
        const Outcome o = run_tool_in(dir.dir, {"check", "--root", root.string(), "--report",
                                                "report", option, "./report/summary.md"});
        CHECK(o.exit_code == 2);
        CHECK(o.err.find(option + " names ./report/summary.md, a file of the --report folder") !=
              std::string::npos);
        CHECK(state_of(report) == "folder summary.md");
        CHECK(state_of(report / "summary.md") == "file old summary");
    }
}

TEST_CASE("A failed scene's picture path that is a folder stops check before any output",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    // An edited description makes the golden stale: a failed scene, drawn.
    const fs::path scene = root / "harness" / "scenes" / "drop-box.json";
    std::string text = slurp(scene);
    const std::string key = "\"description\": \"";
    text.replace(text.find(key), key.size(), key + "edited ");
    spit(scene, text);
    const fs::path report = dir.dir / "report";
    fs::create_directories(report / "drop-box.svg");
    const fs::path json = dir.dir / "j.json";
    const Outcome o = run_tool(
        {"check", "--root", root.string(), "--report", report.string(), "--json", json.string()});
    INFO("stdout: " << o.out << "\nstderr: " << o.err);
    CHECK(o.exit_code == 2);
    CHECK(o.err.find((report / "drop-box.svg").string() +
                     ": cannot be written (it is a directory") != std::string::npos);
    CHECK(state_of(json) == "missing");
    CHECK(state_of(report) == "folder drop-box.svg");
}

TEST_CASE("compare refuses a --junit that is one of the runs --out writes, writing neither",
          "[unit][output-paths]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    fs::create_directories(dir.dir / "runs");
    const Outcome o = run_tool_in(dir.dir, {"compare", "drop-box", "--root", root.string(),
                                            "--with", "none", "--quiet", "--out", "runs", "--junit",
                                            "./runs/drop-box.impulse.json"});
    INFO(o.out << o.err);
    CHECK(o.exit_code == 2);
    CHECK(o.err.find("--junit names ./runs/drop-box.impulse.json, a run --out writes") !=
          std::string::npos);
    CHECK(state_of(dir.dir / "runs") == "folder");
}
