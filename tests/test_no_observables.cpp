// impulse compare (and impulse box2d) through the real binary: a scene that
// declares no observables had nothing compared, a status of its own apart
// from a pass in the text, the totals, JSON and JUnit.
#include "strict_json.h"
#include "support/files.h"
#include "support/tool.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

using namespace impulse::harness;
using namespace impulse::test;
namespace fs = std::filesystem;

namespace {

const std::string source_root = IMPULSE_SOURCE_DIR;

// Neither shipped scene has a box2d block (harness/scenes), so neither is run.
const std::vector<std::string> nothing_to_compare = {"pile-discs", "stack"};

std::vector<std::string> compare_args(std::vector<std::string> extra) {
    std::vector<std::string> args = {"compare", "pile-discs", "stack",     "--with",
                                     "none",    "--root",     source_root, "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

} // namespace

TEST_CASE("compare: no observables is its own status, counted apart", "[no-observables]") {
    for (const std::string& name : nothing_to_compare) {
        const std::string text = slurp(fs::path(source_root) / "harness/scenes" / (name + ".json"));
        REQUIRE(text.find("\"box2d\"") == std::string::npos);
    }
    SECTION("text: a none row per scene and the totals") {
        const Outcome o = run_tool(compare_args({}));
        INFO(o.err);
        CHECK(o.exit_code == 0); // nothing failed
        CHECK(o.out.find("  none    pile-discs  no observables declared") != std::string::npos);
        CHECK(o.out.find("  none    stack       no observables declared") != std::string::npos);
        CHECK(o.out.find("  ok      ") == std::string::npos);
        CHECK(o.out.find("2 scenes: 0 passed, 0 failed, 2 with no observables\n") !=
              std::string::npos);
    }
    SECTION("JSON: status \"no observables\", passed null") {
        const Outcome o = run_tool(compare_args({"--json"}));
        REQUIRE(o.exit_code == 0);
        const nlohmann::json j = parse_strict_json<nlohmann::json>(o.out, "standard output");
        REQUIRE(j["scenes"].size() == 2);
        for (const nlohmann::json& scene : j["scenes"]) {
            CHECK(scene["status"] == "no observables");
            CHECK(scene["passed"].is_null());
        }
    }
    SECTION("JUnit: <skipped> with the reason") {
        const TempDir tmp;
        const fs::path xml = tmp.dir / "compare.xml";
        const Outcome o = run_tool(compare_args({"--junit", xml.string()}));
        REQUIRE(o.exit_code == 0);
        const std::string text = slurp(xml);
        CHECK(text.find("tests=\"2\" failures=\"0\" errors=\"0\" skipped=\"2\"") !=
              std::string::npos);
        CHECK(text.find("<testcase classname=\"impulse.compare.pile-discs\"") != std::string::npos);
        CHECK(text.find("<skipped message=\"no observables declared") != std::string::npos);
    }
}

#ifdef IMPULSE_WITH_BOX2D
TEST_CASE("box2d: no observables is its own status, counted apart", "[no-observables]") {
    const Outcome o = run_tool({"box2d", "pile-discs", "--root", source_root, "--quiet"});
    INFO(o.err);
    CHECK(o.exit_code == 0);
    CHECK(o.out.find("  none    pile-discs  no observables declared") != std::string::npos);
    CHECK(o.out.find("1 scene: 0 passed, 0 failed, 1 with no observables\n") != std::string::npos);
    const Outcome j = run_tool({"box2d", "pile-discs", "--root", source_root, "--quiet", "--json"});
    REQUIRE(j.exit_code == 0);
    const nlohmann::json doc = parse_strict_json<nlohmann::json>(j.out, "standard output");
    CHECK(doc["scenes"][0]["status"] == "no observables");
    CHECK(doc["scenes"][0]["passed"].is_null());
}
#endif
