// Bad trajectories and goldens through the real tool (issue 7, "Bad input";
// docs/design.md, "The command-line tool"): every way one can be wrong ends in
// exit code 2 and one line on stderr (or check's ERROR row) that names the
// file and the JSON path, and no golden is touched (support/bad_input.h).
//
// test_trajectory.cpp checks the reader's messages one by one; these run the
// built `impulse` as a user does and check the contract around them.
#include "support/bad_input.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

TEST_CASE("A trajectory or golden that is not JSON is exit 2 and no golden is touched",
          "[unit][bad-input]") {
    const std::string golden = golden_of_template("drop-box");
    const std::string digest = line_of(golden, "digest");
    const std::vector<BadFile> cases = {
        bad_text("not JSON", "this is not a trajectory\n", "", "not valid JSON: line 1, column "),
        bad_text("empty file", "", "", "not valid JSON"),
        bad_text("truncated in the middle", golden.substr(0, golden.size() / 2), std::nullopt,
                 "not valid JSON"),
        bad_text("truncated: the last brace missing", golden.substr(0, golden.rfind('}')), "",
                 "not valid JSON"),
        bad_text("one byte", golden.substr(0, 1), "", "not valid JSON"),
        bad_text("two goldens in one file", golden + golden, "", "not valid JSON"),
        bad_text("a merge conflict in the digest",
                 replace_once(golden, digest + "\n",
                              "<<<<<<< HEAD\n" + digest + "\n=======\n" +
                                  "  \"digest\": \"0123456789abcdef\",\n>>>>>>> other-branch\n"),
                 "", "has a merge-conflict marker at line 7"),
        bad_text("a merge conflict at the end", golden + "=======\n", "",
                 "has a merge-conflict marker at line"),
        bad_text("binary bytes", std::string("\x89PNG\r\n\x1a\n", 8), "", "not valid JSON"),
        bad_text("the top level an array", "[1, 2]\n", "", "the top level must be a JSON object"),
        bad_text("nested 10000 levels deep", std::string(10000, '['), "", "is nested too deeply"),
        bad_text("nested 10000 levels deep, closed",
                 std::string(10000, '[') + std::string(10000, ']'), "", "is nested too deeply"),
        bad_size("a sparse file over the 256 MiB limit", 256u * 1024 * 1024 + 1,
                 "is too large: more than 256 MiB"),
    };
    for (const BadFile& bad : cases) {
        require_trajectory_refused(bad);
    }
}

TEST_CASE("A trajectory or golden with a wrong schema, type, key or number is exit 2 naming the "
          "JSON path",
          "[unit][bad-input]") {
    const std::string golden = golden_of_template("drop-box");
    const std::string edit_of_first_frame = "\"frames\": [\n    [0, 0, 1.5, 0, 0, 0, 0]";
    REQUIRE(golden.find(edit_of_first_frame) != std::string::npos);
    const auto frame0 = [&](const std::string& values) {
        return replace_once(golden, edit_of_first_frame, "\"frames\": [\n    " + values);
    };
    const auto edit = [&](const std::string& from, const std::string& to) {
        return replace_once(golden, from, to);
    };
    const std::string columns = line_of(golden, "columns");
    const std::string digest = line_of(golden, "digest");
    const std::string sha = line_of(golden, "scene_sha256");
    const std::string scene_file =
        slurp(fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes" / "drop-box.json");
    BadFile scene_as_golden = bad_text("a scene file where a golden belongs", scene_file, "schema",
                                       "must be \"impulse/trajectory@1\", got \"impulse/scene@1\"");
    scene_as_golden.is_scene_for_render = true;

    const std::vector<BadFile> cases = {
        // schema
        bad_text("a scene's schema", edit("\"impulse/trajectory@1\"", "\"impulse/scene@1\""),
                 "schema", "must be \"impulse/trajectory@1\""),
        bad_text("version 2", edit("\"impulse/trajectory@1\"", "\"impulse/trajectory@2\""),
                 "schema", "version 2 of the trajectory format is not supported"),
        bad_text("schema missing", edit("  \"schema\": \"impulse/trajectory@1\",\n", ""), "schema",
                 "is required but missing"),
        scene_as_golden,
        // wrong types
        bad_text("a number for a string", edit("\"scene\": \"drop-box\"", "\"scene\": 5"), "scene",
                 "must be a string, got 5"),
        bad_text("a string for a number", frame0("[0, 0, \"1.5\", 0, 0, 0, 0]"), "frames[0][2]",
                 "must be a number, got \"1.5\""),
        bad_text("null for a number", frame0("[0, 0, 1.5, null, 0, 0, 0]"), "frames[0][3]",
                 "must be a number, got null"),
        bad_text("an object for a frame", frame0("{\"t\": 0}"), "frames[0]",
                 "must be an array, got an object"),
        bad_text("an object for the columns", edit(columns, "  \"columns\": {\"t\": 0},"),
                 "columns", "must be an array, got an object"),
        bad_text("an array for the solver",
                 edit(line_of(golden, "solver"), "  \"solver\": [\"verlet\"],"), "solver",
                 "must be an object, got an array"),
        bad_text("a number for the digest", edit(digest, "  \"digest\": 12,"), "digest",
                 "must be a string, got 12"),
        bad_text("a number for an event's body", edit("\"a\": \"box\"", "\"a\": 7"), "events[0].a",
                 "must be a string, got 7"),
        bad_text("an object for an event's point",
                 with_value(golden, "point", "{\"x\": 0, \"y\": 0}"), "events[0].point",
                 "must be an array, got an object"),
        bad_text("a boolean for an event's impulse", with_value(golden, "impulse", "true"),
                 "events[0].impulse", "must be a number, got true"),
        // missing and unknown keys
        bad_text("the digest missing", edit(digest + "\n", ""), "digest",
                 "is required but missing"),
        bad_text("the columns missing", edit(columns + "\n", ""), "columns",
                 "is required but missing"),
        bad_text("scene_sha256 missing", edit(sha + "\n", ""), "scene_sha256",
                 "is required but missing"),
        bad_text("an event's impulse missing", without_member(golden, "impulse"),
                 "events[0].impulse", "is required but missing"),
        bad_text("a typo in an event", edit("\"impulse\": ", "\"impulze\": "), "events[0].impulze",
                 "unknown key (did you mean impulse?)"),
        bad_text("a typo at the top level", edit("\"frames\": [", "\"framez\": ["), "framez",
                 "unknown key (did you mean frames?)"),
        bad_text("an unknown key", edit(digest, digest + "\n  \"comment\": \"hand-edited\","),
                 "comment", "unknown key; the keys allowed here are"),
        // duplicate keys
        bad_text("the digest twice", edit(digest, digest + "\n" + digest), "digest",
                 "appears more than once in the same object"),
        bad_text("a solver key twice",
                 edit("\"toi\": \"bisection\"", "\"toi\": \"bisection\", \"toi\": \"secant\""),
                 "solver.toi", "appears more than once"),
        // non-finite and inexact numbers
        bad_text("1e999 in a frame", frame0("[0, 0, 1e999, 0, 0, 0, 0]"), "frames[0][2]",
                 "number overflow parsing '1e999'"),
        bad_text("NaN in a frame", frame0("[0, 0, NaN, 0, 0, 0, 0]"), "frames[0][2]",
                 "not valid JSON"),
        bad_text("Infinity in a frame", frame0("[0, 0, 1.5, 0, 0, Infinity, 0]"), "frames[0][5]",
                 "not valid JSON"),
        bad_text("-Infinity in an event", with_value(golden, "vn_after", "-Infinity"),
                 "events[0].vn_after", "not valid JSON"),
        bad_text("an integer a double cannot hold",
                 frame0("[0, 9007199254740993, 1.5, 0, 0, 0, 0]"), "frames[0][1]",
                 "cannot be held exactly by a double"),
        // columns and frames that do not match
        bad_text("a frame one value short", frame0("[0, 0, 1.5, 0, 0, 0]"), "frames[0]",
                 "has 6 values but there are 7 columns"),
        bad_text("a frame one value long", frame0("[0, 0, 1.5, 0, 0, 0, 0, 0]"), "frames[0]",
                 "has 8 values but there are 7 columns"),
        bad_text("a column missing", edit(", \"box.omega\"]", "]"), "frames[0]",
                 "has 7 values but there are 6 columns"),
        bad_text("a column too many", edit("\"box.omega\"]", "\"box.omega\", \"box.spin\"]"),
                 "frames[0]", "has 7 values but there are 8 columns"),
        bad_text("no columns", edit(columns, "  \"columns\": [],"), "columns",
                 "the first column must be \"t\""),
        bad_text("a column repeated", edit("\"box.y\"", "\"box.x\""), "columns[2]",
                 "repeats columns[1]"),
        // digests
        bad_text("a wrong digest", edit(digest, "  \"digest\": \"0123456789abcdef\","), "digest",
                 "stored digest 0123456789abcdef does not match the data"),
        bad_text("a number edited by hand", frame0("[0, 0, 1.25, 0, 0, 0, 0]"), "digest",
                 "does not match the data"),
        bad_text("a digest in capitals", edit(digest, "  \"digest\": \"0123456789ABCDEF\","),
                 "digest", "must be 16 lowercase hex digits"),
        bad_text("a short scene_sha256", edit(sha, "  \"scene_sha256\": \"abc\","), "scene_sha256",
                 "must be 64 lowercase hex digits"),
    };
    for (const BadFile& bad : cases) {
        require_trajectory_refused(bad);
    }
}

TEST_CASE("A missing golden or a golden that is a folder is exit 2 and nothing is written",
          "[unit][bad-input]") {
    const TempDir dir;
    const fs::path root = copy_of_gate(dir);
    const fs::path golden = root / "goldens" / "drop-box.json";
    const std::string r = root.string();

    fs::remove(golden);
    auto before = snapshot(dir.dir);
    check_error_row(run_tool({"check", "--root", r}), "drop-box", golden.string(), "",
                    "no golden for scene 'drop-box'; bless it with scripts/regen-goldens drop-box");
    check_error_row(run_tool({"check", "--root", r}, {"CI=true"}), "drop-box", golden.string(), "",
                    "no golden for scene 'drop-box'");
    CHECK(snapshot(dir.dir) == before);

    // A folder where the golden belongs: check cannot read it, bless cannot
    // replace it; neither leaves a file behind.
    fs::create_directories(golden);
    before = snapshot(dir.dir);
    check_error_row(run_tool({"check", "--root", r}), "drop-box", golden.string(), "",
                    "cannot be read (it is a directory)");
    const Outcome blessed = run_tool({"bless", "--root", r});
    check_refused(blessed, golden.string(), "", "cannot be written");
    CHECK(snapshot(dir.dir) == before);
}

TEST_CASE("A stale golden is exit 1 and named stale, not a broken input", "[unit][bad-input]") {
    // docs/design.md: a golden whose scene_sha256 no longer matches its scene is
    // reported as stale, not as a physics diff; README: exit 1.
    const std::string golden = golden_of_template("drop-box");
    const std::string sha = line_of(golden, "scene_sha256");
    const auto require_stale = [](const Outcome& o) {
        INFO(o.out << o.err);
        CHECK(o.exited);
        CHECK(o.exit_code == 1);
        CHECK(o.out.find("FAILED drop-box  stale golden: the scene changed since it was blessed; "
                         "if that was intended, run scripts/regen-goldens drop-box") !=
              std::string::npos);
        CHECK(o.out.find("ERROR") == std::string::npos);
    };

    SECTION("the golden records another scene_sha256, the motion the same") {
        const TempDir dir;
        const fs::path root = copy_of_gate(dir);
        spit(root / "goldens" / "drop-box.json",
             replace_once(golden, sha, "  \"scene_sha256\": \"" + std::string(64, '0') + "\","));
        const auto before = snapshot(dir.dir);
        require_stale(run_tool({"check", "--root", root.string()}));
        require_stale(run_tool({"check", "--root", root.string()}, {"CI=true"}));
        CHECK(snapshot(dir.dir) == before);
    }
    SECTION("the scene's description was edited since the blessing") {
        const TempDir dir;
        const fs::path root = copy_of_gate(dir);
        const fs::path scene = root / "harness" / "scenes" / "drop-box.json";
        spit(scene,
             replace_once(slurp(scene), "\"description\": \"", "\"description\": \"Edited. "));
        const auto before = snapshot(dir.dir);
        require_stale(run_tool({"check", "--root", root.string()}));
        CHECK(snapshot(dir.dir) == before);
        // Blessing again is the way out.
        CHECK(run_tool({"bless", "--root", root.string()}).exit_code == 0);
        CHECK(run_tool({"check", "--root", root.string()}).exit_code == 0);
    }
    SECTION("the golden of another scene") {
        const TempDir dir;
        const fs::path root = copy_of_gate(dir);
        fs::copy_file(root / "goldens" / "glancing.json", root / "goldens" / "drop-box.json",
                      fs::copy_options::overwrite_existing);
        const auto before = snapshot(dir.dir);
        const Outcome o = run_tool({"check", "--root", root.string()});
        // Stale, and said as what it is: another scene's golden.
        INFO(o.out << o.err);
        CHECK(o.exit_code == 1);
        CHECK(o.out.find("FAILED drop-box  wrong golden: it is of scene 'glancing', not "
                         "'drop-box'; run scripts/regen-goldens drop-box to record this "
                         "scene's") != std::string::npos);
        CHECK(o.out.find("ERROR") == std::string::npos);
        CHECK(snapshot(dir.dir) == before);
    }
    SECTION("diff only notes a different scene_sha256") {
        const TempDir dir;
        const fs::path a = dir.dir / "a.json", b = dir.dir / "b.json";
        spit(a, golden);
        spit(b, replace_once(golden, sha, "  \"scene_sha256\": \"" + std::string(64, 'f') + "\","));
        const Outcome o = run_tool({"diff", a.string(), b.string()});
        CHECK(o.exit_code == 0);
        CHECK(o.out.find("scene_sha256 differs") != std::string::npos);
        CHECK(o.out.find("identical") != std::string::npos);
    }
}
