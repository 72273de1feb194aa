// The scorecard as a table for people (scorecard.h).
#include "input_error.h"
#include "number_format.h"
#include "scorecard.h"
#include "svg.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

namespace {

constexpr std::size_t table_width = 100;
constexpr std::size_t indent = 4; // a check's row, under its expectation's line

// One check across the engines: the engine under test's, and each
// reference's check of the same expectation and key (null where it has none).
struct Row {
    std::string path;
    std::string key;
    std::vector<const ExpectationResult*> by_engine;
};

// The engine under test's checks in its order; a reference's check it lacks
// (it found fewer impacts, or did not run) after the last row of the same
// expectation, or at the end.
std::vector<Row> rows_of(const SceneScore& scene) {
    std::vector<Row> rows;
    const std::size_t engines = scene.engines.size();
    for (std::size_t e = 0; e < engines; ++e) {
        for (const ExpectationResult& r : scene.engines[e].results) {
            const std::string key = check_key(r);
            auto row = std::find_if(rows.begin(), rows.end(), [&](const Row& x) {
                return x.path == r.path && x.key == key && x.by_engine[e] == nullptr;
            });
            if (row == rows.end()) {
                auto after = std::find_if(rows.rbegin(), rows.rend(),
                                          [&](const Row& x) { return x.path == r.path; });
                row = rows.insert(after == rows.rend() ? rows.end() : after.base(),
                                  Row{r.path, key, {}});
                row->by_engine.assign(engines, nullptr);
            }
            row->by_engine[e] = &r;
        }
    }
    return rows;
}

// "drop of 'box'" of "drop of 'box': impact 1 time"; empty when the key has no subject.
std::string subject_of(const std::string& key) {
    const std::size_t colon = key.find(": ");
    return colon == std::string::npos ? "" : key.substr(0, colon);
}

std::string label_of(const std::string& key, const std::string& subject) {
    return !subject.empty() && key.rfind(subject + ": ", 0) == 0 ? key.substr(subject.size() + 2)
                                                                 : key;
}

std::optional<double> abs_error(const ExpectationResult& r) {
    if (!r.allowed) {
        return std::nullopt;
    }
    return std::abs(r.actual - r.expected);
}

std::string value_cell(std::optional<double> value, int digits) {
    return value ? significant_text(*value, digits) : "-";
}

// A reference's cell: its absolute error, "!" when outside its allowance.
std::string reference_cell(const EngineScore& engine, const ExpectationResult* r) {
    if (engine.outcome == EngineScore::Outcome::unsupported) {
        return "skip";
    }
    if (engine.outcome == EngineScore::Outcome::error) {
        return "error";
    }
    if (r == nullptr) {
        return "-";
    }
    const std::string mark = r->passed ? "" : " !";
    const std::optional<double> off = abs_error(*r);
    return off ? significant_text(*off, 2) + mark : (r->passed ? "ok" : "!");
}

// The first of the engines' checks in the row, for the exact value when the
// engine under test has none.
const ExpectationResult* first_numeric(const Row& row) {
    for (const ExpectationResult* r : row.by_engine) {
        if (r != nullptr && r->allowed) {
            return r;
        }
    }
    return nullptr;
}

std::vector<std::string> cells_of(const SceneScore& scene, const Row& row) {
    const ExpectationResult* mine = row.by_engine[0];
    const ExpectationResult* exact = mine != nullptr && mine->allowed ? mine : first_numeric(row);
    std::vector<std::string> cells;
    cells.push_back(value_cell(exact ? std::optional(exact->expected) : std::nullopt, 6));
    const bool numeric = mine != nullptr && mine->allowed;
    cells.push_back(value_cell(numeric ? std::optional(mine->actual) : std::nullopt, 6));
    const std::optional<double> off = numeric ? abs_error(*mine) : std::nullopt;
    cells.push_back(value_cell(off, 2));
    cells.push_back(value_cell(off && mine->expected != 0.0
                                   ? std::optional(*off / std::abs(mine->expected))
                                   : std::nullopt,
                               2));
    cells.push_back(value_cell(numeric ? mine->allowed : std::nullopt, 2));
    cells.push_back(mine == nullptr ? "-" : mine->passed ? "yes" : "NO");
    for (std::size_t e = 1; e < scene.engines.size(); ++e) {
        cells.push_back(reference_cell(scene.engines[e], row.by_engine[e]));
    }
    return cells;
}

// "passed 17 of 20", "unsupported: MESSAGE", "error: MESSAGE".
std::string tally(const EngineScore& e, bool with_message) {
    switch (e.outcome) {
    case EngineScore::Outcome::ran:
        return "passed " + std::to_string(e.within()) + " of " + std::to_string(e.results.size());
    case EngineScore::Outcome::unsupported:
        return with_message ? "unsupported: " + e.message : "unsupported";
    case EngineScore::Outcome::error:
        return with_message ? "error: " + e.message : "error";
    }
    return "";
}

// "NAME passed 17 of 20", "unsupported by NAME: MESSAGE" (the protocol's
// words for a refusal), "NAME error: MESSAGE".
std::string engine_tally(const EngineScore& e) {
    return e.outcome == EngineScore::Outcome::unsupported
               ? "unsupported by " + e.engine + ": " + e.message
               : e.engine + " " + tally(e, true);
}

// Under a failed check's row, in the table that has its NO: why, wrapped
// to the table's width (an outside review found the sentence, the only
// word on a check without numbers, listed far below its row).
void write_reason(std::string& out, const ExpectationResult* mine) {
    if (mine == nullptr || mine->passed) {
        return;
    }
    const std::string margin(indent + 2, ' ');
    const std::string why = mine->detail.empty() ? mine->what : mine->detail;
    for (const std::string& line : picture::wrap("NO: " + why, table_width - margin.size())) {
        out += margin + line + "\n";
    }
}

// Numbers right-aligned in columns as wide as their widest cell; the check's
// label gets what is left of the 100 columns, and a longer label a line of
// its own above its numbers. `header` names the columns of cells_of from
// `first` on.
void write_checks(std::string& out, const SceneScore& scene, const std::vector<Row>& rows,
                  const std::vector<std::string>& header, std::size_t first = 0) {
    std::vector<std::vector<std::string>> cells;
    std::vector<std::size_t> width(header.size());
    for (std::size_t c = 0; c < header.size(); ++c) {
        width[c] = header[c].size();
    }
    for (const Row& row : rows) {
        const std::vector<std::string> all = cells_of(scene, row);
        const auto from = all.begin() + static_cast<std::ptrdiff_t>(first);
        cells.emplace_back(from, from + static_cast<std::ptrdiff_t>(header.size()));
        for (std::size_t c = 0; c < header.size(); ++c) {
            width[c] = std::max(width[c], cells.back()[c].size());
        }
    }
    std::size_t numbers = 0;
    for (std::size_t w : width) {
        numbers += w + 2;
    }
    const std::size_t room =
        std::clamp<std::size_t>(table_width - std::min(table_width, indent + numbers), 12, 40);
    std::size_t longest = 5; // "check"
    for (const Row& row : rows) {
        const std::size_t size = label_of(row.key, subject_of(row.key)).size();
        longest = std::max(longest, size <= room ? size : 0);
    }
    const std::size_t label = std::min(longest, room);
    auto line = [&](const std::string& text, const std::vector<std::string>& row) {
        std::string l = std::string(indent, ' ') + padded(text, label);
        for (std::size_t c = 0; c < row.size(); ++c) {
            l += "  " + padded(row[c], width[c], true);
        }
        out += l + "\n";
    };
    line("check", header);
    std::string path;
    std::string subject;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (rows[i].path != path) {
            path = rows[i].path;
            subject = subject_of(rows[i].key);
            out += "  " + path + (subject.empty() ? "" : " " + subject) + "\n";
        }
        const std::string text = label_of(rows[i].key, subject);
        if (text.size() > label) {
            out += std::string(indent, ' ') + text + "\n";
            line("", cells[i]);
        } else {
            line(text, cells[i]);
        }
        if (first == 0) {
            write_reason(out, rows[i].by_engine.front());
        }
    }
}

void write_scene(std::string& out, const Scorecard& card, const SceneScore& scene) {
    out += "\n" + scene.name + " (" + printable_path(scene.file) + ")\n";
    for (const EngineScore& e : scene.engines) {
        out += "  " + engine_tally(e) + "\n";
    }
    const std::vector<Row> rows = rows_of(scene);
    if (!rows.empty()) {
        std::vector<std::string> header = {"exact", "value", "abs err", "rel err", "allowed", "ok"};
        // Two reference columns fit the 100 columns beside the engine's six;
        // more get a table of their own below, the same checks' rows.
        constexpr std::size_t beside = 2;
        if (card.references.size() <= beside) {
            header.insert(header.end(), card.references.begin(), card.references.end());
            write_checks(out, scene, rows, header);
        } else {
            write_checks(out, scene, rows, header);
            out += "  for scale, each reference's abs err on the same checks:\n";
            write_checks(out, scene, rows, card.references, header.size());
        }
    }
}

const char* status_word(const EngineScore& e) {
    switch (e.outcome) {
    case EngineScore::Outcome::ran:
        return e.passed() ? "ok" : "FAILED";
    case EngineScore::Outcome::unsupported:
        return "skipped";
    case EngineScore::Outcome::error:
        return "ERROR";
    }
    return "?";
}

void write_summary(std::string& out, const Scorecard& card) {
    std::size_t name_width = 4;
    for (const SceneScore& s : card.scenes) {
        name_width = std::max(name_width, s.name.size());
    }
    out += "\n" + card.engine + " on each scene:\n";
    for (const SceneScore& s : card.scenes) {
        const EngineScore& mine = s.engines.front();
        std::string line = "  " + padded(status_word(mine), 8) + padded(s.name, name_width) + "  ";
        line += mine.outcome == EngineScore::Outcome::unsupported ? engine_tally(mine)
                                                                  : tally(mine, true);
        std::string references;
        for (std::size_t e = 1; e < s.engines.size(); ++e) {
            references +=
                (e == 1 ? "" : ", ") + s.engines[e].engine + " " + tally(s.engines[e], false);
        }
        out += line + (references.empty() ? "" : "  (" + references + ")") + "\n";
    }
    const ConformanceCounts c = count_engine(card.scenes);
    out += plural(c.scenes, "scene", "scenes") + ": " + std::to_string(c.passed) + " passed, " +
           std::to_string(c.failed) + " failed, " + std::to_string(c.unsupported) +
           " unsupported, " + plural(c.errors, "error", "errors") + "; " +
           std::to_string(c.within) + " of " + plural(c.checks, "check", "checks") +
           " within the allowance\n";
    if (c.passed + c.failed == 0 && c.errors == 0) {
        out += card.engine + " ran none of the scenes: nothing was scored\n";
    }
    for (std::size_t e = 0; e < card.references.size(); ++e) {
        out += "  for scale, " + reference_tally(card, e + 1) + "\n";
    }
}

} // namespace

std::string reference_tally(const Scorecard& card, std::size_t index) {
    const ConformanceCounts c = count_engine(card.scenes, index);
    return card.references.at(index - 1) + ": " + std::to_string(c.within) + " of " +
           plural(c.checks, "check", "checks") + " within the allowance on " +
           plural(c.passed + c.failed, "scene", "scenes") + " it ran (" + std::to_string(c.passed) +
           " passed, " + std::to_string(c.failed) + " failed, " + std::to_string(c.unsupported) +
           " unsupported, " + plural(c.errors, "error", "errors") + ")";
}

std::string scorecard_text(const Scorecard& card) {
    std::string out = "conform: " + card.engine + " on " +
                      plural(card.scenes.size(), "conformance scene", "conformance scenes") +
                      " from " + printable_path(card.scenes_dir) + "\n";
    std::string references;
    for (const std::string& r : card.references) {
        references += (references.empty() ? "" : ", ") + r;
    }
    out += "  for scale: " + (references.empty() ? std::string("none") : references) + "\n";
    for (const std::string& note : card.notes) {
        out += "  " + note + "\n";
    }
    out += "  value: " + card.engine +
           "'s; abs err |value - exact|, rel err abs err / |exact|; allowed: the scene's\n"
           "  atol + rtol x scale; ok: abs err within it." +
           (references.empty() ? std::string()
                               // The names are in the line above: this one stays 100
                               // columns wide however many references there are.
                               : " Each reference's column: its abs err on the\n  same "
                                 "check (! outside the allowance, skip: the engine refused "
                                 "the scene).") +
           "\n";
    for (const SceneScore& scene : card.scenes) {
        write_scene(out, card, scene);
    }
    write_summary(out, card);
    return out;
}

} // namespace impulse::harness
