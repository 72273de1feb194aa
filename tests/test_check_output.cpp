// `impulse check` for CI, through the real tool: --json (impulse/check@1)
// says the first divergence the terminal says, with the exact numbers of the
// golden that was changed; --quiet prints the failing rows and the totals
// only; --compare puts the reference comparison into the same JUnit file as
// a second testsuite; a shard that holds none of the scenes given says where
// they are; a bad --json, --compare or pair of standard outputs is one
// sentence, exit 2, nothing written.
#include "gate.h"
#include "strict_json.h"
#include "support/bad_input.h"
#include "support/files.h"
#include "support/roots.h"
#include "support/tool.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;
using impulse::harness::parse_strict_json;
using impulse::harness::read_trajectory_file;
using impulse::harness::Trajectory;
using impulse::harness::write_trajectory;
using Json = nlohmann::json;

namespace {

// The golden value a test moved by one ULP, and where.
struct Moved {
    std::size_t frame = 0;
    double t = 0.0;
    double before = 0.0; // what the engine computes again
    double after = 0.0;  // what the golden now says
};

// Moves box.y of one frame of ROOT/goldens/drop-box.json up by one ULP (the
// digest written again, so the golden still reads): the run then differs
// from its golden in that one value, 1 ULP apart.
Moved move_drop_box_y(const fs::path& root, std::size_t frame) {
    const fs::path file = root / "goldens" / "drop-box.json";
    Trajectory golden = read_trajectory_file(file.string(), "a golden");
    std::size_t y = 0;
    while (y < golden.columns.size() && golden.columns[y] != "box.y") {
        ++y;
    }
    REQUIRE(y < golden.columns.size());
    REQUIRE(frame < golden.frames.size());
    Moved moved;
    moved.frame = frame;
    moved.t = golden.frames[frame][0];
    moved.before = golden.frames[frame][y];
    moved.after = std::nextafter(moved.before, std::numeric_limits<double>::infinity());
    golden.frames[frame][y] = moved.after;
    spit(file, write_trajectory(golden));
    return moved;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t from = 0;
    for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', from)) {
        lines.push_back(text.substr(from, at - from));
        from = at + 1;
    }
    if (from < text.size()) {
        lines.push_back(text.substr(from));
    }
    return lines;
}

// A refusal: one line on standard error naming `option`, exit 2, nothing on
// standard output.
void require_refused(const Outcome& o, const std::string& option) {
    CHECK(o.exit_code == 2);
    CHECK(o.out.empty());
    CHECK(count_of(o.err, "\n") == 1);
    CHECK(o.err.find(option) != std::string::npos);
}

} // namespace

TEST_CASE("check --json states the terminal's first divergence with the golden's exact numbers",
          "[check-output]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box", "drop-circle"}, Goldens::copied);
    const Moved moved = move_drop_box_y(root, 10);
    const fs::path json_file = dir.dir / "check.json";

    const Outcome o = run_tool({"check", "--root", root.string(), "--json", json_file.string()});
    REQUIRE(o.exit_code == 1);
    const Json doc = parse_strict_json<Json>(slurp(json_file), json_file.string());
    CHECK(doc["schema"] == "impulse/check@1");
    CHECK(doc["exit_code"] == 1);
    CHECK(doc["totals"]["scenes"] == 2);
    CHECK(doc["totals"]["passed"] == 1);
    CHECK(doc["totals"]["failed"] == 1);
    CHECK(doc["accept"].is_string());
    REQUIRE(doc["scenes"].size() == 2);
    const Json& box = doc["scenes"][0]["name"] == "drop-box" ? doc["scenes"][0] : doc["scenes"][1];
    const Json& circle =
        doc["scenes"][0]["name"] == "drop-box" ? doc["scenes"][1] : doc["scenes"][0];
    CHECK(circle["status"] == "ok");
    CHECK(circle["first_divergence"].is_null());
    CHECK(box["status"] == "diff");
    CHECK(box["golden"].get<std::string>().find("drop-box.json") != std::string::npos);

    const Json& first = box["first_divergence"];
    REQUIRE(first.is_object());
    CHECK(first["column"] == "box.y");
    CHECK(first["body"] == "box");
    CHECK(first["field"] == "y");
    CHECK(first["channel"] == "position");
    CHECK(first["frame"] == moved.frame);
    CHECK(first["t"].get<double>() == moved.t);
    CHECK(first["golden"].get<double>() == moved.after);
    CHECK(first["new"].get<double>() == moved.before);
    CHECK(first["abs"].get<double>() == moved.after - moved.before);
    CHECK(first["ulp"] == 1);
    // Only the one value moved: the position channel differs once, no other.
    CHECK(box["channels"]["position"]["differing"] == 1);
    CHECK(box["channels"]["position"]["max_ulp"] == 1);
    CHECK(box["channels"]["velocity"]["differing"] == 0);

    // The terminal says the same sentence, in the same run's table.
    const std::string line = first["line"].get<std::string>();
    CHECK(line.find("box.y") != std::string::npos);
    CHECK(o.out.find(line) != std::string::npos);
    CHECK(box["message"].get<std::string>().find(line) != std::string::npos);
}

TEST_CASE("check --json - is standard output alone; the table goes to standard error",
          "[check-output]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-circle"}, Goldens::copied);
    const Outcome o = run_tool({"check", "--root", root.string(), "--json", "-"});
    REQUIRE(o.exit_code == 0);
    const Json doc = parse_strict_json<Json>(o.out, "standard output");
    CHECK(doc["scenes"][0]["status"] == "ok");
    CHECK(doc["exit_code"] == 0);
    CHECK(doc["accept"].is_null());
    CHECK(o.err.find("1 scene: 1 passed, 0 failed, 0 errors") != std::string::npos);
}

TEST_CASE("check --quiet prints only the failing rows and the totals", "[check-output]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box", "drop-circle"}, Goldens::copied);
    move_drop_box_y(root, 10);

    const Outcome o = run_tool({"check", "--root", root.string(), "--quiet"});
    CHECK(o.exit_code == 1);
    const std::vector<std::string> lines = lines_of(o.out);
    REQUIRE(lines.size() == 2);
    CHECK(lines[0].rfind("  FAILED drop-box", 0) == 0);
    CHECK(lines[0].find("box.y") != std::string::npos);
    CHECK(lines[1] == "2 scenes: 1 passed, 1 failed, 0 errors");
    CHECK(o.out.find("drop-circle") == std::string::npos);

    // All passing: the totals line alone.
    const TempDir clean;
    const fs::path passing = make_root(clean, {"drop-circle"}, Goldens::copied);
    const Outcome ok = run_tool({"check", "--root", passing.string(), "--quiet"});
    CHECK(ok.exit_code == 0);
    CHECK(ok.out == "1 scene: 1 passed, 0 failed, 0 errors\n");
}

TEST_CASE("check --compare puts the reference comparison in the same JUnit file and JSON",
          "[check-output]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box", "drop-circle"}, Goldens::copied);
    const fs::path junit = dir.dir / "junit.xml";
    const fs::path json_file = dir.dir / "check.json";

    const Outcome o = run_tool({"check", "--root", root.string(), "--compare=box2d-2.4", "--junit",
                                junit.string(), "--json", json_file.string()});
    const std::string xml = slurp(junit);
    INFO(o.out << o.err);
    CHECK(count_of(xml, "<testsuites ") == 1);
    CHECK(count_of(xml, "<testsuite name=\"impulse.gate\"") == 1);
    CHECK(count_of(xml, "<testsuite name=\"impulse.compare\"") == 1);
    CHECK(xml.find("classname=\"impulse.gate\" name=\"drop-box\"") != std::string::npos);
    CHECK(xml.find("classname=\"impulse.compare.drop-box\" name=\"box2d-2.4\"") !=
          std::string::npos);
    CHECK(xml.find("classname=\"impulse.compare.drop-circle\" name=\"box2d-2.4\"") !=
          std::string::npos);
    // The gate's suite comes first and both close.
    CHECK(xml.find("impulse.gate") < xml.find("impulse.compare"));
    CHECK(count_of(xml, "</testsuite>") == 2);

    // The comparison's summary follows the gate's totals on the terminal.
    const std::size_t totals = o.out.find("2 scenes: 2 passed, 0 failed, 0 errors");
    REQUIRE(totals != std::string::npos);
    CHECK(o.out.find("compare: 2 scenes", totals) != std::string::npos);

    // A comparison that passes has no row per scene: its summary stays a few lines.
    if (o.exit_code == 0) {
        const std::string summary = o.out.substr(o.out.find("compare: 2 scenes"));
        CHECK(summary.find("\n  ok ") == std::string::npos);
        CHECK(count_of(summary, "\n") <= 8);
    }

    const Json doc = parse_strict_json<Json>(slurp(json_file), json_file.string());
    REQUIRE(doc["comparison"].is_object());
    CHECK(doc["comparison"]["schema"] == "impulse/engine-comparison@1");
    CHECK(doc["comparison"]["scenes"].size() == 2);
    // The exit code is the worse of the gate's (0 here) and the comparison's.
    const int comparison_code = doc["comparison"]["passed"].get<bool>() ? 0 : 1;
    CHECK(o.exit_code == comparison_code);
    CHECK(doc["exit_code"] == comparison_code);

    // Quiet and passing: the gate's totals line alone.
    if (comparison_code == 0) {
        const Outcome quiet =
            run_tool({"check", "--root", root.string(), "--compare=box2d-2.4", "--quiet"});
        CHECK(quiet.exit_code == 0);
        CHECK(quiet.out == "2 scenes: 2 passed, 0 failed, 0 errors\n");
    }
}

TEST_CASE("A shard that holds none of the scenes given says which shard holds them",
          "[check-output]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-box"}, Goldens::copied);
    const std::string scene = (root / "harness" / "scenes" / "drop-box.json").string();
    int home = 0;
    for (int k = 1; k <= 3; ++k) {
        if (!impulse::harness::shard({scene}, k, 3).empty()) {
            home = k;
        }
    }
    REQUIRE(home != 0);
    const int other = home % 3 + 1;

    const Outcome empty = run_tool(
        {"check", "drop-box", "--root", root.string(), "--shard", std::to_string(other) + "/3"});
    CHECK(empty.exit_code == 0);
    CHECK(empty.out.find("check: shard " + std::to_string(other) +
                         "/3 holds none of the 1 scene given (drop-box is in shard " +
                         std::to_string(home) + "/3)") != std::string::npos);
    CHECK(empty.out.find("0 scenes: 0 passed") != std::string::npos);

    const Outcome held = run_tool(
        {"check", "drop-box", "--root", root.string(), "--shard", std::to_string(home) + "/3"});
    CHECK(held.exit_code == 0);
    CHECK(held.out.find("holds none") == std::string::npos);
    CHECK(held.out.find("1 scene: 1 passed") != std::string::npos);
}

TEST_CASE("Bad --json, --compare and standard outputs: one sentence, exit 2, nothing written",
          "[check-output]") {
    const TempDir dir;
    const fs::path root = make_root(dir, {"drop-circle"}, Goldens::copied);
    const std::string r = root.string();

    SECTION("--json to a directory") {
        const fs::path folder = dir.dir / "a-folder";
        fs::create_directories(folder);
        const Outcome o = run_tool({"check", "--root", r, "--json", folder.string()});
        require_refused(o, "--json");
        CHECK(o.err.find("is a directory") != std::string::npos);
        CHECK(fs::is_directory(folder));
        CHECK(fs::is_empty(folder));
    }
    SECTION("--json into goldens/") {
        const fs::path target = root / "goldens" / "check.json";
        const Outcome o = run_tool({"check", "--root", r, "--json", target.string()});
        require_refused(o, "--json");
        CHECK(o.err.find("goldens folder") != std::string::npos);
        CHECK_FALSE(fs::exists(target));
    }
    SECTION("--compare with an unknown reference") {
        const fs::path target = dir.dir / "check.json";
        const Outcome o =
            run_tool({"check", "--root", r, "--compare=no-such-engine", "--json", target.string()});
        require_refused(o, "--compare");
        CHECK(o.err.find("no reference engine is named 'no-such-engine'") != std::string::npos);
        CHECK_FALSE(fs::exists(target));
    }
    SECTION("--json - and --junit - together") {
        const Outcome o = run_tool({"check", "--root", r, "--json", "-", "--junit", "-"});
        require_refused(o, "--json");
        CHECK(o.err.find("standard output") != std::string::npos);
    }
}

TEST_CASE("A bad -j names its bounds, and a bad --shard is said before the engine is looked for",
          "[unit][check-output]") {
    const TempDir dir;
    // A project whose only engine cannot start: an option's mistake must be
    // the sentence the user reads, not the engine's.
    const fs::path root = dir.dir / "project";
    spit(root / "scenes" / "drop-box.json",
         slurp(fs::path(IMPULSE_SOURCE_DIR) / "harness/scenes/drop-box.json"));
    spit(root / "impulse.json", R"({"schema": "impulse/project@1", "scenes": ["scenes"],
        "engines": [{"name": "mine", "command": ["./no-such-engine"]}]})");
    for (const std::string& jobs : std::vector<std::string>{"0", "1025", "99999999999"}) {
        const Outcome o = run_tool({"check", "--root", root.string(), "-j", jobs});
        INFO("-j " << jobs << ": " << o.err);
        CHECK(o.exit_code == 2);
        CHECK(o.err.find("--jobs must be a whole number from 1 to 1024, got '" + jobs + "'") !=
              std::string::npos);
    }
    for (const std::string& shard :
         std::vector<std::string>{"0/3", "4/3", "1/99999999999", "1-3"}) {
        const Outcome o = run_tool({"check", "--root", root.string(), "--shard", shard});
        INFO("--shard " << shard << ": " << o.err);
        CHECK(o.exit_code == 2);
        CHECK(o.err.find("--shard") != std::string::npos);
        CHECK(o.err.find("no-such-engine") == std::string::npos);
    }
    // With good options, the engine is what is wrong.
    const Outcome o = run_tool({"check", "--root", root.string(), "--shard", "1/3", "-j", "2"});
    CHECK(o.exit_code == 2);
    CHECK(o.err.find("no-such-engine") != std::string::npos);
}
