// The gate's reports (report.h): JUnit XML for CI, a Markdown summary for a
// pull-request comment, and a self-contained HTML page with pictures.
//
// Everything here is text built by hand and depends only on the checks, so
// the same checks always give the same bytes.
#include "report.h"

#include "atomic_file.h"
#include "input_error.h"
#include "markup.h"
#include "number_format.h"
#include "render.h"
#include "text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace impulse::harness {

namespace {

using Status = SceneCheck::Status;

struct Counts {
    std::size_t passed = 0, failed = 0, errors = 0;
    double seconds = 0.0;
};

double safe_seconds(double s) {
    return std::isfinite(s) && s > 0.0 ? s : 0.0;
}

Counts count(const std::vector<SceneCheck>& checks) {
    Counts c;
    for (const SceneCheck& check : checks) {
        switch (check.status) {
        case Status::passed:
            ++c.passed;
            break;
        case Status::failed:
            ++c.failed;
            break;
        case Status::error:
            ++c.errors;
            break;
        }
        c.seconds += safe_seconds(check.seconds);
    }
    return c;
}

// Seconds with three decimals: "0.012".
std::string seconds_text(double s) {
    char buffer[64];
    const auto r =
        std::to_chars(buffer, buffer + sizeof buffer, safe_seconds(s), std::chars_format::fixed, 3);
    return std::string(buffer, r.ptr);
}

// A number for people: three (or `digits`) significant digits.
std::string approx(double value, int digits = 3) {
    if (!std::isfinite(value)) {
        return sentence_number(value);
    }
    char buffer[64];
    const auto r =
        std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, digits);
    return std::string(buffer, r.ptr);
}

std::string verdict_counts(const Counts& c) {
    return plural(c.passed + c.failed + c.errors, "scene", "scenes") + ": " +
           std::to_string(c.passed) + " passed, " + std::to_string(c.failed) + " failed, " +
           plural(c.errors, "error", "errors");
}

const char* status_word(Status status) {
    switch (status) {
    case Status::passed:
        return "passed";
    case Status::failed:
        return "failed";
    case Status::error:
        return "error";
    }
    return "error";
}

std::string display_name(const SceneCheck& check) {
    if (!check.name.empty()) {
        return check.name;
    }
    return check.scene_file.empty() ? std::string("(unnamed)") : check.scene_file;
}

// Why a scene failed, in two or three words (JUnit's failure type).
std::string failure_kind(const SceneCheck& check) {
    if (check.stale) {
        return "stale golden";
    }
    if (check.comparison && !check.comparison->passed) {
        return "physics mismatch";
    }
    for (const ExpectationResult& e : check.expectations) {
        if (!e.passed) {
            return "failed expectation";
        }
    }
    return "failed";
}

// "box.vy at t = 0.766667 s (frame 46): golden 1.25, new 1.2500000000000002
// (abs 2.22e-16, rel 1.78e-16, 1 ULP)": the values exactly, the rest for people.
std::string divergence_text(const Divergence& d) {
    const bool event = d.column.rfind("events[", 0) == 0;
    std::string text = d.column + " at t = " + approx(d.t, 6) + " s";
    if (!event) {
        text += " (frame " + std::to_string(d.frame) + ")";
    }
    text += ": golden " + sentence_number(d.gold) + ", new " + sentence_number(d.value) + " (abs " +
            approx(d.abs_diff);
    if (std::isfinite(d.rel_diff)) {
        text += ", rel " + approx(d.rel_diff);
    }
    return text + ", " + std::to_string(d.ulp) + " ULP)";
}

// The one-line description of a scene's outcome for tables.
std::string outcome_line(const SceneCheck& check) {
    if (check.status == Status::failed && !check.stale && check.comparison) {
        if (const Divergence* first = first_divergence(*check.comparison)) {
            return divergence_text(*first);
        }
    }
    if (!check.message.empty()) {
        return check.message;
    }
    if (check.status == Status::passed && check.comparison) {
        return check.comparison->identical ? "bit-identical to the golden"
                                           : "within tolerance of the golden";
    }
    switch (check.status) {
    case Status::passed:
        return "";
    case Status::failed:
        return failure_kind(check);
    case Status::error:
        break;
    }
    return "could not be checked";
}

// ---- JUnit ----------------------------------------------------------------------

std::string junit_body(const SceneCheck& check) {
    std::string body = check.details.empty() ? check.message : check.details;
    std::string files;
    if (!check.scene_file.empty()) {
        files += "scene: " + check.scene_file + "\n";
    }
    if (!check.golden_file.empty()) {
        files += "golden: " + check.golden_file + "\n";
    }
    if (!files.empty()) {
        if (!body.empty() && body.back() != '\n') {
            body += "\n";
        }
        body += (body.empty() ? "" : "\n") + files;
    }
    return body;
}

// ---- Markdown -------------------------------------------------------------------

// Text for one table cell: no line breaks, no column separators, no HTML.
std::string markdown_cell(const std::string& text, std::size_t longest = 300) {
    std::string cell;
    for (const char c : text) {
        switch (c) {
        case '|':
            cell += "\\|";
            break;
        case '\\':
            cell += "\\\\";
            break;
        case '<':
            cell += "&lt;";
            break;
        case '>':
            cell += "&gt;";
            break;
        case '\n':
        case '\r':
        case '\t':
            cell += ' ';
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20U) {
                cell += "\xEF\xBF\xBD";
            } else {
                cell += c;
            }
        }
    }
    if (cell.size() > longest) {
        std::size_t cut = longest;
        while (cut > 0 && (static_cast<unsigned char>(cell[cut]) & 0xC0U) == 0x80U) {
            --cut;
        }
        // Never leave a lone backslash escaping the cell's closing bar.
        std::size_t slashes = 0;
        while (slashes < cut && cell[cut - 1 - slashes] == '\\') {
            ++slashes;
        }
        cut -= slashes % 2;
        cell = cell.substr(0, cut) + "\u2026";
    }
    return cell;
}

// Control characters other than tab and line feed would garble the comment.
std::string printable(const std::string& text) {
    std::string out;
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\r') {
            continue;
        }
        if ((u < 0x20U && c != '\n' && c != '\t') || u == 0x7FU) {
            out += "\xEF\xBF\xBD";
        } else {
            out += c;
        }
    }
    return out;
}

// A fence longer than any run of backticks in the text.
std::string fence_for(const std::string& text) {
    std::size_t longest = 0, run = 0;
    for (const char c : text) {
        run = c == '`' ? run + 1 : 0;
        longest = std::max(longest, run);
    }
    return std::string(std::max<std::size_t>(3, longest + 1), '`');
}

// At most max_lines lines and max_chars characters, saying how much was left out.
std::string capped(const std::string& text, std::size_t max_lines, std::size_t max_chars) {
    std::size_t lines = 0, end = 0;
    while (end < text.size() && lines < max_lines && end < max_chars) {
        const std::size_t next = text.find('\n', end);
        end = next == std::string::npos ? text.size() : next + 1;
        ++lines;
    }
    if (end >= text.size()) {
        return text;
    }
    end = std::min(end, max_chars);
    while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0U) == 0x80U) {
        --end;
    }
    std::size_t rest = 0;
    for (std::size_t i = end; i < text.size(); ++i) {
        rest += text[i] == '\n' ? 1 : 0;
    }
    std::string head = text.substr(0, end);
    if (!head.empty() && head.back() != '\n') {
        head += "\n";
    }
    return head + "... (" + std::to_string(rest + 1) +
           " more lines; the HTML report has them all)\n";
}

// ---- HTML -------------------------------------------------------------------------

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

std::string lower_first(std::string text) {
    if (!text.empty() && text[0] >= 'A' && text[0] <= 'Z') {
        text[0] = static_cast<char>(text[0] - 'A' + 'a');
    }
    return text;
}

} // namespace

std::string junit_xml(const std::vector<SceneCheck>& checks) {
    const Counts c = count(checks);
    const std::string totals = " tests=\"" + std::to_string(checks.size()) + "\" failures=\"" +
                               std::to_string(c.failed) + "\" errors=\"" +
                               std::to_string(c.errors) + "\"";
    std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += "<testsuites name=\"impulse\"" + totals + " time=\"" + seconds_text(c.seconds) + "\">\n";
    out += "  <testsuite name=\"impulse.gate\"" + totals + " skipped=\"0\" time=\"" +
           seconds_text(c.seconds) + "\">\n";
    for (const SceneCheck& check : checks) {
        out += "    <testcase classname=\"impulse.gate\" name=\"" +
               xml_escape(display_name(check), true) + "\" time=\"" + seconds_text(check.seconds) +
               "\"";
        if (check.status == Status::passed) {
            out += "/>\n";
            continue;
        }
        const bool failed = check.status == Status::failed;
        const char* element = failed ? "failure" : "error";
        std::string message = check.message.empty() ? outcome_line(check) : check.message;
        if (message.empty()) {
            message = failed ? "does not match its golden" : "could not be checked";
        }
        out += ">\n      <" + std::string(element) + " message=\"" + xml_escape(message, true) +
               "\" type=\"" + (failed ? failure_kind(check) : std::string("input error")) + "\">" +
               xml_escape(junit_body(check)) + "</" + element + ">\n";
        out += "    </testcase>\n";
    }
    out += "  </testsuite>\n</testsuites>\n";
    return out;
}

std::string summary_markdown(const std::vector<SceneCheck>& checks) {
    const Counts c = count(checks);
    const bool all_passed = c.failed == 0 && c.errors == 0;
    std::string out = "## impulse check\n\n";
    out += std::string("**") + (all_passed ? "\u2705 " : "\u274c ") + verdict_counts(c) + "** (" +
           seconds_text(c.seconds) + " s)\n\n";
    if (checks.empty()) {
        out += "No scenes were checked.\n";
        return out;
    }
    out += "| scene | result | first divergence or message | time |\n";
    out += "| --- | --- | --- | ---: |\n";
    for (const SceneCheck& check : checks) {
        std::string result;
        switch (check.status) {
        case Status::passed:
            result = "\u2705 passed";
            break;
        case Status::failed:
            result = "\u274c failed" + (check.stale ? std::string(" (stale golden)") : "");
            break;
        case Status::error:
            result = "\u26a0\ufe0f error";
            break;
        }
        out += "| " + markdown_cell(display_name(check), 100) + " | " + result + " | " +
               markdown_cell(outcome_line(check)) + " | " + seconds_text(check.seconds) + " s |\n";
    }
    for (const SceneCheck& check : checks) {
        if (check.status == Status::passed) {
            continue;
        }
        out += "\n### " + markdown_cell(display_name(check), 100) + ": " +
               status_word(check.status) + "\n\n";
        if (!check.message.empty()) {
            out += markdown_cell(check.message, 1000) + "\n\n";
        }
        if (!check.details.empty()) {
            std::string details = printable(capped(check.details, 80, 8000));
            if (details.back() != '\n') {
                details += "\n";
            }
            const std::string fence = fence_for(details);
            out += fence + "text\n" + details + fence + "\n";
        }
    }
    return out;
}

void write_report(const std::string& dir, const std::vector<SceneCheck>& checks) {
    namespace fs = std::filesystem;
    std::error_code error;
    fs::create_directories(dir, error);
    if (error) {
        throw InputError(dir, "", "cannot be created (" + lower_first(error.message()) + ")");
    }
    if (!fs::is_directory(dir, error)) {
        throw InputError(dir, "", "cannot hold the report: it is not a directory");
    }
    const fs::path base(dir);
    // Written only when no path is refused (a link, a FIFO): never half new.
    std::vector<std::pair<std::string, std::string>> files;
    files.emplace_back((base / "summary.md").string(), summary_markdown(checks));
    const Counts c = count(checks);
    const bool all_passed = c.failed == 0 && c.errors == 0;
    const std::vector<std::string> stems = file_stems(checks);
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
    for (std::size_t i = 0; i < checks.size(); ++i) {
        const std::string picture = picture_of(checks[i]);
        const bool picture_file = !picture.empty() && checks[i].status == Status::failed;
        if (picture_file) {
            files.emplace_back((base / (stems[i] + ".svg")).string(), picture);
        }
        html_section(html, checks[i], stems[i], picture, picture_file);
    }
    html += "</body>\n</html>\n";
    files.emplace_back((base / "index.html").string(), html);
    for (const auto& [path, content] : files) {
        require_regular_or_missing(path);
    }
    for (const auto& [path, content] : files) {
        write_file_atomically(path, content);
    }
}

} // namespace impulse::harness
