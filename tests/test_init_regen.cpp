// `impulse init` (a starter project) and `impulse regen` (the goldens of the
// project found from the current folder), through the real binary.
#include "support/bad_input.h"
#include "support/files.h"
#include "support/outcome.h"
#include "support/tool.h"
#include "support/tool_in_folder.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

// What init's next steps tell a user who wants to try the gate before
// wiring their engine: the placeholder engine becomes the builtin one.
void use_builtin_engine(const fs::path& project_file) {
    std::string text = slurp(project_file);
    const std::string placeholder =
        R"({"name": "my-engine", "command": ["./my-engine"], "time_limit": 60})";
    const std::size_t at = text.find(placeholder);
    REQUIRE(at != std::string::npos);
    text.replace(at, placeholder.size(), R"({"name": "impulse", "builtin": "impulse"})");
    spit(project_file, text);
}

// A project made by init with the builtin engine and its goldens blessed.
struct BlessedProject {
    TempDir temp;
    fs::path dir = temp.dir / "mine";
    BlessedProject() {
        require_exit(impulse::test::run_tool({"init", dir.string()}), 0);
        use_builtin_engine(dir / "impulse.json");
        require_exit(run_tool_in(dir, {"bless"}), 0);
        fs::create_directories(dir / "src" / "physics");
    }
};

} // namespace

TEST_CASE("init writes a project file and an example scene that bless and check then accept",
          "[init-regen]") {
    const TempDir temp;
    const fs::path dir = temp.dir / "new-project";
    const Outcome init = impulse::test::run_tool({"init", dir.string()});
    require_exit(init, 0);
    const fs::path project_file = dir / "impulse.json", scene = dir / "scenes" / "drop.json";
    REQUIRE(fs::is_regular_file(project_file));
    REQUIRE(fs::is_regular_file(scene));
    CHECK(std::distance(fs::directory_iterator(dir / "scenes"), fs::directory_iterator()) == 1);
    // The placeholder command is explained on standard output, since JSON cannot.
    CHECK(has(init.out, "engines[0].command"));
    CHECK(has(init.out, "docs/engine-protocol.md"));
    CHECK(has(init.out, "impulse bless"));
    CHECK(has(init.out, "impulse regen"));

    // As written, the placeholder engine is one sentence naming where its
    // command is written, before any scene runs.
    const Outcome placeholder = run_tool_in(dir, {"check"});
    require_exit(placeholder, 2);
    CHECK(has(placeholder.err, "impulse.json: engines[0].command[0]: cannot start './my-engine'"));
    CHECK(has(placeholder.err, "engine 'my-engine'"));

    // With an engine that runs, the example's exact answer holds: bless
    // accepts it (a run breaking the scene's expectation is refused, exit 1).
    use_builtin_engine(project_file);
    const Outcome blessed = run_tool_in(dir, {"bless"});
    require_exit(blessed, 0);
    CHECK(has(blessed.out, "new        drop"));
    CHECK(fs::is_regular_file(dir / "goldens" / "drop.json"));
    const Outcome checked = run_tool_in(dir, {"check"});
    require_exit(checked, 0);
    CHECK(has(checked.out, "1 scene: 1 passed, 0 failed, 0 errors"));

    // The starter names Box2D observables, so the comparison compares
    // something: its tolerances (2 dt in time, about 3.6 |g| dt in speed)
    // hold Box2D 2.4.1's lag of one to two steps.
    const Outcome box2d = run_tool_in(dir, {"box2d"});
    require_exit(box2d, 0);
    CHECK(has(box2d.out, "impact 1 time of 'ball'"));
    CHECK(has(box2d.out, "apex 2 / apex 1 of 'ball'"));
    CHECK(has(box2d.out, "all 8 rows within tolerance"));
}

TEST_CASE("init refuses to overwrite either file and writes nothing", "[init-regen]") {
    const TempDir temp;
    SECTION("a project file exists") {
        spit(temp.dir / "impulse.json", "{\"mine\": true}\n");
    }
    SECTION("the example scene exists") {
        spit(temp.dir / "scenes" / "drop.json", "my own drop\n");
    }
    const auto before = snapshot(temp.dir);
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"init", temp.dir.string()}, std::vector<std::string>{"init"}}) {
        const Outcome o =
            args.size() == 2 ? impulse::test::run_tool(args) : run_tool_in(temp.dir, args);
        require_exit(o, 2);
        CHECK(has(o.err, "already exists; impulse init writes a new project and never "
                         "overwrites one"));
        CHECK(o.out.empty());
        CHECK(snapshot(temp.dir) == before);
    }
}

TEST_CASE("init says why scenes/ cannot be made when a dangling link is in its way",
          "[init-regen]") {
    const TempDir temp;
    fs::create_directory_symlink(temp.dir / "nowhere", temp.dir / "scenes");
    const Outcome o = run_tool_in(temp.dir, {"init"});
    require_exit(o, 2);
    CHECK(o.err == "./scenes: cannot be made (a symbolic link to a folder that does not exist is "
                   "in the way)\n");
    CHECK(fs::is_symlink(temp.dir / "scenes"));
    CHECK_FALSE(fs::exists(temp.dir / "impulse.json"));
}

TEST_CASE("regen from a subfolder regenerates the goldens of the project found upwards",
          "[init-regen]") {
    BlessedProject p;
    const fs::path golden = p.dir / "goldens" / "drop.json";
    const std::string blessed = slurp(golden);
    const fs::path sub = p.dir / "src" / "physics";

    // A lost golden is written again, byte for byte, from two folders down.
    fs::remove(golden);
    const Outcome named = run_tool_in(sub, {"regen", "drop"});
    require_exit(named, 0);
    CHECK(has(named.out, "new        drop -> ../../goldens/drop.json"));
    CHECK(slurp(golden) == blessed);

    // A scene path is relative to the caller's folder.
    const Outcome by_path = run_tool_in(sub, {"regen", "../../scenes/drop.json"});
    require_exit(by_path, 0);
    CHECK(has(by_path.out, "unchanged  drop"));
    // Named twice, by name and by path: one scene, one golden.
    const Outcome twice = run_tool_in(sub, {"regen", "drop", "../../scenes/../scenes/drop.json"});
    require_exit(twice, 0);
    CHECK(has(twice.out, "goldens: 0 new, 0 changed, 1 unchanged"));

    // --prune from the subfolder removes a golden with no scene.
    spit(p.dir / "goldens" / "ghost.json", blessed);
    const Outcome pruned = run_tool_in(sub, {"regen", "--prune"});
    require_exit(pruned, 0);
    CHECK(has(pruned.out, "removed    ../../goldens/ghost.json"));
    CHECK_FALSE(fs::exists(p.dir / "goldens" / "ghost.json"));
    CHECK(slurp(golden) == blessed);

    // --root . is the caller's folder: no project file and no harness/scenes there.
    const Outcome here = run_tool_in(sub, {"regen", "--root", "."});
    require_exit(here, 2);
    CHECK(has(here.err, "harness/scenes: no scene folder here"));

    // A --root that is not there, or is a file, is said as such.
    const Outcome missing = run_tool_in(sub, {"check", "--root", "no-such-folder"});
    require_exit(missing, 2);
    CHECK(missing.err == "no-such-folder: --root: does not exist; give the project's folder\n");
    const Outcome file = run_tool_in(p.dir, {"check", "--root", "impulse.json"});
    require_exit(file, 2);
    CHECK(file.err == "impulse.json: --root: is not a folder; give the project's folder\n");
}

TEST_CASE("regen changes a golden after an intended change and is refused in CI mode",
          "[init-regen]") {
    BlessedProject p;
    const fs::path golden = p.dir / "goldens" / "drop.json";
    const std::string before = slurp(golden);
    // An intended change: a slower time step moves the motion, check fails, regen accepts it.
    const fs::path scene = p.dir / "scenes" / "drop.json";
    std::string text = slurp(scene);
    const std::string dt = "\"dt\": 0.01,";
    REQUIRE(text.find(dt) != std::string::npos);
    text.replace(text.find(dt), dt.size(), "\"dt\": 0.005,");
    spit(scene, text);
    require_exit(run_tool_in(p.dir / "src", {"check"}), 1);

    const Outcome refused = run_tool_in(p.dir / "src", {"regen"}, {"CI=true"});
    require_exit(refused, 2);
    CHECK(has(refused.err, "impulse regen: refusing to write goldens in CI mode"));
    CHECK(slurp(golden) == before);

    const Outcome changed = run_tool_in(p.dir / "src", {"regen"});
    require_exit(changed, 0);
    CHECK(has(changed.out, "changed    drop -> ../goldens/drop.json"));
    CHECK(slurp(golden) != before);
    require_exit(run_tool_in(p.dir / "src", {"check"}), 0);
}

TEST_CASE("regen names a golden's changed solver settings, even when the numbers are identical",
          "[init-regen]") {
    BlessedProject p;
    const fs::path golden = p.dir / "goldens" / "drop.json";
    // The golden says it ran with another contact tolerance: check fails on
    // it, so regen must say what it rewrites, not "identical".
    std::string text = slurp(golden);
    const std::string tolerance = "\"contact_tolerance\": 1e-09";
    REQUIRE(text.find(tolerance) != std::string::npos);
    text.replace(text.find(tolerance), tolerance.size(), "\"contact_tolerance\": 1e-06");
    spit(golden, text);
    require_exit(run_tool_in(p.dir, {"check"}), 1);
    const Outcome changed = run_tool_in(p.dir, {"regen"});
    require_exit(changed, 0);
    INFO(changed.out);
    CHECK(has(changed.out, "changed    drop"));
    CHECK(has(changed.out, "contact_tolerance"));
    CHECK(has(changed.out, "the numbers are identical"));
    require_exit(run_tool_in(p.dir, {"check"}), 0);
}

TEST_CASE("init --engine-command names the user's engine in the project file, or writes nothing",
          "[init-regen]") {
    TempDir temp;
    const fs::path dir = temp.dir / "mine";
    const Outcome o = impulse::test::run_tool(
        {"init", dir.string(), "--engine", "seed", "--engine-command", "python3 engine/run.py"});
    require_exit(o, 0);
    CHECK(has(slurp(dir / "impulse.json"),
              R"({"name": "seed", "command": ["python3", "engine/run.py"], "time_limit": 60})"));
    CHECK(has(o.out, "impulse conform"));

    // A word with a space is quoted as in a shell and kept whole.
    const fs::path spaced = temp.dir / "spaced";
    require_exit(impulse::test::run_tool({"init", spaced.string(), "--engine-command",
                                          "python3 'my engine/run.py' --fast"}),
                 0);
    CHECK(has(slurp(spaced / "impulse.json"),
              R"("command": ["python3", "my engine/run.py", "--fast"])"));

    // A name the project file refuses is refused by init, and nothing is left.
    const fs::path other = temp.dir / "other";
    fs::create_directories(other);
    const Outcome bad = impulse::test::run_tool(
        {"init", other.string(), "--engine", "my seed", "--engine-command", "python3 run.py"});
    require_exit(bad, 2);
    CHECK(has(bad.err, "engines[0].name"));
    CHECK(fs::is_empty(other));

    // Into folders that do not exist yet: every folder init made is taken
    // back (an outside review found a/ and a/b/scenes/ left behind), and an
    // empty or unclosed --engine-command is refused before any is made.
    const fs::path deep = temp.dir / "new" / "a" / "b";
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"init", deep.string(), "--engine", "my seed"},
          std::vector<std::string>{"init", deep.string(), "--engine-command", "  "},
          std::vector<std::string>{"init", deep.string(), "--engine-command", "node 'a b"}}) {
        const Outcome refused = impulse::test::run_tool(args);
        INFO(refused.err);
        require_exit(refused, 2);
        CHECK_FALSE(fs::exists(temp.dir / "new"));
    }
}
