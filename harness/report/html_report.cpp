// The HTML report (html_report.h), text built by hand from the checks alone,
// so the same checks always give the same bytes.
#include "html_report.h"

#include "check_outcome.h"
#include "comparison_picture.h"
#include "first_divergence.h"
#include "markup.h"
#include "motion_picture.h"
#include "page_assets.h"
#include "replay_data.h"
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

// The scene's heading, files, message, details and expectations.
void section_text(std::string& out, const SceneCheck& check) {
    const std::string status = status_word(check.status);
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
    // A failed comparison's first divergence and its cause, once: the gate's
    // message is the same sentence when the comparison is all that failed.
    const bool divergence = check.status == Status::failed && check.comparison && !check.stale &&
                            earliest_divergence(*check.comparison) != nullptr;
    if (divergence) {
        out += "<p class=\"cause\"><b>First divergence:</b> " + xml_escape(line) + "</p>\n";
    }
    const bool repeated = divergence && check.message == first_divergence_line(*check.comparison);
    if (check.status != Status::passed && !check.message.empty() && !repeated) {
        out += "<p class=\"message\">" + xml_escape(check.message) + "</p>\n";
    } else if (!line.empty() && check.status != Status::failed) {
        out += "<p>" + xml_escape(line) + "</p>\n";
    }
}

void expectations_list(std::string& out, const SceneCheck& check) {
    if (check.expectations.empty()) {
        return;
    }
    out += "<ul class=\"expectations\">\n";
    for (const ExpectationResult& e : check.expectations) {
        out += std::string("<li class=\"") + (e.passed ? "pass" : "fail") + "\">" +
               (e.passed ? "&#10003; " : "&#10007; ") + xml_escape(e.what);
        if (e.numeric) {
            out += ": expected " + xml_escape(sentence_number(e.expected)) + ", got " +
                   xml_escape(sentence_number(e.actual));
        }
        if (!e.detail.empty()) {
            out += " &#8212; " + xml_escape(e.detail);
        }
        out += "</li>\n";
    }
    out += "</ul>\n";
}

// The replay's mount point and its data, which the page's script reads.
void replay_block(std::string& out, const SceneCheck& check, const std::string& stem) {
    const std::string data = replay_json(check);
    if (data.empty()) {
        return;
    }
    out += "<div class=\"replay\" data-source=\"data-" + stem + "\"></div>\n";
    out += "<script type=\"application/json\" id=\"data-" + stem + "\">" + data + "</script>\n";
}

void html_section(std::string& out, const SceneCheck& check, const std::string& stem,
                  const std::string& picture, bool picture_file) {
    const bool folded = check.status == Status::passed;
    if (folded) {
        // Passed scenes are folded: what a reviewer opens the page for is above them.
        out += "<details class=\"scene\"><summary>" + xml_escape(display_name(check)) +
               " <span class=\"badge passed\">passed</span> " + xml_escape(outcome_line(check)) +
               "</summary>\n";
    }
    out += "<section id=\"scene-" + stem + "\" class=\"" + status_word(check.status) + "\">\n";
    section_text(out, check);
    if (check.status == Status::failed) {
        replay_block(out, check, stem);
    }
    if (!check.details.empty()) {
        out += "<pre>" + xml_escape(check.details) + "</pre>\n";
    }
    expectations_list(out, check);
    if (!picture.empty()) {
        const bool fold_picture = check.status == Status::failed && check.gold && check.value;
        out += fold_picture ? "<details><summary>The static picture</summary>\n" : "";
        out += "<figure>\n" + picture;
        if (picture_file) {
            out += "<figcaption>Also in <a href=\"" + stem + ".svg\">" + stem +
                   ".svg</a>.</figcaption>\n";
        }
        out += "</figure>\n";
        out += fold_picture ? "</details>\n" : "";
    }
    out += "</section>\n";
    out += folded ? "</details>\n" : "";
}

// Failed scenes first, then errors, skipped and passed ones, each in the
// order checked: the page opens on what needs looking at.
std::vector<std::size_t> page_order(const std::vector<SceneCheck>& checks) {
    std::vector<std::size_t> order;
    for (const Status status : {Status::failed, Status::error, Status::skipped, Status::passed}) {
        for (std::size_t i = 0; i < checks.size(); ++i) {
            if (checks[i].status == status) {
                order.push_back(i);
            }
        }
    }
    return order;
}

// The page's head, the verdict and the table of scenes.
std::string html_head(const std::vector<SceneCheck>& checks, const std::vector<std::string>& stems,
                      const std::vector<std::size_t>& order) {
    const CheckCounts c = count_checks(checks);
    const bool all_passed = c.failed == 0 && c.errors == 0;
    std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
    html += "<title>impulse check: " + xml_escape(verdict_counts(c)) + "</title>\n";
    html += "<script>" + std::string(page_error_hook()) + "</script>\n";
    html += "<style>" + std::string(page_style()) + "</style>\n</head>\n<body>\n";
    html += "<h1>impulse check</h1>\n";
    html += std::string("<p class=\"verdict ") + (all_passed ? "passed" : "failed") + "\">" +
            (all_passed ? "&#10004; " : "&#10008; ") + xml_escape(verdict_counts(c)) + " (" +
            seconds_text(c.seconds) + " s)</p>\n";
    if (c.failed > 0) {
        html += "<p class=\"keys\">Each failed scene has a replay: golden (amber, dashed) and new "
                "(blue) overlaid. Space plays or pauses, the arrow keys step a frame.</p>\n";
    }
    if (!checks.empty()) {
        html += "<table>\n<tr><th>scene</th><th>result</th><th>first divergence or "
                "message</th><th>time</th></tr>\n";
        for (const std::size_t i : order) {
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
    const std::vector<std::size_t> order = page_order(checks);
    std::string html = html_head(checks, stems, order);
    std::vector<std::string> pictures;
    for (std::size_t i = 0; i < checks.size(); ++i) {
        pictures.push_back(picture_of(checks[i]));
        if (!pictures[i].empty() && checks[i].status == Status::failed) {
            files.emplace_back(stems[i] + ".svg", pictures[i]);
        }
    }
    for (const std::size_t i : order) {
        html_section(html, checks[i], stems[i], pictures[i],
                     !pictures[i].empty() && checks[i].status == Status::failed);
    }
    html += "<script>" + std::string(page_script()) + "</script>\n</body>\n</html>\n";
    files.emplace_back("index.html", html);
    return files;
}

} // namespace impulse::harness
