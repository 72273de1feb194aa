// The goldens folder as the disk has it, not only as impulse.json spells it
// (docs/project-file.md, "goldens"): a symbolic link must not turn bless into
// a writer over scene files or --prune into a deleter of the project file,
// and --prune deletes goldens only, never another JSON file left there.
#include "support/files.h"
#include "support/outcome.h"
#include "support/tool.h"
#include "support/tool_in_folder.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

// A project made by init, with the builtin engine, its goldens not yet blessed.
fs::path starter_project(const TempDir& temp) {
    const fs::path dir = temp.dir / "mine";
    require_exit(run_tool({"init", dir.string()}), 0);
    std::string text = slurp(dir / "impulse.json");
    const std::string placeholder =
        R"({"name": "my-engine", "command": ["./my-engine"], "time_limit": 60})";
    REQUIRE(text.find(placeholder) != std::string::npos);
    text.replace(text.find(placeholder), placeholder.size(),
                 R"({"name": "impulse", "builtin": "impulse"})");
    spit(dir / "impulse.json", text);
    return dir;
}

} // namespace

TEST_CASE("a goldens folder that links to a scenes folder, the project or outside is refused",
          "[unit][gate-reliability]") {
    const TempDir temp;
    const fs::path dir = starter_project(temp);
    const std::string scene = slurp(dir / "scenes" / "drop.json");
    const std::string project = slurp(dir / "impulse.json");
    spit(dir / "package.json", "{\"keep\": 1}\n");
    fs::create_directories(temp.dir / "elsewhere");

    struct Case {
        fs::path target;
        std::string words;
    };
    for (const Case& c : {Case{"scenes", "the folder of scenes[0] (through a symbolic link)"},
                          Case{".", "the project's own folder (through a symbolic link)"},
                          Case{temp.dir / "elsewhere", "outside the project's folder"}}) {
        INFO(c.target);
        fs::remove(dir / "goldens");
        fs::create_directory_symlink(c.target, dir / "goldens");
        for (const std::vector<std::string>& args :
             {std::vector<std::string>{"bless", "--prune"},
              std::vector<std::string>{"regen", "--prune"}, std::vector<std::string>{"check"}}) {
            const Outcome o = run_tool_in(dir, args);
            INFO(args.front() << ": " << o.err);
            CHECK(o.exit_code == 2);
            CHECK(o.err.rfind("impulse.json: goldens: \"goldens\" resolves on disk to ", 0) == 0);
            CHECK(has(o.err, c.words));
            CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
        }
        // Nothing was written or deleted anywhere.
        CHECK(slurp(dir / "scenes" / "drop.json") == scene);
        CHECK(slurp(dir / "impulse.json") == project);
        CHECK(fs::exists(dir / "package.json"));
        CHECK(fs::is_empty(temp.dir / "elsewhere"));
    }
}

TEST_CASE("bless --prune deletes unreferenced goldens and leaves other JSON files",
          "[unit][gate-reliability]") {
    const TempDir temp;
    const fs::path dir = starter_project(temp);
    require_exit(run_tool_in(dir, {"bless"}), 0);
    const fs::path goldens = dir / "goldens";
    // A golden whose scene is gone, a note and a copy of a scene.
    fs::copy_file(goldens / "drop.json", goldens / "gone.json");
    spit(goldens / "notes.json", "{\"keep\": 1}\n");
    fs::copy_file(dir / "scenes" / "drop.json", goldens / "backup.json");

    const Outcome listed = run_tool_in(dir, {"bless"});
    INFO(listed.out);
    CHECK(has(listed.out, "unreferenced"));
    CHECK(has(listed.out, "gone.json"));
    CHECK_FALSE(has(listed.out, "notes.json"));
    CHECK_FALSE(has(listed.out, "backup.json"));

    const Outcome pruned = run_tool_in(dir, {"bless", "--prune"});
    INFO(pruned.out << pruned.err);
    CHECK(pruned.exit_code == 0);
    CHECK(has(pruned.out, "1 removed"));
    CHECK_FALSE(fs::exists(goldens / "gone.json"));
    CHECK(fs::exists(goldens / "notes.json"));
    CHECK(fs::exists(goldens / "backup.json"));
    CHECK(fs::exists(goldens / "drop.json"));
}

TEST_CASE("regen writes no golden when one golden's path cannot be written",
          "[unit][gate-reliability]") {
    const TempDir temp;
    const fs::path dir = starter_project(temp);
    const fs::path source = IMPULSE_SOURCE_DIR;
    fs::copy_file(source / "harness" / "scenes" / "head-on.json", dir / "scenes" / "head-on.json");
    require_exit(run_tool_in(dir, {"bless"}), 0);
    const fs::path goldens = dir / "goldens";
    const std::string head_on = slurp(goldens / "head-on.json");
    // Both scenes edited, so both goldens would change; one path is a folder.
    for (const char* name : {"drop.json", "head-on.json"}) {
        std::string text = slurp(dir / "scenes" / name);
        const std::string key = "\"description\": \"";
        REQUIRE(text.find(key) != std::string::npos);
        text.replace(text.find(key), key.size(), key + "edited ");
        spit(dir / "scenes" / name, text);
    }
    fs::remove(goldens / "drop.json");
    fs::create_directory(goldens / "drop.json");

    const Outcome o = run_tool_in(dir, {"regen"});
    INFO(o.out << o.err);
    CHECK(o.exit_code == 2);
    CHECK(has(o.out, "NOT WRITTEN drop"));
    CHECK(has(o.out, "held back  head-on"));
    CHECK(has(o.out, "no golden was written"));
    CHECK(has(o.err, "drop.json: cannot be written (it is a directory"));
    CHECK(slurp(goldens / "head-on.json") == head_on);

    const Outcome partial = run_tool_in(dir, {"regen", "--partial"});
    INFO(partial.out << partial.err);
    CHECK(partial.exit_code == 2);
    CHECK(slurp(goldens / "head-on.json") != head_on);
    CHECK(fs::is_directory(goldens / "drop.json"));
}

TEST_CASE("bless never replaces a read-only golden and keeps a replaced golden's permissions",
          "[unit][gate-reliability]") {
    const TempDir temp;
    const fs::path dir = starter_project(temp);
    require_exit(run_tool_in(dir, {"bless"}), 0);
    const fs::path golden = dir / "goldens" / "drop.json";
    const auto edit_scene = [&dir](const std::string& word) {
        std::string text = slurp(dir / "scenes" / "drop.json");
        const std::string key = "\"description\": \"";
        REQUIRE(text.find(key) != std::string::npos);
        text.replace(text.find(key), key.size(), key + word + " ");
        spit(dir / "scenes" / "drop.json", text);
    };

    // Made read-only by the user: refused, its bytes and mode kept (rename()
    // alone would replace it, since only the folder's permission counts).
    const std::string before = slurp(golden);
    fs::permissions(golden, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
    edit_scene("edited");
    const Outcome refused = run_tool_in(dir, {"bless"});
    INFO(refused.out << refused.err);
    CHECK(refused.exit_code == 2);
    CHECK(has(refused.out, "NOT WRITTEN drop"));
    CHECK(has(refused.err, "drop.json: is read-only; bless does not replace a golden"));
    CHECK(slurp(golden) == before);
    CHECK((fs::status(golden).permissions() & fs::perms::owner_write) == fs::perms::none);

    // Writable with permissions of its own (0640): replaced, the permissions kept.
    const fs::perms shared = fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read;
    fs::permissions(golden, shared);
    const Outcome blessed = run_tool_in(dir, {"bless"});
    INFO(blessed.out << blessed.err);
    CHECK(blessed.exit_code == 0);
    CHECK(has(blessed.out, "changed    drop"));
    CHECK(slurp(golden) != before);
    CHECK((fs::status(golden).permissions() & fs::perms::all) == shared);
}
