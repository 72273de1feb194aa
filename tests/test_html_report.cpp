// The HTML report as a tool for looking (issue 16): failed scenes first and
// passed ones folded, each failed scene's replay data (golden and new, the
// first divergence, the diverging channels, energy and momentum), the frame
// budget, and data that cannot end the page's script element. The page in a
// real browser is tests/browser/report_in_browser.py (CTest browser.report).
#include "compare.h"
#include "first_divergence.h"
#include "html_report.h"
#include "page_json.h"
#include "replay_data.h"
#include "scene.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

using namespace impulse::harness;

namespace {

const std::string source = IMPULSE_SOURCE_DIR;

SceneCheck passed_check(const std::string& name) {
    SceneCheck check;
    check.name = name;
    check.scene = load_scene(source + "/harness/scenes/" + name + ".json");
    check.gold = read_trajectory_file(source + "/goldens/" + name + ".json", "a golden");
    check.value = check.gold;
    check.comparison = compare(*check.gold, *check.value, std::nullopt);
    return check;
}

// drop-box whose new run has box.y one ULP higher from frame `from` on.
SceneCheck one_ulp_check(std::size_t from) {
    SceneCheck check = passed_check("drop-box");
    const std::size_t y = 2; // columns: t, box.x, box.y, ...
    REQUIRE(check.gold->columns[y] == "box.y");
    for (std::size_t k = from; k < check.value->frames.size(); ++k) {
        double& v = check.value->frames[k][y];
        v = std::nextafter(v, INFINITY);
    }
    check.comparison = compare(*check.gold, *check.value, std::nullopt);
    check.status = SceneCheck::Status::failed;
    check.message = "differs from its golden";
    return check;
}

std::string page_of(const std::vector<SceneCheck>& checks) {
    return html_report_files(checks).back().second;
}

nlohmann::json data_of(const std::string& html, const std::string& stem) {
    const std::string open = "<script type=\"application/json\" id=\"data-" + stem + "\">";
    const std::size_t start = html.find(open);
    REQUIRE(start != std::string::npos);
    const std::size_t end = html.find("</script>", start);
    return nlohmann::json::parse(html.substr(start + open.size(), end - start - open.size()));
}

} // namespace

TEST_CASE("The report page puts failed scenes first and folds the passed ones", "[html-report]") {
    const std::string html = page_of({passed_check("bullet"), one_ulp_check(40)});
    const std::size_t failed = html.find("<section id=\"scene-drop-box\" class=\"failed\">");
    const std::size_t passed = html.find("<section id=\"scene-bullet\" class=\"passed\">");
    REQUIRE(failed != std::string::npos);
    REQUIRE(passed != std::string::npos);
    CHECK(failed < passed);
    // The table lists them in the same order.
    CHECK(html.find("<a href=\"#scene-drop-box\">") < html.find("<a href=\"#scene-bullet\">"));
    // The passed scene sits in a <details> of its own, closed; the failed one does not.
    const std::size_t fold = html.rfind("<details class=\"scene\">", passed);
    REQUIRE(fold != std::string::npos);
    CHECK(fold > failed);
    CHECK(html.find("<details class=\"scene\" open") == std::string::npos);
    // The failed scene has a replay, the passed one none; the script and the
    // error hook are inline (no network).
    CHECK(html.find("<div class=\"replay\" data-source=\"data-drop-box\">") != std::string::npos);
    CHECK(html.find("data-source=\"data-bullet\"") == std::string::npos);
    CHECK(html.find("data-script-errors") != std::string::npos);
    CHECK(html.find("src=") == std::string::npos);
    CHECK(html.find("<link") == std::string::npos);
}

TEST_CASE("A failed scene's first divergence and its cause are said once, as every report says "
          "them",
          "[html-report]") {
    SceneCheck check = one_ulp_check(40);
    const std::optional<FirstDivergence> first = first_divergence_of(*check.comparison);
    REQUIRE(first);
    CHECK(first->divergence.column == "box.y");
    // The gate's message is this sentence when the comparison is all that failed.
    check.message = first_divergence_line(*check.comparison);
    const std::string html = page_of({check});
    const std::size_t cause =
        html.find("<p class=\"cause\"><b>First divergence:</b> box.y at t = ");
    REQUIRE(cause != std::string::npos);
    CHECK(html.find(first->cause, cause) < html.find("</p>", cause));
    CHECK(html.find("<p class=\"message\">") == std::string::npos);
    // Another message (an expectation that failed too) is still shown.
    check.message += "; expectation failed";
    CHECK(page_of({check}).find("<p class=\"message\">") != std::string::npos);
}

TEST_CASE("A failed scene's replay data: golden and new, the first divergence, the channel "
          "difference at full precision, energy from the scene",
          "[html-report]") {
    const std::size_t from = 40;
    const SceneCheck check = one_ulp_check(from);
    const nlohmann::json d = data_of(page_of({check}), "drop-box");
    const std::size_t frames = check.gold->frames.size();
    REQUIRE(d.at("runs").size() == 2);
    CHECK(d["runs"][0]["label"] == "golden");
    CHECK(d["runs"][1]["label"] == "new");
    CHECK(d["runs"][0]["count"] == frames);
    CHECK(d["runs"][0]["t"].size() == frames); // under the budget: every frame
    CHECK(d["runs"][0]["events"].size() == check.gold->events.size());
    // The box (a 1 x 1 polygon) and the ground (static, drawn).
    REQUIRE(d["bodies"].size() == 1);
    CHECK(d["bodies"][0]["name"] == "box");
    CHECK(d["bodies"][0]["v"].size() == 8);
    CHECK(d["statics"].size() == 1);
    // The first divergence is where the nudge starts.
    const double t_from = check.gold->frames[from][0];
    REQUIRE(d["first"].is_object());
    CHECK(d["first"]["column"] == "box.y");
    CHECK(d["first"]["t"].get<double>() == Approx(t_from).epsilon(1e-9));
    // box.y's difference: 0 before the nudge, one ULP of the golden value after.
    REQUIRE(d["channels"]["list"].size() == 1);
    const nlohmann::json& y = d["channels"]["list"][0];
    CHECK(y["name"] == "box.y");
    CHECK(y["diff"][from - 1].get<double>() == 0.0);
    const double gold_y = check.gold->frames[from][2];
    const double ulp = std::nextafter(gold_y, INFINITY) - gold_y;
    CHECK(y["diff"][from].get<double>() == Approx(ulp).epsilon(0.01));
    CHECK(d["channels"]["more"] == 0);
    // Energy at t = 0: the box at rest 1.5 m up, 1 kg, g = 9.81 (the scene's numbers).
    REQUIRE(d["totals"][0].is_object());
    CHECK(d["totals"][0]["E"][0].get<double>() == Approx(1.0 * 9.81 * 1.5));
    CHECK(d["totals"][0]["px"][0].get<double>() == 0.0);
    CHECK(d["totals"][1]["E"].size() == frames);
}

TEST_CASE("A long run is shown at most at the frame budget, keeping the divergence and the last "
          "frame",
          "[html-report]") {
    CHECK(sampled_frames(10, 4, 5) == std::vector<std::size_t>{0, 3, 5, 6, 9});
    CHECK(sampled_frames(10, 20, 5).size() == 10);
    CHECK(sampled_frames(0, 4, 0).empty());
    const std::size_t from = 101; // not a multiple of the stride below
    const SceneCheck check = one_ulp_check(from);
    const std::size_t frames = check.gold->frames.size();
    const std::size_t budget = 40;
    const nlohmann::json d = nlohmann::json::parse(replay_json(check, budget));
    const nlohmann::json& t = d["runs"][0]["t"];
    CHECK(d["runs"][0]["count"] == frames);
    CHECK(t.size() <= budget + 2);
    CHECK(t.size() >= budget - 2);
    CHECK(t.back().get<double>() == Approx(check.gold->frames.back()[0]));
    bool has_divergence = false;
    for (const auto& v : t) {
        has_divergence = has_divergence || v.get<double>() == Approx(check.gold->frames[from][0]);
    }
    CHECK(has_divergence);
}

TEST_CASE("A run of many bodies gets fewer frames, so the page stays a few MB", "[html-report]") {
    CHECK(replay_frames_for(1, replay_frame_budget) == replay_frame_budget);
    // 1000 bodies: 3000 pose numbers a frame, so 600000 / 3000 = 200 frames.
    CHECK(replay_frames_for(1000, replay_frame_budget) == replay_value_budget / 3000);
    CHECK(replay_frames_for(1'000'000, replay_frame_budget) == replay_min_frames);

    SceneCheck check;
    check.name = "crowd";
    Trajectory t;
    t.columns = {"t"};
    const std::size_t bodies = 1000, frames = 300;
    for (std::size_t b = 0; b < bodies; ++b) {
        for (const char* c : {".x", ".y", ".angle", ".vx", ".vy", ".omega"}) {
            t.columns.push_back("b" + std::to_string(b) + c);
        }
    }
    for (std::size_t k = 0; k < frames; ++k) {
        std::vector<double> frame(t.columns.size(), 0.0);
        frame[0] = 0.01 * static_cast<double>(k);
        t.frames.push_back(frame);
    }
    check.gold = t;
    check.value = t;
    const nlohmann::json d = nlohmann::json::parse(replay_json(check));
    CHECK(d["runs"][0]["count"] == frames);
    CHECK(d["runs"][0]["t"].size() <= replay_value_budget / (3 * bodies) + 1);
    CHECK(d["runs"][0]["pose"][0].size() == 3 * bodies);
}

TEST_CASE("Text in the page's data cannot end its script element", "[html-report]") {
    const std::string text = json_string("a</script><b>&\"\\\n");
    CHECK(text.find('<') == std::string::npos);
    CHECK(text.find('>') == std::string::npos);
    CHECK(nlohmann::json::parse(text).get<std::string>() == "a</script><b>&\"\\\n");
    CHECK(json_number(NAN, 6) == "null");
    CHECK(json_number(INFINITY, 6) == "null");
    CHECK(json_numbers({0.5, -2.0}, 6) == "[0.5,-2]");
}
