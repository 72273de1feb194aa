// The HTML report (html_report.h), text built by hand from the checks alone,
// so the same checks always give the same bytes.
#include "html_report.h"

#include "check_outcome.h"
#include "comparison_picture.h"
#include "markup.h"
#include "motion_picture.h"
#include "text.h"

#include <cstddef>
#include <cstring>
#include <set>

namespace impulse::harness {

namespace {

using Status = SceneCheck::Status;

// File and anchor names: [A-Za-z0-9._-], not starting with '.', unique.
std::vector<std::string> file_stems(const std::vector<SceneCheck>& checks) {
    std::vector<std::string> stems;
    std::set<std::string> taken;
    for (const SceneCheck& check : checks) {
        std::string stem;
        for (const char c : display_name(check)) {
            const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                              (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
            stem += safe ? c : '_';
        }
        if (stem.empty() || stem[0] == '.') {
            stem = "_" + stem;
        }
        if (stem.size() > 100) {
            stem.resize(100);
        }
        std::string unique = stem;
        for (int n = 2; taken.count(unique) != 0; ++n) {
            unique = stem + "-" + std::to_string(n);
        }
        taken.insert(unique);
        stems.push_back(unique);
    }
    return stems;
}

// Rendering every frame of a very long run costs more than a passing scene's
// picture is worth.
bool cheap_to_draw(const Trajectory& t) {
    const std::size_t columns = t.columns.empty() ? 1 : t.columns.size();
    return t.frames.size() * columns <= 4'000'000;
}

bool same_bits(const Trajectory& a, const Trajectory& b) {
    if (a.columns != b.columns || a.frames.size() != b.frames.size() ||
        a.events.size() != b.events.size()) {
        return false;
    }
    for (std::size_t k = 0; k < a.frames.size(); ++k) {
        if (a.frames[k].size() != b.frames[k].size() ||
            (!a.frames[k].empty() && std::memcmp(a.frames[k].data(), b.frames[k].data(),
                                                 a.frames[k].size() * sizeof(double)) != 0)) {
            return false;
        }
    }
    return true;
}

// The picture for a scene: golden vs new for a failed scene that has both,
// its motion otherwise; empty when there is nothing to draw.
std::string picture_of(const SceneCheck& check) {
    const Scene* scene = check.scene ? &*check.scene : nullptr;
    if (check.status == Status::error || !check.value) {
        return "";
    }
    if (check.status == Status::failed && check.gold) {
        if (check.comparison) {
            return render_comparison_svg(scene, *check.gold, *check.value, *check.comparison);
        }
        // Not compared (a stale golden, say): the picture says only whether
        // the frames are the same bits.
        Comparison plain;
        plain.identical = same_bits(*check.gold, *check.value);
        plain.passed = plain.identical;
        return render_comparison_svg(scene, *check.gold, *check.value, plain);
    }
    if (check.status == Status::passed && !cheap_to_draw(*check.value)) {
        return "";
    }
    return scene != nullptr ? render_svg(*scene, *check.value) : render_svg(*check.value);
}

constexpr const char* css = R"(
body { font-family: "DejaVu Sans", Helvetica, Arial, sans-serif; color: #222; margin: 2em auto;
       max-width: 1000px; padding: 0 1em; line-height: 1.45; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.25em; margin: 0 0 0.4em 0; }
.verdict { font-size: 1.1em; font-weight: bold; padding: 0.5em 0.8em; border-radius: 6px; }
.verdict.passed { background: #e8f5e9; color: #1b5e20; }
.verdict.failed { background: #fdecea; color: #8e1b10; }
table { border-collapse: collapse; width: 100%; margin: 1em 0 2em 0; font-size: 0.92em; }
th, td { text-align: left; padding: 0.35em 0.6em; border-bottom: 1px solid #e3e3e3;
         vertical-align: top; }
th { background: #f5f5f5; }
td.time { text-align: right; white-space: nowrap; font-variant-numeric: tabular-nums; }
td.detail { word-break: break-word; }
.badge { display: inline-block; font-size: 0.8em; padding: 0.1em 0.6em; border-radius: 1em;
         font-weight: bold; vertical-align: middle; }
.badge.passed { background: #e8f5e9; color: #1b5e20; }
.badge.failed { background: #fdecea; color: #b71c1c; }
.badge.error { background: #fff3e0; color: #e65100; }
section { border: 1px solid #e3e3e3; border-left-width: 6px; border-radius: 6px; padding: 1em 1.2em;
          margin: 1.2em 0; }
section.passed { border-left-color: #43a047; }
section.failed { border-left-color: #e53935; }
section.error { border-left-color: #fb8c00; }
.files { color: #666; font-size: 0.88em; margin: 0.2em 0 0.6em 0; }
.files code { color: #333; }
.message { font-weight: bold; }
pre { background: #f7f7f7; border: 1px solid #e6e6e6; border-radius: 4px; padding: 0.8em;
      overflow-x: auto; font-size: 0.85em; line-height: 1.35; }
ul.expectations { padding-left: 1.2em; font-size: 0.92em; }
li.fail { color: #b71c1c; }
figure { margin: 1em 0 0 0; overflow-x: auto; }
figure svg { max-width: 100%; height: auto; }
figcaption { color: #666; font-size: 0.85em; }
a { color: #1565c0; }
)";

void html_section(std::string& out, const SceneCheck& check, const std::string& stem,
                  const std::string& picture, bool picture_file) {
    const std::string status = status_word(check.status);
    out += "<section id=\"scene-" + stem + "\" class=\"" + status + "\">\n";
    out += "<h2>" + xml_escape(display_name(check)) + " <span class=\"badge " + status + "\">" +
           status + "</span></h2>\n";
    out += "<p class=\"files\">";
    if (!check.scene_file.empty()) {
        out += "scene <code>" + xml_escape(check.scene_file) + "</code> &#183; ";
    }
    if (!check.golden_file.empty()) {
        out += "golden <code>" + xml_escape(check.golden_file) + "</code> &#183; ";
    }
    out += seconds_text(check.seconds) + " s</p>\n";
    const std::string line = outcome_line(check);
    if (check.status != Status::passed && !check.message.empty()) {
        out += "<p class=\"message\">" + xml_escape(check.message) + "</p>\n";
    } else if (!line.empty()) {
        out += "<p>" + xml_escape(line) + "</p>\n";
    }
    if (!check.details.empty()) {
        out += "<pre>" + xml_escape(check.details) + "</pre>\n";
    }
    if (!check.expectations.empty()) {
        out += "<ul class=\"expectations\">\n";
        for (const ExpectationResult& e : check.expectations) {
            out += std::string("<li class=\"") + (e.passed ? "pass" : "fail") + "\">" +
                   (e.passed ? "&#10003; " : "&#10007; ") + xml_escape(e.what) + ": expected " +
                   xml_escape(sentence_number(e.expected)) + ", got " +
                   xml_escape(sentence_number(e.actual));
            if (!e.detail.empty()) {
                out += " &#8212; " + xml_escape(e.detail);
            }
            out += "</li>\n";
        }
        out += "</ul>\n";
    }
    if (!picture.empty()) {
        out += "<figure>\n" + picture;
        if (picture_file) {
            out += "<figcaption>Also in <a href=\"" + stem + ".svg\">" + stem +
                   ".svg</a>.</figcaption>\n";
        }
        out += "</figure>\n";
    }
    out += "</section>\n";
}

// The page's head, the verdict and the table of scenes.
std::string html_head(const std::vector<SceneCheck>& checks,
                      const std::vector<std::string>& stems) {
    const CheckCounts c = count_checks(checks);
    const bool all_passed = c.failed == 0 && c.errors == 0;
    std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
    html += "<title>impulse check: " + xml_escape(verdict_counts(c)) + "</title>\n";
    html += "<style>" + std::string(css) + "</style>\n</head>\n<body>\n";
    html += "<h1>impulse check</h1>\n";
    html += std::string("<p class=\"verdict ") + (all_passed ? "passed" : "failed") + "\">" +
            (all_passed ? "&#10004; " : "&#10008; ") + xml_escape(verdict_counts(c)) + " (" +
            seconds_text(c.seconds) + " s)</p>\n";
    if (!checks.empty()) {
        html += "<table>\n<tr><th>scene</th><th>result</th><th>first divergence or "
                "message</th><th>time</th></tr>\n";
        for (std::size_t i = 0; i < checks.size(); ++i) {
            const std::string status = status_word(checks[i].status);
            html += "<tr><td><a href=\"#scene-" + stems[i] + "\">" +
                    xml_escape(display_name(checks[i])) + "</a></td><td><span class=\"badge " +
                    status + "\">" + status + "</span></td><td class=\"detail\">" +
                    xml_escape(outcome_line(checks[i])) + "</td><td class=\"time\">" +
                    seconds_text(checks[i].seconds) + " s</td></tr>\n";
        }
        html += "</table>\n";
    }
    return html;
}

} // namespace

std::vector<std::pair<std::string, std::string>>
html_report_files(const std::vector<SceneCheck>& checks) {
    std::vector<std::pair<std::string, std::string>> files;
    const std::vector<std::string> stems = file_stems(checks);
    std::string html = html_head(checks, stems);
    for (std::size_t i = 0; i < checks.size(); ++i) {
        const std::string picture = picture_of(checks[i]);
        const bool picture_file = !picture.empty() && checks[i].status == Status::failed;
        if (picture_file) {
            files.emplace_back(stems[i] + ".svg", picture);
        }
        html_section(html, checks[i], stems[i], picture, picture_file);
    }
    html += "</body>\n</html>\n";
    files.emplace_back("index.html", html);
    return files;
}

} // namespace impulse::harness
