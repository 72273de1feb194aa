// The project file, impulse.json (docs/project-file.md), through the real
// binary: where a user's scenes and goldens are, which engines run them, and
// every mistake in it refused with the file and the JSON path.
#include "junit.h"
#include "scene_check.h"
#include "support/bad_input.h"
#include "support/files.h"
#include "support/outcome.h"
#include "support/tool.h"
#include "support/tool_in_folder.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

const fs::path source_scenes = fs::path(IMPULSE_SOURCE_DIR) / "harness" / "scenes";
const fs::path source_goldens = fs::path(IMPULSE_SOURCE_DIR) / "goldens";

// A project folder with `project_json` as its impulse.json and copies of the
// canonical scenes named in `scenes`, each into the folder given with it.
struct ProjectDir {
    TempDir temp;
    fs::path dir = temp.dir / "project";

    ProjectDir(const std::string& project_json,
               const std::vector<std::pair<std::string, std::string>>& scenes) {
        spit(dir / "impulse.json", project_json);
        for (const auto& [folder, name] : scenes) {
            spit(dir / folder / (name + ".json"), slurp(source_scenes / (name + ".json")));
        }
    }
};

std::string project_with(const std::string& rest) {
    return R"({"schema": "impulse/project@1", )" + rest + "}";
}

} // namespace

TEST_CASE("A project's builtin engine under another name blesses and checks from the project "
          "folder and from a subfolder, with no argument",
          "[project]") {
    ProjectDir p(project_with(R"("scenes": ["scenes"], "goldens": "gold",
                                 "engines": [{"name": "reference", "builtin": "impulse"}])"),
                 {{"scenes", "drop-box"}, {"scenes", "glancing"}});
    fs::create_directories(p.dir / "deep" / "er");

    require_exit(run_tool_in(p.dir, {"bless"}), 0);
    // One engine: GOLDENS/NAME.json, the same bytes as this repository's golden
    // of the same scene in the same engine (a golden is the engine's, not the folder's).
    for (const char* name : {"drop-box", "glancing"}) {
        const fs::path golden = p.dir / "gold" / (std::string(name) + ".json");
        REQUIRE(fs::is_regular_file(golden));
        CHECK(slurp(golden) == slurp(source_goldens / (std::string(name) + ".json")));
    }
    CHECK_FALSE(fs::exists(p.dir / "goldens"));

    for (const fs::path& folder : {p.dir, p.dir / "deep" / "er"}) {
        const Outcome checked = run_tool_in(folder, {"check"});
        require_exit(checked, 0);
        CHECK(has(checked.out, "check: 2 scenes"));
        CHECK(has(checked.out, "ok     drop-box"));
        CHECK(has(checked.out, "ok     glancing"));
        // One engine: rows carry no engine name.
        CHECK_FALSE(has(checked.out, "reference/"));
    }
    // A scene named from a subfolder is the project's scene of that name.
    require_exit(run_tool_in(p.dir / "deep", {"check", "glancing"}), 0);
    // --root names the project from anywhere.
    require_exit(run_tool_in(p.temp.dir, {"check", "--root", "project"}), 0);
}

TEST_CASE("Two engines keep their goldens side by side in GOLDENS/ENGINE/NAME.json and each row "
          "names its engine",
          "[project]") {
    ProjectDir p(project_with(R"("scenes": ["scenes"],
                                 "engines": [{"name": "double", "builtin": "impulse"},
                                             {"name": "other", "builtin": "impulse"}])"),
                 {{"scenes", "drop-box"}});
    const Outcome blessed = run_tool_in(p.dir, {"bless"});
    require_exit(blessed, 0);
    CHECK(has(blessed.out, "new        double/drop-box"));
    CHECK(has(blessed.out, "new        other/drop-box"));
    const fs::path a = p.dir / "goldens" / "double" / "drop-box.json";
    const fs::path b = p.dir / "goldens" / "other" / "drop-box.json";
    REQUIRE(fs::is_regular_file(a));
    REQUIRE(fs::is_regular_file(b));
    CHECK(slurp(a) == slurp(b)); // the same engine twice: the same bytes
    CHECK_FALSE(fs::exists(p.dir / "goldens" / "drop-box.json"));

    const Outcome checked = run_tool_in(p.dir, {"check", "--junit", "-"});
    require_exit(checked, 0);
    CHECK(has(checked.out, "name=\"double/drop-box\""));
    CHECK(has(checked.out, "name=\"other/drop-box\""));
    CHECK(has(checked.err, "ok     double/drop-box"));
    CHECK(has(checked.err, "ok     other/drop-box"));

    // --engine picks one; the other's missing golden is then no concern.
    fs::remove(b);
    const Outcome one = run_tool_in(p.dir, {"check", "--engine", "double"});
    require_exit(one, 0);
    CHECK(has(one.out, "1 scene: 1 passed"));
    CHECK_FALSE(has(one.out, "other/"));
    // The missing golden's hint names the engine to regenerate.
    const Outcome missing = run_tool_in(p.dir, {"check"});
    require_exit(missing, 2);
    CHECK(has(missing.out, "ERROR  other/drop-box"));
    CHECK(has(missing.out, "bless it with impulse regen drop-box --engine other"));

    const Outcome unknown = run_tool_in(p.dir, {"check", "--engine", "float"});
    require_exit(unknown, 2);
    CHECK(has(unknown.err, "impulse.json: engines: no engine is named 'float' (--engine); the "
                           "project's engines are double, other"));
    CHECK(unknown.out.empty());
}

TEST_CASE("A project's scenes are folders and glob patterns, and a scene outside them is refused",
          "[project]") {
    ProjectDir p(project_with(R"("scenes": ["scenes/drop-*.json", "more"])"),
                 {{"scenes", "drop-box"},
                  {"scenes", "drop-circle"},
                  {"scenes", "glancing"},
                  {"more", "head-on"}});
    const Outcome blessed = run_tool_in(p.dir, {"bless"});
    require_exit(blessed, 0);
    CHECK(has(blessed.out, "goldens: 3 new"));
    for (const char* name : {"drop-box", "drop-circle", "head-on"}) {
        CHECK(fs::is_regular_file(p.dir / "goldens" / (std::string(name) + ".json")));
    }
    CHECK_FALSE(fs::exists(p.dir / "goldens" / "glancing.json"));
    require_exit(run_tool_in(p.dir / "more", {"check"}), 0);

    // glancing.json sits in scenes/ but no pattern selects it: its golden
    // would be unreferenced, so bless and check refuse it and write nothing.
    const auto before = snapshot(p.temp.dir);
    const std::string outside = (p.dir / "scenes" / "glancing.json").string();
    const std::string sentence =
        "is not one of the project's scenes, so its golden would be unreferenced";
    for (const std::string& argument : {std::string("glancing"), outside}) {
        INFO("argument " << argument);
        const Outcome refused = run_tool_in(p.dir, {"bless", argument});
        require_exit(refused, 2);
        CHECK(has(refused.err, sentence));
        CHECK(has(refused.err, "add its folder to \"scenes\" in"));
        // Said alone, before anything runs: the argument is the mistake.
        CHECK(refused.out.empty());
        CHECK(std::count(refused.err.begin(), refused.err.end(), '\n') == 1);
        const Outcome checked = run_tool_in(p.dir, {"check", argument});
        require_exit(checked, 2);
        CHECK(has(checked.out, "ERROR  glancing"));
        CHECK(has(checked.out, sentence));
    }
    CHECK(snapshot(p.temp.dir) == before);
}

TEST_CASE("A scene file outside the implicit project is refused by bless, not blessed as "
          "new and then called unreferenced",
          "[project]") {
    const TempDir dir;
    const fs::path root = dir.dir / "root";
    spit(root / "harness" / "scenes" / "drop-box.json", slurp(source_scenes / "drop-box.json"));
    spit(dir.dir / "elsewhere" / "glancing.json", slurp(source_scenes / "glancing.json"));
    const auto before = snapshot(dir.dir);
    const Outcome refused = impulse::test::run_tool(
        {"bless", (dir.dir / "elsewhere" / "glancing.json").string(), "--root", root.string()});
    require_exit(refused, 2);
    CHECK(has(refused.err, "glancing.json: is not one of the project's scenes, so its golden "
                           "would be unreferenced"));
    CHECK(has(refused.err, "write an impulse.json whose \"scenes\" lists its folder"));
    CHECK_FALSE(has(refused.out, "unreferenced"));
    CHECK(snapshot(dir.dir) == before);
}

TEST_CASE("Hints name the project's regen command", "[project]") {
    ProjectDir p(project_with(R"("scenes": ["scenes"], "regen": "make goldens")"),
                 {{"scenes", "drop-box"}});
    const Outcome missing = run_tool_in(p.dir, {"check"});
    require_exit(missing, 2);
    CHECK(has(missing.out, "no golden for scene 'drop-box'; bless it with make goldens drop-box"));
    CHECK_FALSE(has(missing.out, "regen-goldens"));

    require_exit(run_tool_in(p.dir, {"bless"}), 0);
    // The scene edited after its blessing: a stale golden, with the same command.
    const fs::path scene = p.dir / "scenes" / "drop-box.json";
    std::string text = slurp(scene);
    const std::string from = "\"description\": \"";
    REQUIRE(text.find(from) != std::string::npos);
    text.insert(text.find(from) + from.size(), "edited: ");
    spit(scene, text);
    const Outcome stale = run_tool_in(p.dir, {"check"});
    require_exit(stale, 1);
    CHECK(has(stale.out, "stale golden: the scene changed since it was blessed; if that was "
                         "intended, run make goldens drop-box"));

    // An orphan golden's hint too.
    spit(p.dir / "goldens" / "ghost.json", slurp(p.dir / "goldens" / "drop-box.json"));
    const Outcome orphan = run_tool_in(p.dir, {"check"}, {"CI=true"});
    CHECK(has(orphan.out, "delete it with make goldens --prune"));

    // Without "regen" the hint is the verb every project has.
    ProjectDir plain(project_with(R"("scenes": ["scenes"])"), {{"scenes", "drop-box"}});
    CHECK(has(run_tool_in(plain.dir, {"check"}).out, "bless it with impulse regen drop-box"));
}

namespace {

// A project file with one mistake: what it is, the file's text, and the
// JSON path and words of the sentence that refuses it.
struct BadProject {
    std::string what, json, path, words;
};

std::vector<BadProject> bad_projects() {
    const std::string engines = R"("scenes": ["scenes"], "engines": )";
    return {
        {"an unknown key", project_with(R"("scenes": ["scenes"], "golden": "g")"), "golden",
         "unknown key (did you mean goldens?)"},
        {"another schema", R"({"schema": "impulse/project@2", "scenes": ["scenes"]})", "schema",
         "must be \"impulse/project@1\", got \"impulse/project@2\""},
        {"no schema", R"({"scenes": ["scenes"]})", "schema", "is required but missing"},
        {"a duplicate key", project_with(R"("scenes": ["scenes"], "scenes": ["scenes"])"), "scenes",
         "appears more than once in the same object"},
        {"no scenes", project_with(R"("goldens": "goldens")"), "scenes", "is required but missing"},
        {"scenes not an array", project_with(R"("scenes": "scenes")"), "scenes",
         "must be an array, got \"scenes\""},
        {"a scene folder outside the project", project_with(R"("scenes": ["../scenes"])"),
         "scenes[0]", "must stay inside the project file's folder (no '..')"},
        {"a '..' in the middle", project_with(R"("scenes": ["scenes/../../x"])"), "scenes[0]",
         "must stay inside the project file's folder (no '..')"},
        {"absolute goldens", project_with(R"("scenes": ["scenes"], "goldens": "/tmp/goldens")"),
         "goldens", "must be relative to the project file's folder"},
        {"goldens in a scenes folder",
         project_with(R"("scenes": ["scenes"], "goldens": "scenes/")"), "goldens",
         "is also a scenes folder"},
        {"goldens differing from a scenes folder only in case",
         project_with(R"("scenes": ["scenes"], "goldens": "Scenes")"), "goldens",
         "and the scenes folder \"scenes\" differ only in case"},
        {"a glob matching nothing", project_with(R"("scenes": ["scenes", "scenes/zz-*.json"])"),
         "scenes[1]", "\"scenes/zz-*.json\" matches no scene file"},
        {"a folder that does not exist", project_with(R"("scenes": ["missing"])"), "scenes[0]",
         "\"missing\" is not a folder"},
        {"a wildcard in the folder part", project_with(R"("scenes": ["sc*/drop-box.json"])"),
         "scenes[0]", "may have wildcards (*, ?, [...]) only in its file-name part"},
        {"a duplicate engine name", project_with(engines + R"([{"name": "a", "builtin": "impulse"},
                                    {"name": "a", "builtin": "impulse"}])"),
         "engines[1].name", "repeats the engine name \"a\""},
        {"an engine without a command",
         project_with(engines + R"([{"name": "mine", "time_limit": 5}])"), "engines[0]",
         "must have exactly one of \"builtin\""},
        {"an empty command", project_with(engines + R"([{"name": "mine", "command": []}])"),
         "engines[0].command", "must name the program to run"},
        {"a command that is not strings",
         project_with(engines + R"([{"name": "mine", "command": ["run", 3]}])"),
         "engines[0].command[1]", "must be a string, got 3"},
        {"a time limit of 0",
         project_with(engines + R"([{"name": "mine", "command": ["x"], "time_limit": 0}])"),
         "engines[0].time_limit", "must be > 0, got 0"},
        {"a negative time limit",
         project_with(engines + R"([{"name": "mine", "command": ["x"], "time_limit": -1}])"),
         "engines[0].time_limit", "must be > 0, got -1"},
        {"a time limit as text",
         project_with(engines + R"([{"name": "mine", "command": ["x"], "time_limit": "60"}])"),
         "engines[0].time_limit", "must be a number, got \"60\""},
        {"an unknown builtin", project_with(engines + R"([{"name": "b", "builtin": "bullet"}])"),
         "engines[0].builtin", "must be \"impulse\", \"box2d\" or \"chipmunk\", got \"bullet\""},
        {"an engine name with a slash",
         project_with(engines + R"([{"name": "a/b", "builtin": "impulse"}])"), "engines[0].name",
         "must be 1 to 64 letters, digits"},
        {"no engines", project_with(engines + "[]"), "engines", "must name at least one engine"},
        {"a skip naming no scene",
         project_with(engines + R"([{"name": "a", "builtin": "impulse", "skip": ["drop-bx"]}])"),
         "engines[0].skip[0]",
         "names no scene of the project: \"drop-bx\" matches no file of \"scenes\""},
        {"a skip as text",
         project_with(engines + R"([{"name": "a", "builtin": "impulse", "skip": "drop-box"}])"),
         "engines[0].skip", "must be an array"},
        {"a skip repeated", project_with(engines + R"([{"name": "a", "builtin": "impulse",
                                                       "skip": ["drop-box", "drop-box"]}])"),
         "engines[0].skip[1]", "repeats the scene name \"drop-box\""},
        {"box2d as text", project_with(R"("scenes": ["scenes"], "box2d": "yes")"), "box2d",
         "must be true or false, got \"yes\""},
        {"an empty regen", project_with(R"("scenes": ["scenes"], "regen": "")"), "regen",
         "must not be empty"},
        // A newline would print a forged row of check's table inside a hint.
        {"a regen of two lines",
         project_with(R"("scenes": ["scenes"], "regen": "make goldens\n  ok     drop  0.001 s")"),
         "regen", "holds the control character 0x0A at byte 12"},
    };
}

} // namespace

TEST_CASE("Every mistake in a project file is exit 2 with the file and the JSON path, and "
          "nothing is written",
          "[project]") {
    for (const BadProject& bad : bad_projects()) {
        INFO("case: " << bad.what);
        ProjectDir p(bad.json, {{"scenes", "drop-box"}});
        fs::create_directories(p.dir / "sub");
        const auto before = snapshot(p.temp.dir);
        const std::string sentence = "impulse.json: " + bad.path + ": " + bad.words;
        for (const std::vector<std::string>& args :
             {std::vector<std::string>{"check"}, std::vector<std::string>{"bless"},
              std::vector<std::string>{"regen"},
              std::vector<std::string>{"run", "../scenes/drop-box.json"}}) {
            INFO("verb: " << args.front());
            const Outcome o = run_tool_in(p.dir / "sub", args);
            require_exit(o, 2);
            CHECK(has(o.err, sentence));
            CHECK(o.err.find('\n') == o.err.size() - 1); // one sentence, one line
            CHECK(o.out.empty());
        }
        CHECK(snapshot(p.temp.dir) == before);
    }
}

TEST_CASE("A skipped scene is a JUnit <skipped/>, counted apart from passes and failures",
          "[project]") {
    using impulse::harness::SceneCheck;
    SceneCheck skipped;
    skipped.name = "drop-box";
    skipped.engine = "mine";
    skipped.status = SceneCheck::Status::skipped;
    skipped.message = "unsupported by mine: polygons are not modelled";
    SceneCheck passed;
    passed.name = "glancing";
    const std::string xml = impulse::harness::junit_xml({skipped, passed});
    CHECK(has(xml, "<testcase classname=\"impulse.gate\" name=\"mine/drop-box\""));
    CHECK(has(xml, "<skipped message=\"unsupported by mine: polygons are not modelled\"/>"));
    CHECK(has(xml, "tests=\"2\" failures=\"0\" errors=\"0\" skipped=\"1\""));
    CHECK_FALSE(has(xml, "<failure"));
    CHECK_FALSE(has(xml, "<error"));
}

// Needs the external-engine side of run_engine (engine_process): hidden until
// it lands, then run with `impulse_tests "[engine-external]"`.
TEST_CASE("An engine that refuses a scene makes a SKIPPED row and check still passes",
          "[engine-external]") {
    ProjectDir p(project_with(R"("scenes": ["scenes"],
                                 "engines": [{"name": "impulse", "builtin": "impulse"},
                                             {"name": "refuser", "command": ["sh", "refuse.sh"],
                                              "time_limit": 10}])"),
                 {{"scenes", "drop-box"}});
    spit(p.dir / "refuse.sh", "echo 'boxes are not modelled' >&2\nexit 3\n");
    const Outcome blessed = run_tool_in(p.dir, {"bless"});
    require_exit(blessed, 0);
    CHECK(has(blessed.out, "skipped    refuser/drop-box: unsupported by refuser: boxes are not "
                           "modelled"));
    CHECK_FALSE(fs::exists(p.dir / "goldens" / "refuser" / "drop-box.json"));

    const Outcome checked = run_tool_in(p.dir, {"check", "--junit", "-"});
    require_exit(checked, 0);
    CHECK(has(checked.err, "SKIPPED refuser/drop-box  unsupported by refuser: boxes are not "
                           "modelled"));
    CHECK(has(checked.err, "2 scenes: 1 passed, 0 failed, 0 errors, 1 skipped"));
    CHECK(has(checked.out, "<skipped message=\"unsupported by refuser: boxes are not modelled\""));

    // Any other failure of the engine is that scene's ERROR, exit 2, naming the engine.
    spit(p.dir / "refuse.sh", "echo 'segfault in narrow phase' >&2\nexit 1\n");
    const Outcome failed = run_tool_in(p.dir, {"check"});
    require_exit(failed, 2);
    CHECK(has(failed.out, "ERROR  refuser/drop-box"));
    CHECK(has(failed.out, "refuser"));
    CHECK(has(failed.out, "segfault in narrow phase"));
}

TEST_CASE("An engine's skip leaves a scene out for it alone: SKIPPED, no golden, check passes",
          "[project]") {
    ProjectDir p(project_with(R"("scenes": ["scenes"],
                                 "engines": [{"name": "all", "builtin": "impulse"},
                                             {"name": "some", "builtin": "impulse",
                                              "skip": ["glancing"]}])"),
                 {{"scenes", "drop-box"}, {"scenes", "glancing"}});
    const Outcome blessed = run_tool_in(p.dir, {"bless"});
    require_exit(blessed, 0);
    CHECK(fs::is_regular_file(p.dir / "goldens" / "all" / "glancing.json"));
    CHECK(fs::is_regular_file(p.dir / "goldens" / "some" / "drop-box.json"));
    CHECK_FALSE(fs::exists(p.dir / "goldens" / "some" / "glancing.json"));
    const Outcome checked = run_tool_in(p.dir, {"check"});
    require_exit(checked, 0);
    CHECK(has(checked.out, "SKIPPED some/glancing  unsupported by some: listed in its \"skip\" "
                           "at impulse.json: engines[1]"));
    CHECK(has(checked.out, "4 scenes: 3 passed, 0 failed, 0 errors, 1 skipped"));
}

TEST_CASE("run and render take the project's first engine or --engine NAME", "[project]") {
    ProjectDir p(project_with(R"("scenes": ["scenes"],
                                 "engines": [{"name": "first", "builtin": "impulse"},
                                             {"name": "second", "builtin": "impulse"}])"),
                 {{"scenes", "drop-box"}});
    fs::create_directories(p.dir / "sub");
    require_exit(run_tool_in(p.dir, {"bless"}), 0);
    // run writes what bless wrote as the first engine's golden.
    const Outcome ran = run_tool_in(p.dir / "sub", {"run", "../scenes/drop-box.json"});
    require_exit(ran, 0);
    CHECK(ran.out == slurp(p.dir / "goldens" / "first" / "drop-box.json"));
    const Outcome second =
        run_tool_in(p.dir / "sub", {"run", "../scenes/drop-box.json", "--engine", "second"});
    require_exit(second, 0);
    CHECK(second.out == slurp(p.dir / "goldens" / "second" / "drop-box.json"));

    for (const std::string& verb : {std::string("run"), std::string("render")}) {
        const Outcome unknown =
            run_tool_in(p.dir, {verb, "scenes/drop-box.json", "--engine", "third"});
        require_exit(unknown, 2);
        CHECK(has(unknown.err, "impulse.json: engines: no engine is named 'third' (--engine)"));
        CHECK(unknown.out.empty());
    }
    // A golden drawn from a subfolder finds its scene's shapes in the project.
    const Outcome drawn = run_tool_in(p.dir / "sub", {"render", "../goldens/first/drop-box.json"});
    require_exit(drawn, 0);
    CHECK(has(drawn.out, "<svg"));
    CHECK_FALSE(has(drawn.err, "drawing paths, contact points and normals only"));
}
