// Regeneration is all or nothing (docs/gate-rules.md): when any scene
// refuses to be blessed, `impulse regen` writes no golden, unless --partial,
// which writes the others and names what it leaves inconsistent.
#include "support/files.h"
#include "support/roots.h"
#include "support/tool.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <iterator>
#include <map>
#include <string>

using namespace impulse::test;
namespace fs = std::filesystem;

namespace {

const char* const scene_names[] = {"drop-box", "drop-circle", "glancing"};

struct ThreeScenes {
    TempDir temp;
    fs::path root =
        make_root(temp, {std::begin(scene_names), std::end(scene_names)}, Goldens::none);
    fs::path scene(const std::string& name) const {
        return root / "harness" / "scenes" / (name + ".json");
    }
    fs::path golden(const std::string& name) const { return root / "goldens" / (name + ".json"); }
    std::map<std::string, std::string> goldens() const {
        std::map<std::string, std::string> bytes;
        for (const char* name : scene_names) {
            bytes[name] = slurp(golden(name));
        }
        return bytes;
    }
    // Every golden would change: each scene's text (so its fingerprint)
    // changes. drop-box also expects 60 impacts where the physics gives 6,
    // so it refuses to be blessed.
    void change_scenes() const {
        for (const char* name : scene_names) {
            std::string text = slurp(scene(name));
            const std::string key = "\"description\": \"";
            const std::size_t at = text.find(key);
            REQUIRE(at != std::string::npos);
            text.insert(at + key.size(), "Changed. ");
            if (std::string(name) == "drop-box") {
                const std::string from = "\"impacts\": 6,";
                REQUIRE(text.find(from) != std::string::npos);
                text.replace(text.find(from), from.size(), "\"impacts\": 60,");
            }
            spit(scene(name), text);
        }
    }
};

} // namespace

TEST_CASE("regen writes no golden when one scene of three refuses", "[regen-all-or-nothing]") {
    ThreeScenes p;
    const std::string root = p.root.string();
    REQUIRE(run_tool({"regen", "--root", root}).exit_code == 0);
    const std::map<std::string, std::string> before = p.goldens();
    p.change_scenes();

    const Outcome o = run_tool({"regen", "--root", root});
    INFO(o.out << o.err);
    CHECK(o.exit_code == 1);
    CHECK(p.goldens() == before); // every byte of every golden
    CHECK(o.out.find("REFUSED    drop-box") != std::string::npos);
    CHECK(o.out.find("held back  drop-circle: would be changed") != std::string::npos);
    CHECK(o.out.find("held back  glancing: would be changed") != std::string::npos);
    CHECK(o.out.find("no golden was written: drop-box refuses to be blessed") != std::string::npos);

    SECTION("bless is the same verb") {
        const Outcome b = run_tool({"bless", "--root", root});
        CHECK(b.exit_code == 1);
        CHECK(p.goldens() == before);
    }
    SECTION("--partial writes the two others and names the third") {
        const Outcome partial = run_tool({"regen", "--root", root, "--partial"});
        INFO(partial.out << partial.err);
        CHECK(partial.exit_code == 1);
        const std::map<std::string, std::string> after = p.goldens();
        CHECK(after.at("drop-box") == before.at("drop-box"));
        CHECK(after.at("drop-circle") != before.at("drop-circle"));
        CHECK(after.at("glancing") != before.at("glancing"));
        CHECK(partial.out.find("--partial: 2 goldens were written, but drop-box was not "
                               "regenerated and still holds the old motion") != std::string::npos);
        // The two written goldens are the changed scenes' own: check passes them.
        const Outcome check = run_tool({"check", "--root", root, "drop-circle", "glancing"});
        CHECK(check.exit_code == 0);
    }
    SECTION("--partial on a scene never blessed says it has no golden, not an old one") {
        fs::remove(p.golden("drop-box"));
        const Outcome partial = run_tool({"regen", "--root", root, "--partial"});
        INFO(partial.out << partial.err);
        CHECK(partial.exit_code == 1);
        CHECK_FALSE(fs::exists(p.golden("drop-box")));
        CHECK(partial.out.find("--partial: 2 goldens were written, but drop-box has no golden "
                               "yet") != std::string::npos);
        CHECK(partial.out.find("old motion") == std::string::npos);
    }
}

TEST_CASE("regen writes no golden when one scene of three cannot be loaded",
          "[regen-all-or-nothing]") {
    ThreeScenes p;
    const std::string root = p.root.string();
    REQUIRE(run_tool({"regen", "--root", root}).exit_code == 0);
    const std::map<std::string, std::string> before = p.goldens();
    p.change_scenes();
    spit(p.scene("drop-box"), "{\"schema\": \"impulse/scene@1\",");

    const Outcome o = run_tool({"regen", "--root", root});
    INFO(o.out << o.err);
    CHECK(o.exit_code == 2);
    CHECK(p.goldens() == before);
    // Not "refuses": a scene that could not be loaded broke no expectation.
    CHECK(o.out.find("no golden was written: drop-box could not be loaded or run (its error "
                     "above), and 2 other new or changed goldens were held back; fix it") !=
          std::string::npos);
}
