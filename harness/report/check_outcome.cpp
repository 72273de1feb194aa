// A scene's check in words (check_outcome.h).
#include "check_outcome.h"

#include "first_divergence.h"
#include "text.h"

#include <charconv>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <optional>
#include <system_error>

namespace impulse::harness {

namespace {

using Status = SceneCheck::Status;

double safe_seconds(double s) {
    return std::isfinite(s) && s > 0.0 ? s : 0.0;
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

} // namespace

CheckCounts count_checks(const std::vector<SceneCheck>& checks) {
    CheckCounts c;
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
        case Status::skipped:
            ++c.skipped;
            break;
        }
        c.seconds += safe_seconds(check.seconds);
    }
    return c;
}

std::string seconds_text(double s) {
    return fixed_text(safe_seconds(s), 3);
}

std::string verdict_counts(const CheckCounts& c) {
    return plural(c.passed + c.failed + c.errors + c.skipped, "scene", "scenes") + ": " +
           std::to_string(c.passed) + " passed, " + std::to_string(c.failed) + " failed, " +
           plural(c.errors, "error", "errors") +
           (c.skipped > 0 ? ", " + std::to_string(c.skipped) + " skipped" : "");
}

const char* status_word(Status status) {
    constexpr const char* words[] = {"passed", "failed", "error", "skipped"}; // in Status's order
    const auto i = static_cast<std::size_t>(status);
    return i < std::size(words) ? words[i] : "error";
}

std::string display_name(const SceneCheck& check) {
    const std::string engine = check.engine.empty() ? "" : check.engine + "/";
    if (!check.name.empty()) {
        return engine + check.name;
    }
    return engine + (check.scene_file.empty() ? std::string("(unnamed)") : check.scene_file);
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

std::string error_kind(const SceneCheck& check) {
    switch (check.error_source) {
    case SceneCheck::ErrorSource::input:
        break;
    case SceneCheck::ErrorSource::engine:
        return "engine error";
    case SceneCheck::ErrorSource::internal:
        return "internal error";
    }
    return "input error";
}

// The one-line description of a scene's outcome for tables.
std::string outcome_line(const SceneCheck& check) {
    if (check.status == Status::failed && !check.stale && check.comparison) {
        if (const std::optional<FirstDivergence> first = first_divergence_of(*check.comparison)) {
            return divergence_text(first->divergence) + ": " + first->cause +
                   shape_clause(*check.comparison);
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
    case Status::skipped:
        return "skipped";
    }
    return "could not be checked";
}

} // namespace impulse::harness
