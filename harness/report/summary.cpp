// summary.md (summary.h), text built by hand from the checks alone, so the
// same checks always give the same bytes.
#include "summary.h"

#include "check_outcome.h"

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

} // namespace

std::string summary_markdown(const std::vector<SceneCheck>& checks) {
    const CheckCounts c = count_checks(checks);
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
        case Status::skipped:
            result = "\u23ed\ufe0f skipped";
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

} // namespace impulse::harness
