// `impulse stress`: the extremes matrix (harness/study/stress.h) as a table or JSON.
#include "stress.h"

#include "cli.h"
#include "progress.h"
#include "text.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace impulse::harness::cli {

namespace {

constexpr const char* stress_help =
    R"(usage: impulse stress [--json] [--case NAME[,NAME...]] [--list]

Numerical stability at the extremes: runs a matrix of scenes built in the
tool (mass ratios 1 to 1e6, speeds 0.01 to 1000 m/s, sizes 0.05 to 50 m,
positions 1e4 m from the origin, dt 1e-4 to 1/30 s, e of 0 and 1, 1e4
simulated seconds, near-parallel edges, corner on corner) and checks at every
frame the invariants that apply, keeping the worst value of each:

  finite                 every state value of every body stays finite
  interpenetration       no pair overlaps by more than solver.contact_tolerance
  side                   a body's centre stays on its side of another's (no tunnelling)
  momentum drift         free collisions: within 1e-12 of the sum of |m v|
  energy gain            e <= 1: never more than 1e-12 of the energy's terms
  energy drift           e = 1: within 1e-12 + 32 epsilon per collision
  drop ladder            impact times and rebound speeds against docs/physics.md
  head-on velocities     against docs/physics.md's 1D formula, within 1e-12

A case whose numbers would tunnel without ccd must be refused before it runs;
its row shows the refusal. Each case's wall time is shown, never judged.

  --case NAME[,NAME...]  only these cases
  --list                 the cases and what each one does
  --json                 the results as JSON on standard output
  --quiet                no progress bar (drawn on standard error only when that is
                         a terminal, after about a second of work)

Exit: 0 every row within its bound (or refused as expected), 1 otherwise, 2 bad input.
)";

std::string sci(double value) {
    if (std::isnan(value)) {
        return "nan";
    }
    if (std::isinf(value)) {
        return value > 0 ? "inf" : "-inf";
    }
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.2e", value);
    return buffer;
}

std::string seconds_text(double seconds) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.2f s", seconds);
    return buffer;
}

// A table cell: the text padded to its column, then the gap before the next.
std::string cell(const std::string& text, std::size_t width, bool right = false) {
    return padded(text, width, right) + " ";
}

std::string bound_text(const StressRow& row) {
    switch (row.kind) {
    case Bound::at_most:
        return sci(row.bound);
    case Bound::above:
        return "> " + (row.bound == 0.0 ? std::string("0") : sci(row.bound));
    case Bound::finite:
        return "finite";
    }
    return "";
}

constexpr std::size_t case_width = 22;
constexpr std::size_t invariant_width = 46;

void write_header(std::ostream& out) {
    out << cell("case", case_width) << cell("invariant", invariant_width) << cell("worst", 10, true)
        << cell("bound", 10, true) << cell("result", 7) << "wall time (steps, collisions)\n";
}

// One case's rows, its wall time on the first; a refusal or a stop is a row
// of its own with the message on the line below, as is a failed row's detail.
void write_case(const StressResult& r, std::ostream& out) {
    bool first = true;
    const auto row = [&](const std::string& invariant, const std::string& worst,
                         const std::string& bound, bool passed) {
        std::string line = cell(first ? r.name : "", case_width) +
                           cell(invariant, invariant_width) + cell(worst, 10, true) +
                           cell(bound, 10, true) + cell(passed ? "pass" : "FAIL", 7);
        if (first) {
            line += seconds_text(r.seconds);
            if (r.refusal.empty()) {
                line += " (" + std::to_string(r.steps) + ", " + std::to_string(r.collisions) + ")";
            }
        }
        out << line.erase(line.find_last_not_of(' ') + 1) << "\n";
        first = false;
    };
    const auto below = [&](const std::string& text) {
        out << cell("", case_width) << "  " << text << "\n";
    };
    if (!r.refusal.empty()) {
        row(r.expected_refusal ? "refused up front, as it must be" : "refused up front", "-", "-",
            r.passed());
        below("refused: " + r.refusal);
        return;
    }
    if (r.expected_refusal) {
        row("not refused up front, but it must be", "-", "-", false);
    }
    if (!r.stopped.empty()) {
        row("stopped during the run", "-", "-", false);
        below("stopped: " + r.stopped);
    }
    for (const StressRow& s : r.rows) {
        row(s.invariant, sci(s.worst), bound_text(s), s.passed);
        if (!s.passed) {
            below(s.detail);
        }
    }
}

nlohmann::json number_or_null(double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json to_json(const StressResult& r) {
    nlohmann::json rows = nlohmann::json::array();
    for (const StressRow& row : r.rows) {
        const char* kind = row.kind == Bound::at_most ? "at_most"
                           : row.kind == Bound::above ? "above"
                                                      : "finite";
        rows.push_back({{"invariant", row.invariant},
                        {"worst", number_or_null(row.worst)},
                        {"bound", number_or_null(row.bound)},
                        {"kind", kind},
                        {"passed", row.passed},
                        {"detail", row.detail}});
    }
    return {{"name", r.name},
            {"description", r.description},
            {"passed", r.passed()},
            {"expected_refusal", r.expected_refusal},
            {"refusal", r.refusal.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.refusal)},
            {"stopped", r.stopped.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.stopped)},
            {"seconds", r.seconds},
            {"steps", r.steps},
            {"collisions", r.collisions},
            {"rows", std::move(rows)}};
}

// Runs the cases in order, each row printed as soon as its case is done
// (the matrix takes seconds), with the progress bar between rows.
std::vector<StressResult> run_cases(const std::vector<StressCase>& cases, bool json, bool quiet,
                                    std::ostream& out) {
    std::vector<StressResult> results;
    Progress progress("stress", progress_wanted(quiet));
    progress.set_total(cases.size(), "cases");
    for (const StressCase& c : cases) {
        progress.set_item(c.name);
        results.push_back(run_stress_case(c));
        progress.advance();
        if (!json) {
            progress.without_bar([&] {
                write_case(results.back(), out);
                out.flush();
            });
        }
    }
    return results;
}

} // namespace

int stress_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& /*err*/) {
    const Arguments a =
        parse_arguments(args, {"--case"}, {"--help", "--json", "--list", "--quiet"});
    if (a.has_flag("--help")) {
        out << stress_help;
        return exit_ok;
    }
    if (!a.positional.empty()) {
        throw UsageError("takes no positional arguments, got '" + a.positional.front() + "'");
    }
    std::vector<StressCase> cases = stress_cases();
    if (const auto list = a.option("--case")) {
        std::vector<StressCase> chosen;
        for (const std::string& name : comma_list(*list)) {
            const auto it = std::find_if(cases.begin(), cases.end(),
                                         [&](const StressCase& c) { return c.name == name; });
            if (it == cases.end()) {
                throw UsageError("no stress case '" + name +
                                 "'; 'impulse stress --list' names them");
            }
            chosen.push_back(*it);
        }
        cases = std::move(chosen);
    }
    if (a.has_flag("--list")) {
        for (const StressCase& c : cases) {
            out << cell(c.name, case_width) << c.description << "\n";
        }
        return exit_ok;
    }

    const bool json = a.has_flag("--json");
    const auto started = std::chrono::steady_clock::now();
    if (!json) {
        out << "stress: " << cases.size()
            << " cases; the worst value of each invariant over every frame against its bound\n\n";
        write_header(out);
    }
    const std::vector<StressResult> results = run_cases(cases, json, a.has_flag("--quiet"), out);
    const double total =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const auto failed = static_cast<std::size_t>(std::count_if(
        results.begin(), results.end(), [](const StressResult& r) { return !r.passed(); }));
    const auto refused = static_cast<std::size_t>(
        std::count_if(results.begin(), results.end(),
                      [](const StressResult& r) { return r.passed() && r.expected_refusal; }));

    if (json) {
        nlohmann::json list = nlohmann::json::array();
        for (const StressResult& r : results) {
            list.push_back(to_json(r));
        }
        out << nlohmann::json{{"cases", std::move(list)},
                              {"passed", failed == 0},
                              {"failed", failed},
                              {"refused_as_expected", refused},
                              {"seconds", total}}
                   .dump(2)
            << "\n";
    } else {
        out << "\n"
            << results.size() << " cases: " << results.size() - failed - refused << " passed, "
            << refused << " refused as expected, " << failed << " failed; " << seconds_text(total)
            << "\n";
    }
    return failed == 0 ? exit_ok : exit_failed;
}

} // namespace impulse::harness::cli
