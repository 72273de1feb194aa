// Bad scenes through the real tool (issue 7, "Bad input"; docs/design.md, "The
// command-line tool"): every way a scene can be wrong ends in exit code 2 and
// one line on stderr that names the file and the JSON path. Never a crash or
// a stack trace, never a partial output file, never a golden touched, never a
// file written outside goldens/ (support/bad_input.h).
//
// test_scene_*.cpp check the loader's messages one by one; these run the
// built `impulse` as a user does and check the contract around them: exit
// code, one sentence, nothing written.
#include "support/bad_input.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

// A valid scene, written over several lines as people write them: a box
// dropped onto static ground. Every case below changes one thing in it.
const std::string valid_scene = R"({
  "schema": "impulse/scene@1",
  "name": "drop",
  "gravity": [0, -9.81],
  "restitution": 0.5,
  "dt": 0.01,
  "duration": 0.5,
  "solver": {"integrator": "symplectic-euler"},
  "bodies": [
    {"name": "ground", "static": true, "shape": {"box": [5, 0.5]}, "position": [0, -0.5]},
    {"name": "box", "shape": {"box": [0.5, 0.5]}, "mass": 1, "position": [0, 2]}
  ]
}
)";

// The same with `from` replaced by `to`.
std::string scene_edit(const std::string& from, const std::string& to) {
    return replace_once(valid_scene, from, to);
}

// A valid gas scene (no listed bodies: the block makes them).
const std::string valid_gas_scene = R"({
  "schema": "impulse/scene@1",
  "name": "gas",
  "gravity": [0, 0],
  "dt": 0.01,
  "duration": 0.1,
  "gas": {"count": 4, "shape": {"circle": 0.1}, "mass": 1, "spacing": 0.5, "max_speed": 1}
}
)";

std::string gas_edit(const std::string& from, const std::string& to) {
    return replace_once(valid_gas_scene, from, to);
}

std::string with_scene_name(const std::string& json_string) {
    return scene_edit("\"name\": \"drop\"", "\"name\": " + json_string);
}

const std::string name_rule = "must be 1 to 64 letters, digits, '.', '_' or '-'";

} // namespace

TEST_CASE("The scenes the bad-input cases start from are valid", "[unit][bad-input]") {
    const TempDir dir;
    for (const std::string& text : {valid_scene, valid_gas_scene}) {
        const fs::path scene = dir.dir / "scene.json";
        spit(scene, text);
        const Outcome o = run_tool({"run", scene.string()});
        INFO(o.err);
        CHECK(o.exit_code == 0);
        CHECK(o.err.empty());
        CHECK_FALSE(o.out.empty());
    }
}

TEST_CASE("A scene that is not JSON is exit 2, one sentence, nothing written",
          "[unit][bad-input]") {
    const std::string real_scene =
        slurp(fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes" / "drop-box.json");
    REQUIRE(real_scene.size() > 100);
    const std::vector<BadFile> cases = {
        bad_text("not JSON", "this is not a scene\n", "", "not valid JSON: line 1, column "),
        bad_text("a bare word where a value belongs", scene_edit("\"drop\"", "drop"), "name",
                 "not valid JSON: line 3"),
        bad_text("empty file", "", "", "not valid JSON"),
        bad_text("only whitespace", "\n\n  \n", "", "not valid JSON"),
        bad_text("truncated: a real scene cut in the middle",
                 real_scene.substr(0, real_scene.size() / 2), std::nullopt, "not valid JSON"),
        bad_text("truncated: the last brace missing", valid_scene.substr(0, valid_scene.rfind('}')),
                 "", "not valid JSON"),
        bad_text("truncated after a key", valid_scene.substr(0, valid_scene.find("0.01")), "dt",
                 "not valid JSON"),
        bad_text("something after the document", valid_scene + "}\n", "", "not valid JSON"),
        bad_text("a merge conflict",
                 scene_edit("  \"restitution\": 0.5,\n",
                            "<<<<<<< HEAD\n  \"restitution\": 0.5,\n=======\n"
                            "  \"restitution\": 0.7,\n>>>>>>> other-branch\n"),
                 "", "has a merge-conflict marker at line 5"),
        bad_text("a leftover ======= alone", scene_edit("  \"dt\"", "=======\n  \"dt\""), "",
                 "has a merge-conflict marker at line 6"),
        bad_text("a leftover >>>>>>> alone", valid_scene + ">>>>>>> theirs\n", "",
                 "has a merge-conflict marker at line 14"),
        bad_text("binary bytes", std::string("\xff\xfe\x00\x01", 4), "", "not valid JSON"),
        bad_text("a string that is not UTF-8",
                 scene_edit("\"name\": \"drop\"", "\"name\": \"dr\xffop\""), "name",
                 "ill-formed UTF-8"),
        bad_text("the top level an array", "[1, 2]\n", "", "the top level must be a JSON object"),
        bad_text("the top level a string", "\"impulse/scene@1\"\n", "",
                 "the top level must be a JSON object"),
        bad_text("nested 10000 levels deep, unclosed", std::string(10000, '['), "",
                 "is nested too deeply"),
        bad_text(
            "nested 10000 levels deep inside a value",
            scene_edit("\"symplectic-euler\"", std::string(10000, '[') + std::string(10000, ']')),
            "", "is nested too deeply"),
        bad_size("a sparse file of 17 MiB, over the 16 MiB limit", 17u * 1024 * 1024,
                 "is too large: more than 16 MiB"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A scene with the wrong schema, types or keys is exit 2 naming the JSON path",
          "[unit][bad-input]") {
    const std::vector<BadFile> cases = {
        // schema
        bad_text("a trajectory's schema", scene_edit("impulse/scene@1", "impulse/trajectory@1"),
                 "schema", "not a scene: expected \"impulse/scene@1\""),
        bad_text("no version", scene_edit("impulse/scene@1", "impulse/scene"), "schema",
                 "not a scene"),
        bad_text("version 2", scene_edit("impulse/scene@1", "impulse/scene@2"), "schema",
                 "unsupported scene version \"impulse/scene@2\""),
        bad_text("schema a number", scene_edit("\"impulse/scene@1\"", "1"), "schema",
                 "not a scene"),
        bad_text("schema missing", scene_edit("  \"schema\": \"impulse/scene@1\",\n", ""), "schema",
                 "is required but missing"),
        // wrong types
        bad_text("a string for a number", scene_edit("\"dt\": 0.01", "\"dt\": \"0.01\""), "dt",
                 "must be a number, got \"0.01\""),
        bad_text("a number for a string", scene_edit("\"name\": \"drop\"", "\"name\": 5"), "name",
                 "must be a string, got 5"),
        bad_text("a boolean for a number",
                 scene_edit("\"restitution\": 0.5", "\"restitution\": true"), "restitution",
                 "must be a number, got true"),
        bad_text("an object for an array",
                 scene_edit("\"gravity\": [0, -9.81]", "\"gravity\": {\"x\": 0, \"y\": -9.81}"),
                 "gravity", "must be an array of two numbers"),
        bad_text("a string inside an array", scene_edit("[0, -9.81]", "[0, \"down\"]"),
                 "gravity[1]", "must be a number, got \"down\""),
        bad_text("an array for an object",
                 scene_edit("\"solver\": {\"integrator\": \"symplectic-euler\"}",
                            "\"solver\": [\"symplectic-euler\"]"),
                 "solver", "must be an object, got an array"),
        bad_text("a number for a name in the solver",
                 scene_edit("\"integrator\": \"symplectic-euler\"", "\"integrator\": 4"),
                 "solver.integrator", "must be one of"),
        bad_text("an object for the bodies array",
                 R"({"schema": "impulse/scene@1", "name": "drop", "dt": 0.01, "duration": 0.5,
                     "bodies": {"box": {"shape": {"circle": 1}}}})",
                 "bodies", "must be an array, got an object"),
        bad_text("a string for a body",
                 scene_edit("{\"name\": \"box\", \"shape\": {\"box\": [0.5, 0.5]}, "
                            "\"mass\": 1, \"position\": [0, 2]}",
                            "\"box\""),
                 "bodies[1]", "must be an object"),
        bad_text("an array for a shape",
                 scene_edit("\"shape\": {\"box\": [0.5, 0.5]}", "\"shape\": [0.5, 0.5]"),
                 "bodies[1].shape", "must be an object, got an array"),
        bad_text("a string for a boolean", scene_edit("\"static\": true", "\"static\": \"yes\""),
                 "bodies[0].static", "must be true or false, got \"yes\""),
        bad_text("null for a number", scene_edit("\"mass\": 1", "\"mass\": null"), "bodies[1].mass",
                 "must be a number, got null"),
        bad_text("a pair with one number", scene_edit("\"position\": [0, 2]", "\"position\": [2]"),
                 "bodies[1].position", "must be an array of two numbers"),
        bad_text("\"NaN\" as a string", scene_edit("\"mass\": 1", "\"mass\": \"NaN\""),
                 "bodies[1].mass", "must be a number, got \"NaN\""),
        // missing required keys
        bad_text("name missing", scene_edit("  \"name\": \"drop\",\n", ""), "name",
                 "is required but missing"),
        bad_text("dt missing", scene_edit("  \"dt\": 0.01,\n", ""), "dt",
                 "is required but missing"),
        bad_text("duration missing", scene_edit("  \"duration\": 0.5,\n", ""), "duration",
                 "is required but missing"),
        bad_text("bodies missing",
                 R"({"schema": "impulse/scene@1", "name": "drop", "dt": 0.01, "duration": 0.5})",
                 "bodies", "is required but missing"),
        bad_text("a body's name missing", scene_edit("\"name\": \"box\", ", ""), "bodies[1].name",
                 "is required but missing"),
        bad_text("a body's shape missing", scene_edit("\"shape\": {\"box\": [0.5, 0.5]}, ", ""),
                 "bodies[1].shape", "is required but missing"),
        bad_text("the gas block's count missing", gas_edit("\"count\": 4, ", ""), "gas.count",
                 "is required but missing"),
        // unknown keys, with the hint when it is a typo
        bad_text("a typo at the top level", scene_edit("\"gravity\"", "\"gravty\""), "gravty",
                 "unknown key (did you mean gravity?)"),
        bad_text("a typo in a body", scene_edit("\"mass\": 1", "\"mas\": 1"), "bodies[1].mas",
                 "unknown key (did you mean mass?)"),
        bad_text("a typo in the solver", scene_edit("\"integrator\"", "\"integrater\""),
                 "solver.integrater", "unknown key (did you mean integrator?)"),
        bad_text("a typo in the gas block", gas_edit("\"spacing\"", "\"spaceing\""), "gas.spaceing",
                 "unknown key (did you mean spacing?)"),
        bad_text("an unknown key that is no typo",
                 scene_edit("\"gravity\"", "\"comment\": \"x\", \"gravity\""), "comment",
                 "unknown key; the keys allowed here are"),
        bad_text("an unknown key that is not an identifier",
                 scene_edit("\"gravity\"", "\"we ird\": 1, \"gravity\""), "[\"we ird\"]",
                 "unknown key"),
        // duplicate keys
        bad_text("a key twice at the top level",
                 scene_edit("\"dt\": 0.01,", "\"dt\": 0.01, \"dt\": 0.02,"), "dt",
                 "appears more than once in the same object"),
        bad_text("a key twice in a body", scene_edit("\"mass\": 1", "\"mass\": 1, \"mass\": 2"),
                 "bodies[1].mass", "appears more than once"),
        bad_text("a key twice in the solver",
                 scene_edit("\"integrator\": \"symplectic-euler\"",
                            "\"integrator\": \"symplectic-euler\", \"integrator\": \"rk4\""),
                 "solver.integrator", "appears more than once"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A scene with a non-finite or out-of-range number is exit 2 naming the JSON path",
          "[unit][bad-input]") {
    const std::vector<BadFile> cases = {
        // non-finite: JSON has no NaN or Infinity, and 1e999 overflows a double
        bad_text("1e999", scene_edit("\"restitution\": 0.5", "\"restitution\": 1e999"),
                 "restitution", "number overflow parsing '1e999'"),
        bad_text("-1e999 inside an array", scene_edit("[0, 2]", "[0, -1e999]"),
                 "bodies[1].position[1]", "number overflow"),
        bad_text("NaN", scene_edit("\"mass\": 1", "\"mass\": NaN"), "bodies[1].mass",
                 "not valid JSON"),
        bad_text("Infinity", scene_edit("\"dt\": 0.01", "\"dt\": Infinity"), "dt",
                 "not valid JSON"),
        bad_text("-Infinity", scene_edit("[0, -9.81]", "[0, -Infinity]"), "gravity[1]",
                 "not valid JSON"),
        // out of range
        bad_text("negative mass", scene_edit("\"mass\": 1", "\"mass\": -1"), "bodies[1].mass",
                 "must be > 0, got -1"),
        bad_text("zero mass", scene_edit("\"mass\": 1", "\"mass\": 0"), "bodies[1].mass",
                 "must be > 0, got 0"),
        bad_text("negative inertia", scene_edit("\"mass\": 1", "\"mass\": 1, \"inertia\": -2"),
                 "bodies[1].inertia", "must be > 0, got -2"),
        bad_text("e > 1", scene_edit("\"restitution\": 0.5", "\"restitution\": 1.5"), "restitution",
                 "must be between 0 and 1, got 1.5"),
        bad_text("e < 0", scene_edit("\"restitution\": 0.5", "\"restitution\": -0.1"),
                 "restitution", "must be between 0 and 1, got -0.1"),
        bad_text("dt = 0", scene_edit("\"dt\": 0.01", "\"dt\": 0"), "dt", "must be > 0, got 0"),
        bad_text("dt < 0", scene_edit("\"dt\": 0.01", "\"dt\": -0.01"), "dt",
                 "must be > 0, got -0.01"),
        bad_text("duration shorter than dt", scene_edit("\"duration\": 0.5", "\"duration\": 0.001"),
                 "duration", "must be >= dt"),
        bad_text("a huge duration: too many steps",
                 scene_edit("\"duration\": 0.5", "\"duration\": 1e9"), "duration",
                 "steps; at most 10000000 are allowed"),
        bad_text("an absurd duration", scene_edit("\"duration\": 0.5", "\"duration\": 1e300"),
                 "duration", "steps; at most 10000000 are allowed"),
        bad_text("gas count 0", gas_edit("\"count\": 4", "\"count\": 0"), "gas.count",
                 "must be a whole number from 1 to 100000, got 0"),
        bad_text("gas count 2.5", gas_edit("\"count\": 4", "\"count\": 2.5"), "gas.count",
                 "must be a whole number"),
        bad_text("gas count a million", gas_edit("\"count\": 4", "\"count\": 1000000"), "gas.count",
                 "must be a whole number from 1 to 100000"),
        bad_text("gas spacing too small to keep the bodies apart",
                 gas_edit("\"spacing\": 0.5", "\"spacing\": 0.1"), "gas.spacing",
                 "must be more than the shape's bounding diameter"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A scene with a bad shape or overlapping bodies is exit 2 naming the body",
          "[unit][bad-input]") {
    const auto shape = [](const std::string& json) {
        return scene_edit("\"shape\": {\"box\": [0.5, 0.5]}", "\"shape\": " + json);
    };
    const std::vector<BadFile> cases = {
        bad_text("a non-convex polygon",
                 shape(R"({"polygon": [[-1, -1], [1, -1], [1, 1], [0, 0], [-1, 1]]})"),
                 "bodies[1].shape.polygon[3]", "is a reflex corner"),
        bad_text("a clockwise polygon", shape(R"({"polygon": [[-1, -1], [0, 1], [1, -1]]})"),
                 "bodies[1].shape.polygon", "must be counter-clockwise (positive area)"),
        bad_text("a zero-area polygon", shape(R"({"polygon": [[0, 0], [1, 0], [2, 0]]})"),
                 "bodies[1].shape.polygon", "got area 0"),
        bad_text("a polygon too small to have an area",
                 shape(R"({"polygon": [[-1e-200, -1e-200], [1e-200, -1e-200], [0, 1e-200]]})"),
                 "bodies[1].shape.polygon", "got area 0"),
        bad_text("a polygon whose area overflows",
                 shape(R"({"polygon": [[-1e200, -1e200], [1e200, -1e200], [0, 1e200]]})"),
                 "bodies[1].shape.polygon", "its area overflows double precision"),
        // 2^48 contact tolerances (1e-9 m) is 2.8e5 m: these corners are held
        // to 1.5e-8 m, and recentring would carry the body 1e8 m out.
        bad_text("a polygon given 1e8 m from its body's origin",
                 shape(R"({"polygon": [[1e8, 1e8], [100000000.16, 1e8], [100000000.08, )"
                       R"(100000000.12]]})"),
                 "bodies[1].shape.polygon",
                 "has vertices 100000000.16 m from the body's origin, but positions resolve"),
        bad_text("a repeated vertex", shape(R"({"polygon": [[-1, -1], [1, -1], [1, -1], [0, 1]]})"),
                 "bodies[1].shape.polygon[2]", "repeats vertex 1"),
        bad_text("every vertex the same", shape(R"({"polygon": [[0, 0], [0, 0], [0, 0]]})"),
                 "bodies[1].shape.polygon[0]", "repeats vertex"),
        bad_text("two vertices", shape(R"({"polygon": [[0, 0], [1, 0]]})"),
                 "bodies[1].shape.polygon", "must have 3 to"),
        bad_text("zero radius", shape(R"({"circle": 0})"), "bodies[1].shape.circle",
                 "must be > 0, got 0"),
        bad_text("negative radius", shape(R"({"circle": -1})"), "bodies[1].shape.circle",
                 "must be > 0, got -1"),
        bad_text("a radius too small for an inertia", shape(R"({"circle": 1e-300})"), "bodies[1]",
                 "moment of inertia"),
        bad_text("a zero half extent", shape(R"({"box": [0.5, 0]})"), "bodies[1].shape.box[1]",
                 "must be > 0, got 0"),
        bad_text("both half extents zero: the first is named", shape(R"({"box": [0, 0]})"),
                 "bodies[1].shape.box[0]", "must be > 0, got 0"),
        bad_text("two kinds of shape", shape(R"({"box": [0.5, 0.5], "circle": 1})"),
                 "bodies[1].shape.circle",
                 "a shape is exactly one of box, circle or polygon; this one also has box"),
        bad_text("no shape kind", shape("{}"), "bodies[1].shape",
                 "must have one of box, circle or polygon"),
        bad_text("a box sunk into the ground", scene_edit("[0, 2]", "[0, 0.4]"), "bodies[1]",
                 "'box' overlaps bodies[0] 'ground' at t = 0"),
        bad_text("two dynamic bodies overlapping",
                 scene_edit("\"position\": [0, 2]}",
                            "\"position\": [0, 2]},\n    {\"name\": \"ball\", \"shape\": "
                            "{\"circle\": 0.5}, \"position\": [0.5, 2.5]}"),
                 "bodies[2]", "overlaps bodies[1] 'box'"),
        bad_text("every body static", scene_edit("\"mass\": 1", "\"static\": true"), "bodies",
                 "every body is static"),
        bad_text("two bodies of one name", scene_edit("\"name\": \"box\"", "\"name\": \"ground\""),
                 "bodies[1].name", "is already the name of bodies[0]"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A scene or body name that is no plain word, or would leave goldens/, is exit 2",
          "[unit][bad-input]") {
    // As the scene's "name" a golden would be goldens/NAME.json: none of these
    // may become a path. The gate runs in a root inside a temporary folder,
    // whose snapshot shows anything written beside the root, too.
    const std::vector<std::string> names = {
        R"("a b")",  R"("")",        R"("ünïcode")",     "\"" + std::string(100, 'a') + "\"",
        R"("../x")", R"("../../x")", R"("/etc/passwd")", R"("..")",
        R"(".")",    R"(".hidden")", R"("a/b")",         R"("a\\b")",
        R"("-rf")",  R"("a\nb")",    R"("a\u0000b")",    R"("x.json\u0000")",
        R"("a:b")",  R"("a*")",      R"("~")",           R"("$HOME")",
    };
    std::vector<BadFile> cases;
    for (const std::string& name : names) {
        cases.push_back(bad_text("scene name " + name, with_scene_name(name), "name", name_rule));
        cases.push_back(bad_text("body name " + name,
                                 scene_edit("\"name\": \"box\"", "\"name\": " + name),
                                 "bodies[1].name", name_rule));
    }
    cases.push_back(bad_text("a name of 65 characters",
                             with_scene_name("\"" + std::string(65, 'a') + "\""), "name",
                             name_rule));
    // A long name of two-byte characters is shortened in the message without
    // cutting a character in half, wherever the cut falls.
    for (const std::string start : {"", "a", "ab"}) {
        std::string long_unicode = "\"" + start;
        for (int i = 0; i < 40; ++i) {
            long_unicode += "\u00fc"; // ü
        }
        long_unicode += "\"";
        cases.push_back(bad_text("a long name of non-ASCII letters after '" + start + "'",
                                 with_scene_name(long_unicode), "name", name_rule));
    }
    cases.push_back(bad_text("not a name but a number", with_scene_name("0"), "name",
                             "must be a string, got 0"));
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
    CHECK_FALSE(fs::exists("/etc/passwd.json"));
    CHECK_FALSE(fs::exists("/x.json"));
}

TEST_CASE("A scene argument that names no scene file is exit 2 and writes nothing",
          "[unit][bad-input]") {
    // check, bless and run take a scene's name or path. A name that no scene
    // has is refused before anything runs, naming the scenes folder (and the
    // closest name); a path that is not a scene file is that file's ERROR row
    // in check. Nothing is written, in goldens/ or beside it.
    const TempDir dir;
    const fs::path root = copy_of_gate(dir);
    fs::create_directories(dir.dir / "scene-is-a-folder.json");
    spit(dir.dir / "passwd", "root:x:0:0:root:/root:/bin/bash\n"); // a file, but no scene
    const auto before = snapshot(dir.dir);
    const std::string r = root.string();
    const std::string scenes = (root / "harness" / "scenes").string();
    struct Argument {
        std::string given;
        std::string file; // the file the sentence names
        std::string words;
    };
    const std::vector<Argument> arguments = {
        {"no-such-scene", scenes, "is named 'no-such-scene'"},
        {"drop-bx", scenes, "is named 'drop-bx' (did you mean 'drop-box'?)"},
        {"a b", scenes, "is named 'a b'"},
        {"a\\b", scenes, "is named 'a\\b'"},
        {"..", scenes, "is named '..'"},
        {"", scenes, "is named ''"},
        {"../x", "../x", "cannot be read"},
        {"a/b", "a/b", "cannot be read"},
        {(dir.dir / "missing.json").string(), (dir.dir / "missing.json").string(),
         "cannot be read (no such file"},
        {(dir.dir / "scene-is-a-folder.json").string(),
         (dir.dir / "scene-is-a-folder.json").string(), "cannot be read (it is a directory)"},
        {(dir.dir / "passwd").string(), (dir.dir / "passwd").string(), "not valid JSON"},
    };
    for (const Argument& a : arguments) {
        INFO("argument: '" << a.given << "'");
        check_refused(run_tool({"bless", a.given, "--root", r}), a.file, "", a.words);
        const Outcome checked = run_tool({"check", a.given, "--root", r});
        if (a.file == scenes) {
            check_refused(checked, a.file, "", a.words);
            CHECK(checked.out.empty());
            // run takes a name too, resolved in the project found from the
            // current folder: the same sentence.
            check_refused(run_tool({"run", a.given, "--root", r}), a.file, "", a.words);
        } else {
            CHECK(checked.exit_code == 2);
            CHECK(checked.err.empty());
            CHECK(checked.out.find("  ERROR  ") != std::string::npos);
            CHECK(checked.out.find(a.file + ": ") != std::string::npos);
            check_refused(run_tool({"run", a.given}), a.file, "",
                          a.words == "not valid JSON" ? a.words : "cannot be read");
        }
        CHECK(snapshot(dir.dir) == before);
    }
}

TEST_CASE("A scene whose file is not NAME.json is exit 2 and takes no other scene's golden",
          "[unit][bad-input]") {
    // Its golden would be goldens/NAME.json: a copied scene file that kept its
    // name, or a renamed one, would overwrite another scene's golden.
    const TempDir dir;
    const fs::path root = copy_of_gate(dir);
    const fs::path scenes = root / "harness" / "scenes";
    const std::string r = root.string();
    SECTION("a copy of another scene under a new file name") {
        spit(scenes / "zz-copy.json",
             replace_once(slurp(scenes / "glancing.json"), "\"name\": \"glancing\"",
                          "\"name\": \"drop-box\""));
    }
    SECTION("a scene file renamed without its name") {
        fs::rename(scenes / "drop-box.json", scenes / "zz-copy.json");
    }
    const fs::path stray = scenes / "zz-copy.json";
    const auto before = snapshot(dir.dir);
    const std::string words =
        "is \"drop-box\" but the file is zz-copy.json: a scene's golden is goldens/NAME.json";
    check_refused(run_tool({"bless", "--root", r}), stray.string(), "name", words);
    check_refused(run_tool({"bless", stray.string(), "--root", r}), stray.string(), "name", words);
    check_error_row(run_tool({"check", stray.string(), "--root", r}), "zz-copy", stray.string(),
                    "name", words);
    CHECK(snapshot(dir.dir) == before);
    CHECK(slurp(root / "goldens" / "drop-box.json") == golden_of_template("drop-box"));
}
