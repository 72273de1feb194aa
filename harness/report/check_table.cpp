// The gate's results for a terminal (check_table.h).
#include "check_table.h"

#include "check_outcome.h"
#include "first_divergence.h"
#include "input_error.h"
#include "text.h"

#include <algorithm>
#include <cstddef>

namespace impulse::harness {

namespace {

using Status = SceneCheck::Status;

// The table's words, upper case where a reader's eye must stop.
const char* row_word(Status status) {
    switch (status) {
    case Status::passed:
        return "ok";
    case Status::failed:
        return "FAILED";
    case Status::error:
        return "ERROR";
    case Status::skipped:
        return "SKIPPED";
    }
    return "?";
}

// "ENGINE/NAME" when the project has several engines, else the scene's name.
std::string row_name(const SceneCheck& check) {
    return check.engine.empty() ? check.name : check.engine + "/" + check.name;
}

bool shown_when_quiet(const SceneCheck& c) {
    return c.status == Status::failed || c.status == Status::error;
}

// The status column: the widest word shown and one space, so every row's
// name starts in the same column; 7 without a SKIPPED row, as it always was.
std::size_t word_width(const std::vector<SceneCheck>& checks, bool quiet) {
    for (const SceneCheck& c : checks) {
        if (c.status == Status::skipped && (!quiet || shown_when_quiet(c))) {
            return 8;
        }
    }
    return 7;
}

std::string row(const SceneCheck& c, std::size_t word, std::size_t width) {
    std::string text =
        "  " + padded(row_word(c.status), word) + padded(printable_path(row_name(c)), width + 2);
    if (c.status == Status::passed) {
        return text + fixed_text(c.seconds, 3) + " s\n";
    }
    return text + c.message + "\n";
}

} // namespace

std::string check_totals_line(const std::vector<SceneCheck>& checks) {
    const CheckCounts c = count_checks(checks);
    return std::to_string(checks.size()) + " scene" + (checks.size() == 1 ? "" : "s") + ": " +
           std::to_string(c.passed) + " passed, " + std::to_string(c.failed) + " failed, " +
           std::to_string(c.errors) + " error" + (c.errors == 1 ? "" : "s") +
           (c.skipped > 0 ? ", " + std::to_string(c.skipped) + " skipped" : "") + "\n";
}

std::string check_table(const std::vector<SceneCheck>& checks, bool quiet) {
    std::size_t width = 4;
    for (const SceneCheck& c : checks) {
        if (!quiet || shown_when_quiet(c)) {
            width = std::max(width, printable_path(row_name(c)).size());
        }
    }
    const std::size_t word = word_width(checks, quiet);
    std::string out;
    for (const SceneCheck& c : checks) {
        if (!quiet || shown_when_quiet(c)) {
            out += row(c, word, width);
        }
    }
    if (quiet) {
        return out + check_totals_line(checks);
    }
    for (const SceneCheck& c : checks) {
        if (!c.details.empty()) {
            out += "\n" + printable_path(row_name(c)) + " (" + printable_path(c.scene_file) +
                   " vs " + printable_path(c.golden_file) + "):\n" + c.details;
        }
    }
    // Scenes that start diverging at the same cause, said once for all.
    for (const std::string& line : shared_causes(checks)) {
        out += line + "\n";
    }
    return out + check_totals_line(checks);
}

} // namespace impulse::harness
