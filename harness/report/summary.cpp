// summary.md (summary.h), text built by hand from the checks alone, so the
// same checks always give the same bytes.
#include "summary.h"

#include "check_outcome.h"
#include "first_divergence.h"
#include "input_error.h"
#include "text.h"

#include <algorithm>
#include <cstddef>

namespace impulse::harness {

namespace {

using Status = SceneCheck::Status;

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

// A pull-request comment holds 65,536 characters; the rest is headroom for
// what a CI step adds around the file.
constexpr std::size_t summary_budget = 60000;
// Kept free for the closing line that says what was left out.
constexpr std::size_t closing_reserve = 400;

bool is_problem(const SceneCheck& check) {
    return check.status == Status::failed || check.status == Status::error;
}

std::string result_cell(const SceneCheck& check) {
    switch (check.status) {
    case Status::passed:
        return "\u2705 passed";
    case Status::failed:
        return "\u274c failed" + (check.stale ? std::string(" (stale golden)") : "");
    case Status::error:
        return "\u26a0\ufe0f error";
    case Status::skipped:
        return "\u23ed\ufe0f skipped";
    }
    return "\u26a0\ufe0f error";
}

std::string table_row(const SceneCheck& check) {
    return "| " + markdown_cell(printable_path(display_name(check)), 100) + " | " +
           result_cell(check) + " | " + markdown_cell(outcome_line(check)) + " | " +
           seconds_text(check.seconds) + " s |\n";
}

const char* const table_head = "| scene | result | first divergence or message | time |\n"
                               "| --- | --- | --- | ---: |\n";

// The command the gate's hints name, from the checks (every check of one
// project carries the same).
std::string accept_command(const std::vector<SceneCheck>& checks) {
    for (const SceneCheck& check : checks) {
        if (!check.regen.empty()) {
            return check.regen;
        }
    }
    return "impulse regen";
}

// Totals, what accepts the change, where the rest is, and causes shared
// by several scenes: all before any table, so a cut never loses them.
std::string summary_head(const std::vector<SceneCheck>& checks, const CheckCounts& c) {
    const bool all_passed = c.failed == 0 && c.errors == 0;
    std::string out = "## impulse check\n\n";
    out += std::string("**") + (all_passed ? "\u2705 " : "\u274c ") + verdict_counts(c) + "** (" +
           seconds_text(c.seconds) + " s)\n\n";
    if (c.failed > 0) {
        out += "If the change is intended, accept it with `" + accept_command(checks) +
               "`: it regenerates every golden, or none while a scene refuses.\n\n";
    }
    if (!all_passed) {
        out += "The full report, with every scene's details, is `index.html` beside this "
               "file.\n\n";
    }
    const std::vector<std::string> shared = shared_causes(checks);
    for (const std::string& line : shared) {
        out += "- " + markdown_cell(line, 1000) + "\n";
    }
    return out + (shared.empty() ? "" : "\n");
}

// One failing scene's details, folded.
std::string details_block(const SceneCheck& check) {
    std::string out = "<details><summary>" +
                      markdown_cell(printable_path(display_name(check)), 100) + ": " +
                      status_word(check.status) + "</summary>\n\n";
    if (!check.message.empty()) {
        out += markdown_cell(check.message, 1000) + "\n\n";
    }
    if (!check.details.empty()) {
        std::string details = printable(capped(check.details, 80, 8000));
        if (details.back() != '\n') {
            details += "\n";
        }
        const std::string fence = fence_for(details);
        out += fence + "text\n" + details + fence + "\n\n";
    }
    return out + "</details>\n\n";
}

// The failed scenes' rows stop here, so that the first failures' details
// fit too.
constexpr std::size_t table_budget = summary_budget / 2;

// Appends `part` when it keeps `out` within `limit` (with room for the
// closing line).
bool append_within(std::string& out, const std::string& part, std::size_t limit = summary_budget) {
    if (out.size() + part.size() + closing_reserve > limit) {
        return false;
    }
    out += part;
    return true;
}

} // namespace

std::string summary_markdown(const std::vector<SceneCheck>& checks) {
    const CheckCounts c = count_checks(checks);
    std::string out = summary_head(checks, c);
    if (checks.empty()) {
        return out + "No scenes were checked.\n";
    }
    std::size_t left_out = 0; // rows and blocks that did not fit
    if (c.failed + c.errors > 0) {
        out += table_head;
        for (const SceneCheck& check : checks) {
            if (is_problem(check) && !append_within(out, table_row(check), table_budget)) {
                ++left_out;
            }
        }
        out += "\n";
    }
    // Passed (and skipped) scenes folded, failed ones stay first.
    std::string rest = table_head;
    std::size_t others = 0;
    for (const SceneCheck& check : checks) {
        if (!is_problem(check)) {
            rest += table_row(check);
            ++others;
        }
    }
    if (others > 0) {
        const std::string folded =
            "<details><summary>" +
            plural(others, "scene passed or skipped", "scenes passed or were skipped") +
            "</summary>\n\n" + rest + "\n</details>\n\n";
        if (!append_within(out, folded)) {
            out += plural(others, "scene", "scenes") +
                   " passed or were skipped; the full report lists them.\n\n";
        }
    }
    for (const SceneCheck& check : checks) {
        if (is_problem(check) && !append_within(out, details_block(check))) {
            ++left_out;
        }
    }
    if (left_out > 0) {
        out += std::to_string(left_out) +
               " rows and details are left out to fit a pull-request comment; the full report "
               "has them all.\n";
    }
    return out;
}

} // namespace impulse::harness
