// Pictures and reports: the SVG renderer, JUnit XML, the Markdown summary,
// the HTML report and the `impulse render` verb.
#include "atomic_file.h"
#include "cli.h"
#include "input_error.h"
#include "markup.h"
#include "render.h"
#include "report.h"
#include "run.h"
#include "scene.h"
#include "support/files.h"
#include "tracks.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::harness;
using impulse::test::slurp;

namespace {

// Two dynamic bodies over a wide ground: a tilted box starting high on the
// left and a spinning ball starting low on the right. Both land.
constexpr const char* two_bodies_scene = R"({
  "schema": "impulse/scene@1",
  "name": "render-test",
  "description": "A box & a ball <dropped> onto \"ground\"",
  "restitution": 0.5,
  "dt": 0.01,
  "duration": 1.5,
  "bodies": [
    {"name": "ground", "static": true, "shape": {"box": [20, 0.5]}, "position": [0, -0.5]},
    {"name": "high", "shape": {"box": [0.5, 0.25]}, "mass": 1, "position": [-2, 3], "angle": 0.3},
    {"name": "low", "shape": {"circle": 0.4}, "mass": 1, "position": [2, 1], "angular_velocity": 2}
  ]
})";

Scene test_scene() {
    return parse_scene(two_bodies_scene, "render-test.json");
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t i = text.find(what); i != std::string::npos; i = text.find(what, i + 1)) {
        ++n;
    }
    return n;
}

// Every start tag closed by its own end tag, in order; <?...?> and <!...> skipped.
bool balanced(const std::string& xml) {
    std::vector<std::string> open;
    std::size_t i = 0;
    while ((i = xml.find('<', i)) != std::string::npos) {
        const std::size_t end = xml.find('>', i);
        if (end == std::string::npos) {
            return false;
        }
        const std::string tag = xml.substr(i + 1, end - i - 1);
        i = end + 1;
        if (tag.empty()) {
            return false;
        }
        if (tag[0] == '?' || tag[0] == '!') {
            continue;
        }
        if (tag[0] == '/') {
            if (open.empty() || open.back() != tag.substr(1)) {
                return false;
            }
            open.pop_back();
            continue;
        }
        if (tag.back() == '/') {
            continue;
        }
        open.push_back(tag.substr(0, tag.find_first_of(" \t\n")));
    }
    return open.empty();
}

bool well_formed_svg(const std::string& svg) {
    return svg.rfind("<svg", 0) == 0 && svg.size() >= 7 &&
           svg.compare(svg.size() - 7, 7, "</svg>\n") == 0 && balanced(svg);
}

// The first point of the polyline with this class and body.
std::pair<double, double> first_point(const std::string& svg, const std::string& cls,
                                      const std::string& body) {
    const std::string head = "<polyline class=\"" + cls + "\" data-body=\"" + body + "\"";
    const std::size_t at = svg.find(head);
    REQUIRE(at != std::string::npos);
    const std::size_t points = svg.find("points=\"", at) + 8;
    std::istringstream in(svg.substr(points, svg.find('"', points) - points));
    double x = 0.0, y = 0.0;
    char comma = 0;
    in >> x >> comma >> y;
    return {x, y};
}

fs::path temp_path(const std::string& name) {
    return fs::temp_directory_path() /
           ("impulse-render-" + std::to_string(::getpid()) + "-" + name);
}

// The repository's drop scene (drop.json, or drop-box.json where it was renamed).
std::string drop_scene_path() {
    const std::string scenes = std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes/";
    return fs::exists(scenes + "drop.json") ? scenes + "drop.json" : scenes + "drop-box.json";
}

// A copy of the run with every value after frame 50 nudged, and a comparison
// saying so (built by hand: this file tests pictures, not compare()).
struct Perturbed {
    Trajectory value;
    Comparison comparison;
};

Perturbed perturbed(const Trajectory& gold) {
    Perturbed p{gold, {}};
    for (std::size_t k = 50; k < p.value.frames.size(); ++k) {
        for (std::size_t j = 1; j < p.value.frames[k].size(); ++j) {
            p.value.frames[k][j] += 1e-7 * static_cast<double>(k - 49);
        }
    }
    p.comparison.identical = false;
    p.comparison.passed = false;
    Divergence d;
    d.column = gold.columns[2]; // high.y
    d.channel = Channel::position;
    d.frame = 50;
    d.t = gold.frames[50][0];
    d.gold = gold.frames[50][2];
    d.value = p.value.frames[50][2];
    d.abs_diff = 1e-7;
    d.rel_diff = 1e-7;
    d.ulp = 12345;
    p.comparison.first_divergences.push_back(d);
    return p;
}

} // namespace

TEST_CASE("render_svg draws every body's path, every event, deterministically", "[render]") {
    const Scene scene = test_scene();
    const Trajectory trajectory = run_scene(scene);
    REQUIRE(!trajectory.events.empty());

    const std::string svg = render_svg(scene, trajectory);
    CHECK(well_formed_svg(svg));
    CHECK(render_svg(scene, trajectory) == svg);

    CHECK(count(svg, "class=\"path\"") == 2);
    CHECK(count(svg, "class=\"contact\"") == trajectory.events.size());
    CHECK(count(svg, "class=\"normal\"") == trajectory.events.size());
    CHECK(count(svg, "class=\"static\"") == 1);
    // First, last and evenly spaced frames between them: 8 outlines per body.
    CHECK(count(svg, "<polygon class=\"outline\" data-body=\"high\"") == 8);
    CHECK(count(svg, "<g class=\"outline\" data-body=\"low\"") == 8);

    // Title, description (escaped) and legend.
    CHECK(svg.find(">render-test</text>") != std::string::npos);
    CHECK(svg.find("A box &amp; a ball &lt;dropped&gt; onto &quot;ground&quot;") !=
          std::string::npos);
    CHECK(svg.find(">contact point</text>") != std::string::npos);
    CHECK(svg.find(">high</text>") != std::string::npos);
    CHECK(svg.find(">low</text>") != std::string::npos);

    // y points up in the world and down in the picture.
    const auto high = first_point(svg, "path", "high");
    const auto low = first_point(svg, "path", "low");
    CHECK(high.second < low.second);
    CHECK(high.first < low.first);
}

TEST_CASE("The 50 m ground is clipped to the region where things move", "[render]") {
    const Scene scene = load_scene(drop_scene_path());
    const std::string svg = render_svg(scene, run_scene(scene));
    CHECK(well_formed_svg(svg));
    // The picture's width stays modest and the ground's polygon stays inside it.
    const std::size_t at = svg.find("<polygon class=\"static\"");
    REQUIRE(at != std::string::npos);
    const std::size_t points = svg.find("points=\"", at) + 8;
    std::istringstream in(svg.substr(points, svg.find('"', points) - points));
    double x = 0.0, y = 0.0;
    char comma = 0;
    while (in >> x >> comma >> y) {
        CHECK(x >= 0.0);
        CHECK(x <= 1000.0);
    }
}

TEST_CASE("render_svg without a scene draws paths, contacts and normals", "[render]") {
    const Trajectory trajectory = run_scene(test_scene());
    const std::string svg = render_svg(trajectory);
    CHECK(well_formed_svg(svg));
    CHECK(render_svg(trajectory) == svg);
    CHECK(count(svg, "class=\"path\"") == 2);
    CHECK(count(svg, "class=\"contact\"") == trajectory.events.size());
    CHECK(count(svg, "class=\"normal\"") == trajectory.events.size());
    CHECK(count(svg, "class=\"static\"") == 0);
    CHECK(first_point(svg, "path", "high").second < first_point(svg, "path", "low").second);
}

TEST_CASE("render_comparison_svg overlays golden and new paths and plots the error", "[render]") {
    const Scene scene = test_scene();
    const Trajectory gold = run_scene(scene);
    const Perturbed p = perturbed(gold);

    for (const Scene* s : {&scene, static_cast<const Scene*>(nullptr)}) {
        const std::string svg = render_comparison_svg(s, gold, p.value, p.comparison);
        CHECK(well_formed_svg(svg));
        CHECK(render_comparison_svg(s, gold, p.value, p.comparison) == svg);
        CHECK(count(svg, "class=\"path gold\"") == 2);
        CHECK(count(svg, "class=\"path new\"") == 2);
        CHECK(count(svg, "class=\"contact gold\"") == gold.events.size());
        CHECK(count(svg, "class=\"contact new\"") == p.value.events.size());
        CHECK(count(svg, "class=\"divergence\"") == 1);
        CHECK(count(svg, "class=\"divergence-time\"") == 1);
        CHECK(count(svg, "<polyline class=\"error\"") == 4);
        for (const char* channel : {"position", "angle", "velocity", "angular_velocity"}) {
            CHECK(svg.find("data-channel=\"" + std::string(channel) + "\"") != std::string::npos);
        }
        CHECK(svg.find("1e-18") != std::string::npos); // the floor, and the note saying so
        CHECK(svg.find("high.y") != std::string::npos);
        CHECK(svg.find("t (s)") != std::string::npos);
        if (s != nullptr) { // the outlines say when they were drawn: the golden's last frame
            // The legend wraps its notes, so the time follows on a later line.
            const std::size_t note = svg.find("Outlines at the last frame");
            REQUIRE(note != std::string::npos);
            const std::size_t at = svg.find("t\u00a0=\u00a0", note); // no-break spaces
            REQUIRE(at != std::string::npos);
            CHECK(at - note < 200);
            CHECK(std::stod(svg.substr(at + 6)) == Approx(gold.frames.back()[0]).epsilon(1e-3));
        }
    }

    // Identical runs: nothing to mark.
    Comparison same;
    const std::string svg = render_comparison_svg(&scene, gold, gold, same);
    CHECK(well_formed_svg(svg));
    CHECK(count(svg, "class=\"divergence\"") == 0);
    CHECK(svg.find("bit for bit") != std::string::npos);
}

TEST_CASE("xml_escape escapes markup and replaces what XML 1.0 forbids", "[render]") {
    CHECK(xml_escape("a<b&c\"d'e>f") == "a&lt;b&amp;c&quot;d&apos;e&gt;f");
    CHECK(xml_escape(std::string("x\x01y\x1b[0mz")) == "x\xEF\xBF\xBDy\xEF\xBF\xBD[0mz");
    CHECK(xml_escape(std::string("nul\0!", 5)) == "nul\xEF\xBF\xBD!");
    CHECK(xml_escape("line\nnext\ttab") == "line\nnext\ttab");
    CHECK(xml_escape("line\nnext\ttab\r", true) == "line&#10;next&#9;tab&#13;");
    CHECK(xml_escape("caf\xC3\xA9 \xE2\x88\x92") == "caf\xC3\xA9 \xE2\x88\x92"); // UTF-8 kept
    CHECK(xml_escape("bad \xFF\xC3") == "bad \xEF\xBF\xBD\xEF\xBF\xBD");
    CHECK(xml_escape("\xEF\xBF\xBF") == "\xEF\xBF\xBD"); // U+FFFF is not an XML character
}

namespace {

std::vector<SceneCheck> sample_checks() {
    const Scene scene = test_scene();
    const Trajectory gold = run_scene(scene);
    const Perturbed p = perturbed(gold);

    SceneCheck passed;
    passed.name = "render-test";
    passed.scene_file = "harness/scenes/render-test.json";
    passed.golden_file = "goldens/render-test.json";
    passed.comparison = Comparison{};
    passed.scene = scene;
    passed.gold = gold;
    passed.value = gold;
    passed.seconds = 0.0125;

    SceneCheck failed;
    failed.name = "mismatch";
    failed.scene_file = "harness/scenes/mismatch.json";
    failed.golden_file = "goldens/mismatch.json";
    failed.status = SceneCheck::Status::failed;
    failed.message = "differs from <its> golden & \"more\"\x01";
    failed.details = "first divergence: high.y at t = 0.5\n  golden 1\n  new 2 ```\n";
    failed.comparison = p.comparison;
    failed.scene = scene;
    failed.gold = gold;
    failed.value = p.value;
    failed.seconds = 0.25;

    SceneCheck error;
    error.name = "broken";
    error.scene_file = "harness/scenes/broken.json";
    error.golden_file = "goldens/broken.json";
    error.status = SceneCheck::Status::error;
    error.message = "goldens/broken.json: has a merge-conflict marker at line 3";
    error.seconds = 0.001;
    return {passed, failed, error};
}

} // namespace

TEST_CASE("junit_xml: one testcase per scene, failure for mismatches, error for bad input",
          "[render]") {
    const std::string xml = junit_xml(sample_checks());
    CHECK(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>", 0) == 0);
    CHECK(balanced(xml));
    CHECK(xml.find("<testsuite name=\"impulse.gate\" tests=\"3\" failures=\"1\" errors=\"1\"") !=
          std::string::npos);
    CHECK(count(xml, "<testcase classname=\"impulse.gate\"") == 3);
    CHECK(xml.find("name=\"render-test\" time=\"0.013\"/>") != std::string::npos);
    CHECK(count(xml, "<failure ") == 1);
    CHECK(count(xml, "<error ") == 1);
    CHECK(xml.find("<failure message=\"differs from &lt;its&gt; golden &amp; "
                   "&quot;more&quot;\xEF\xBF\xBD\" type=\"physics mismatch\">") !=
          std::string::npos);
    CHECK(xml.find("<error message=\"goldens/broken.json: has a merge-conflict marker at line "
                   "3\" type=\"input error\"") != std::string::npos);
    CHECK(xml.find('\x01') == std::string::npos);
    CHECK(xml.find("first divergence: high.y at t = 0.5\n  golden 1") != std::string::npos);
    // The failure comes inside its own testcase.
    const std::size_t failure = xml.find("<failure ");
    CHECK(xml.rfind("name=\"mismatch\"", failure) != std::string::npos);
    CHECK(xml.rfind("name=\"broken\"", failure) == std::string::npos);

    const std::string empty = junit_xml({});
    CHECK(balanced(empty));
    CHECK(empty.find("tests=\"0\" failures=\"0\" errors=\"0\"") != std::string::npos);
}

TEST_CASE("summary_markdown: verdict, one table row per scene, details of failures", "[render]") {
    const std::string md = summary_markdown(sample_checks());
    CHECK(md.rfind("## ", 0) == 0);
    CHECK(md.find("3 scenes: 1 passed, 1 failed, 1 error") != std::string::npos);
    CHECK(md.find("| scene | result | first divergence or message | time |") != std::string::npos);
    CHECK(md.find("| render-test | \u2705 passed | bit-identical to the golden | 0.013 s |") !=
          std::string::npos);
    // The failed scene's row names its first divergence.
    const std::size_t row = md.find("| mismatch | \u274c failed | high.y at t = ");
    REQUIRE(row != std::string::npos);
    CHECK(md.find("12345 ULP", row) != std::string::npos);
    CHECK(md.find("| broken | \u26a0\ufe0f error | goldens/broken.json: has a merge-conflict") !=
          std::string::npos);
    // Details in a fence longer than the backticks inside them.
    CHECK(md.find("````text\nfirst divergence: high.y at t = 0.5\n") != std::string::npos);
    // Each failure's details folded under its name; a passed scene has none.
    CHECK(md.find("<details><summary>mismatch: failed</summary>") != std::string::npos);
    CHECK(md.find("<details><summary>render-test") == std::string::npos);
    CHECK(md.find('\x01') == std::string::npos);
    CHECK(summary_markdown({}).find("0 scenes") != std::string::npos);
}

TEST_CASE("write_report writes summary.md, index.html and the failed scenes' SVGs", "[render]") {
    const fs::path dir = temp_path("report") / "nested";
    fs::remove_all(dir.parent_path());
    const std::vector<SceneCheck> checks = sample_checks();
    write_report(dir.string(), checks);

    CHECK(slurp(dir / "summary.md") == summary_markdown(checks));
    const std::string html = slurp(dir / "index.html");
    CHECK(html.rfind("<!DOCTYPE html>", 0) == 0);
    CHECK(html.find("<style>") != std::string::npos);
    CHECK(count(html, "<section ") == 3);
    CHECK(html.find("id=\"scene-mismatch\" class=\"failed\"") != std::string::npos);
    CHECK(html.find("differs from &lt;its&gt; golden") != std::string::npos);
    CHECK(html.find("<pre>first divergence: high.y") != std::string::npos);
    // Golden vs new for the failed scene, the plain picture for the passing one.
    CHECK(count(html, "class=\"path gold\"") == 2);
    CHECK(count(html, "<polyline class=\"path\"") == 2);
    const std::string svg = slurp(dir / "mismatch.svg");
    CHECK(well_formed_svg(svg));
    CHECK(svg.find("class=\"divergence\"") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "render-test.svg"));
    CHECK_FALSE(fs::exists(dir / "broken.svg"));

    // Same checks, same bytes.
    const std::string first = html;
    write_report(dir.string(), checks);
    CHECK(slurp(dir / "index.html") == first);
    fs::remove_all(dir.parent_path());
}

TEST_CASE("write_report draws golden vs new for a stale golden that was not compared", "[render]") {
    std::vector<SceneCheck> checks = sample_checks();
    SceneCheck stale = checks[1];
    stale.name = "stale";
    stale.stale = true;
    stale.comparison.reset();
    stale.message = "goldens/stale.json: is stale: its scene_sha256 differs from the scene's";
    const fs::path dir = temp_path("stale-report");
    write_report(dir.string(), {stale});
    const std::string svg = slurp(dir / "stale.svg");
    CHECK(well_formed_svg(svg));
    CHECK(count(svg, "class=\"path gold\"") == 2);
    CHECK(svg.find("Differs from the golden.") != std::string::npos);
    CHECK(junit_xml({stale}).find("type=\"stale golden\"") != std::string::npos);
    CHECK(summary_markdown({stale}).find("\u274c failed (stale golden)") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("write_report names the path it cannot create", "[render]") {
    const fs::path file = temp_path("not-a-dir");
    std::ofstream(file) << "x";
    const std::string dir = (file / "report").string();
    CHECK_THROWS_AS(write_report(dir, sample_checks()), InputError);
    try {
        write_report(dir, std::vector<SceneCheck>{});
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find(dir) != std::string::npos);
    }
    fs::remove(file);
}

TEST_CASE("impulse render draws a scene and a trajectory", "[render]") {
    using impulse::harness::cli::render_verb;
    const std::string scene_file = drop_scene_path();

    SECTION("a scene, to standard output and to --out") {
        std::ostringstream out, err;
        REQUIRE(render_verb({scene_file}, out, err) == 0);
        CHECK(well_formed_svg(out.str()));
        CHECK(count(out.str(), "class=\"path\"") == 1);
        CHECK(count(out.str(), "class=\"static\"") == 1);

        const fs::path svg = temp_path("drop.svg");
        std::ostringstream out2, err2;
        REQUIRE(render_verb({scene_file, "--out", svg.string()}, out2, err2) == 0);
        CHECK(out2.str().empty());
        CHECK(slurp(svg) == out.str());
        fs::remove(svg);
    }

    SECTION("a trajectory: with the scene's shapes when --root has the same scene") {
        const Scene scene = load_scene(scene_file);
        Trajectory trajectory = run_scene(scene);
        const fs::path file = temp_path("drop.trajectory.json");
        write_file_atomically(file.string(), write_trajectory(trajectory));

        std::ostringstream out, err;
        REQUIRE(render_verb({file.string(), "--root", IMPULSE_SOURCE_DIR}, out, err) == 0);
        CHECK(err.str().empty());
        CHECK(out.str() == render_svg(scene, trajectory));

        // No scene under this root (an empty folder): paths only, with a note.
        const fs::path empty_root = temp_path("empty-root");
        fs::create_directories(empty_root);
        std::ostringstream out2, err2;
        REQUIRE(render_verb({file.string(), "--root", empty_root.string()}, out2, err2) == 0);
        CHECK(out2.str() == render_svg(trajectory));
        CHECK(err2.str().rfind("note: ", 0) == 0);
        CHECK(err2.str().find("does not exist") != std::string::npos);

        // A trajectory of an older version of the scene: paths only.
        trajectory.scene_sha256 = std::string(64, '0');
        write_file_atomically(file.string(), write_trajectory(trajectory));
        std::ostringstream out3, err3;
        REQUIRE(render_verb({file.string(), "--root", IMPULSE_SOURCE_DIR}, out3, err3) == 0);
        CHECK(out3.str() == render_svg(trajectory));
        CHECK(err3.str().find("has changed") != std::string::npos);
        fs::remove(file);
    }

    SECTION("bad input is an InputError (exit 2) naming the file") {
        std::ostringstream out, err;
        const fs::path neither = temp_path("neither.json");
        std::ofstream(neither) << R"({"schema": "something/else@1", "x": [1, 2]})";
        try {
            render_verb({neither.string()}, out, err);
            FAIL("no InputError");
        } catch (const InputError& e) {
            CHECK(std::string(e.what()).rfind(neither.string() + ": schema: ", 0) == 0);
        }
        std::ofstream(neither) << "not json at all";
        CHECK_THROWS_AS(render_verb({neither.string()}, out, err), InputError);
        std::ofstream(neither) << R"({"name": "no schema"})";
        CHECK_THROWS_AS(render_verb({neither.string()}, out, err), InputError);
        CHECK_THROWS_AS(render_verb({temp_path("missing.json").string()}, out, err), InputError);
        CHECK_THROWS_AS(render_verb({}, out, err), impulse::harness::cli::UsageError);
        CHECK(out.str().empty());
        fs::remove(neither);

        std::ostringstream help;
        CHECK(render_verb({"--help"}, help, err) == 0);
        CHECK(help.str().find("--root") != std::string::npos);
    }
}

TEST_CASE("a picture frames any motion it can draw: a span too small or too large for doubles",
          "[render]") {
    using picture::Box;
    // Found by an outside review: a body moving 1e-320 m drew a 0 x 0 picture.
    const Box tiny = picture::framed(Box{0.0, 0.0, 1e-320, 0.0}, nullptr);
    CHECK(tiny.width() >= 1.0);
    CHECK(tiny.height() >= 1.0);
    // Positions at +-1e308: a width of inf scaled every point to NaN.
    const Box huge = picture::framed(Box{-1e308, -1e308, 1e308, 1e308}, nullptr);
    CHECK(std::isfinite(huge.width()));
    CHECK(std::isfinite(huge.height()));
    CHECK(huge.width() > 0.0);
    // Ordinary motion keeps its 8% margin.
    const Box drop = picture::framed(Box{0.0, 0.0, 1.0, 2.0}, nullptr);
    CHECK(drop.x0 == Approx(-0.16));
    CHECK(drop.y1 == Approx(2.16));
}
