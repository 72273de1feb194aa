// summary.md fits a pull-request comment (harness/report/summary.h): a
// budget of 60,000 characters, the totals first, the command that accepts
// the change, the long parts folded, failed expectations printed once.
#include "compare.h"
#include "summary.h"
#include "support/bad_input.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

using namespace impulse::harness;
using impulse::test::count_of;

namespace {

// GitHub's limit for a pull-request comment.
constexpr std::size_t comment_limit = 65536;

// A failed scene with a long message and 80 lines of details, as a broken
// engine gives for a scene of many bodies.
SceneCheck failing(int i) {
    SceneCheck check;
    check.name = "scene-" + std::to_string(i);
    check.status = SceneCheck::Status::failed;
    check.regen = "scripts/regen-goldens";
    check.message =
        "first divergence: body" + std::to_string(i) + ".vy at t = 0.5 s " + std::string(300, 'x');
    for (int line = 0; line < 80; ++line) {
        check.details += "  body" + std::to_string(line) + ".vy  t = 0.5  golden 1  new 2  " +
                         std::string(60, 'y') + "\n";
    }
    check.seconds = 0.01;
    return check;
}

} // namespace

TEST_CASE("200 failing scenes still fit a pull-request comment, totals first", "[summary]") {
    std::vector<SceneCheck> checks;
    for (int i = 0; i < 200; ++i) {
        checks.push_back(failing(i));
    }
    SceneCheck passed;
    passed.name = "quiet-scene";
    checks.push_back(passed);

    const std::string md = summary_markdown(checks);
    CHECK(md.size() <= 60000);
    CHECK(md.size() < comment_limit);
    // The totals come first, then the command that accepts the change.
    CHECK(md.rfind("## impulse check\n\n**\u274c 201 scenes: 1 passed, 200 failed, 0 errors**",
                   0) == 0);
    const std::size_t accept = md.find("accept it with `scripts/regen-goldens`");
    REQUIRE(accept != std::string::npos);
    CHECK(accept < md.find("| scene |"));
    CHECK(md.find("`index.html`") < md.find("| scene |"));
    // The first failing scene's row is there; what did not fit is counted.
    CHECK(md.find("| scene-0 |") != std::string::npos);
    CHECK(md.find("<details><summary>scene-0: failed</summary>") != std::string::npos);
    CHECK(md.find("left out to fit a pull-request comment") != std::string::npos);
    // Every <details> that opens closes.
    CHECK(count_of(md, "<details>") == count_of(md, "</details>"));
}

TEST_CASE("Passed scenes are folded after the failed ones", "[summary]") {
    SceneCheck passed;
    passed.name = "aaa-passes";
    std::vector<SceneCheck> checks = {passed, failing(1)};
    const std::string md = summary_markdown(checks);
    CHECK(md.find("| scene-1 |") < md.find("| aaa-passes |"));
    CHECK(md.find("<details><summary>1 scene passed or skipped</summary>") <
          md.find("| aaa-passes |"));
    CHECK(md.find("left out") == std::string::npos); // everything fit
}

TEST_CASE("A failed expectation is printed once", "[summary]") {
    SceneCheck check;
    check.name = "drop-box";
    check.status = SceneCheck::Status::failed;
    check.message = "1 declared expectation failed";
    check.details =
        "failed expectations:\n  expectations[0] drop impact 3: expected 1.25, got 1.5\n";
    const std::string md = summary_markdown({check});
    CHECK(count_of(md, "expected 1.25, got 1.5") == 1);
    CHECK(md.find("accept it with `impulse regen`") != std::string::npos); // no project command
}
