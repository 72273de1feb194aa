// impulse compare's table for people (engine_comparison.h).
#include "engine_comparison.h"
#include "input_error.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace impulse::harness {

namespace {

// About six significant digits: a table is read, not parsed (--json has
// every double exactly).
std::string short_number(std::optional<double> value) {
    if (!value) {
        return "-";
    }
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", *value);
    return buffer;
}

// "+3.35%": an engine's error against a non-zero exact answer, relative.
std::string percent(double value, double exact) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%+.3g%%", 100.0 * (value - exact) / std::abs(exact));
    return buffer;
}

// An engine's cell: its value, its relative error where the exact answer is
// not 0 (where it is 0, the value is the error), " !" for the judged
// reference outside the tolerance, "unsupported" for an engine that refused.
std::string cell(const EngineComparison& c, const ObservableReadings& r, std::size_t i) {
    if (!c.engines[i].run) {
        return "unsupported";
    }
    const std::optional<double>& v = r.values[i];
    std::string text = short_number(v);
    if (v && r.exact && *r.exact != 0.0) {
        text += " (" + percent(*v, *r.exact) + ")";
    }
    if (judged_column(c) == i && !r.within(i)) {
        text += " !";
    }
    return text;
}

void write_table(std::string& out, const EngineComparison& c) {
    std::vector<std::vector<std::string>> lines;
    std::vector<std::string> header = {"observable", "exact"};
    for (const EngineColumn& e : c.engines) {
        header.push_back(e.name);
    }
    lines.push_back(header);
    for (const ObservableReadings& r : c.rows) {
        std::vector<std::string> line = {r.name, short_number(r.exact)};
        for (std::size_t i = 0; i < c.engines.size(); ++i) {
            line.push_back(cell(c, r, i));
        }
        lines.push_back(std::move(line));
    }
    std::vector<std::size_t> width(header.size(), 0);
    for (const auto& line : lines) {
        for (std::size_t i = 0; i < line.size(); ++i) {
            width[i] = std::max(width[i], line[i].size());
        }
    }
    for (const auto& line : lines) {
        std::string text;
        for (std::size_t i = 0; i < line.size(); ++i) {
            // The name column reads left to right; numbers line up on the right.
            text += "  " + padded(line[i], width[i], i != 0);
        }
        out += text + "\n";
    }
    for (const ObservableReadings& r : c.rows) {
        if (!r.note.empty()) {
            out += "  note: " + r.path + ", " + r.name + ": " + r.note + "\n";
        }
    }
}

// "key=value, ...": the run's solver block as recorded, values as JSON.
std::string settings_text(const EngineColumn& e) {
    std::string text;
    for (const auto& [key, value] : e.settings) {
        text += (text.empty() ? "" : ", ") + key + "=" + value;
    }
    return text;
}

std::string command_text(const std::vector<std::string>& command) {
    std::string text;
    for (const std::string& word : command) {
        text += word + " ";
    }
    return text + "SCENE";
}

void write_scene(std::string& out, const EngineComparison& c, std::size_t name_width) {
    out += "\n" + c.name + " (" + printable_path(c.file) + ")";
    if (c.nothing_declared()) {
        out += ": no observables declared (the scene has no box2d.observables block)\n";
        return;
    }
    if (c.skipped()) {
        out += ": skipped, " + c.engines.front().unsupported + "\n";
        return;
    }
    out +=
        ": dt " + short_number(c.dt) + " s (the scene's integrator: " + c.scene_integrator + ")\n";
    for (const EngineColumn& e : c.engines) {
        out += "  " + padded(e.name, name_width) + "  ";
        if (!e.run) {
            out += e.unsupported + "\n";
            continue;
        }
        out += e.engine + ": " + settings_text(e) + "\n";
        if (!e.command.empty()) {
            out += "  " + std::string(name_width, ' ') + "  command: " + command_text(e.command) +
                   "\n";
        }
    }
    if (!c.stopped.empty()) {
        out += "  " + c.stopped + "\n";
    }
    write_table(out, c);
}

void write_engine_summary(std::string& out, const ComparisonReport& report,
                          const std::string& engine, std::size_t width) {
    std::size_t ran = 0, refused = 0, rows = 0, outside = 0;
    for (const EngineComparison& c : report.scenes) {
        for (std::size_t i = 0; i < c.engines.size(); ++i) {
            if (c.engines[i].name != engine) {
                continue;
            }
            ran += c.engines[i].run ? 1 : 0;
            refused += c.engines[i].run ? 0 : 1;
            if (judged_column(c) == i) {
                rows += c.rows.size();
                outside += rows_outside(c);
            }
        }
    }
    std::string line = "  " + padded(engine, width) + "  ran " + plural(ran, "scene", "scenes");
    if (refused > 0) {
        line += ", " + std::to_string(refused) + " unsupported";
    }
    if (const std::optional<WorstError> worst = worst_error(report.scenes, engine)) {
        char buffer[40];
        std::snprintf(buffer, sizeof buffer, "%.3g%%", 100.0 * worst->relative);
        line += "; worst error against the exact answer " + std::string(buffer) + " (" +
                worst->scene + ", " + worst->row + ")";
    } else {
        line += "; no row with an exact answer";
    }
    if (engine == judged_reference) {
        line += "; " + std::to_string(rows - outside) + " of " + plural(rows, "row", "rows") +
                " within the scenes' tolerance of " + report.engine;
    }
    out += line + "\n";
}

void write_summary(std::string& out, const ComparisonReport& report, bool summary_only) {
    std::size_t width = report.engine.size();
    for (const ReferenceEngine& r : report.references) {
        width = std::max(width, r.name.size());
    }
    for (const ReferenceEngine& r : report.skipped) {
        width = std::max(width, r.name.size());
    }
    out += "\neach engine (worst error: |value - exact| / |exact| over the rows whose exact "
           "answer is not 0):\n";
    write_engine_summary(out, report, report.engine, width);
    for (const ReferenceEngine& r : report.references) {
        write_engine_summary(out, report, r.name, width);
    }
    for (const ReferenceEngine& r : report.skipped) {
        out += "  " + padded(r.name, width) + "  skipped, not on this machine (" + r.missing +
               "); install it with: " + r.install + "\n";
    }
    std::size_t name_width = 4;
    for (const EngineComparison& c : report.scenes) {
        name_width = std::max(name_width, c.name.size());
    }
    std::size_t counts[4] = {0, 0, 0, 0}; // by SceneStatus
    std::string lines;
    for (const EngineComparison& c : report.scenes) {
        const SceneStatus status = scene_status(c);
        ++counts[static_cast<int>(status)];
        std::string label = "ok      ";
        std::string what;
        switch (status) {
        case SceneStatus::skipped:
            label = "skipped ";
            what = c.engines.front().unsupported;
            break;
        case SceneStatus::failed:
            label = "FAILED  ";
            what = std::to_string(rows_outside(c)) + " of " + std::to_string(c.rows.size()) + " " +
                   judged_reference + " rows outside tolerance";
            break;
        case SceneStatus::no_observables:
            label = "none    ";
            what = "no observables declared (no box2d.observables block), nothing compared";
            break;
        case SceneStatus::passed:
            what = judged_column(c)
                       ? std::string("all ") + judged_reference + " rows within tolerance"
                       : "compared (no " + std::string(judged_reference) + " column to judge)";
            break;
        }
        // The summary (scripts/gate) shows what needs a look; the totals
        // count the rest.
        const bool quiet_row =
            status == SceneStatus::passed || status == SceneStatus::no_observables;
        if (!summary_only || !quiet_row) {
            lines += "  " + label + padded(c.name, name_width) + "  " + what + "\n";
        }
    }
    out += (lines.empty() ? "" : "\n" + lines);
    out += scene_totals(report.scenes.size(), counts[0], counts[1], counts[2], counts[3]) + "\n";
}

} // namespace

std::string comparison_text(const ComparisonReport& report, bool summary_only) {
    std::string references;
    for (const ReferenceEngine& r : report.references) {
        references += (references.empty() ? "" : ", ") + r.name;
    }
    // Another engine is given the integrator as solver.integrator, which an
    // engine without integrators ignores (docs/engine-protocol.md, Overrides).
    const std::string integrator = report.scene_integrator ? "each scene's own integrator"
                                                           : "symplectic-euler, Box2D's integrator";
    const std::string given =
        report.engine_is_impulse
            ? integrator
            : "given " + integrator + ", which an engine without integrators ignores";
    std::string out = "compare: " + plural(report.scenes.size(), "scene", "scenes") + "; " +
                      report.engine + " (" + given + ") beside " +
                      (references.empty() ? "no reference" : references) + "\n";
    for (const std::string& note : report.notes) {
        out += "  " + note + "\n";
    }
    if (!summary_only) {
        std::size_t width = report.engine.size();
        for (const ReferenceEngine& r : report.references) {
            width = std::max(width, r.name.size());
        }
        for (const EngineComparison& c : report.scenes) {
            write_scene(out, c, width);
        }
        out += "\nA cell is the engine's value and, where the exact answer is not 0, its error "
               "against it;\n" +
               std::string(judged_reference) +
               " is judged against the scene's box2d block (! outside atol + rtol |" +
               report.engine +
               "|),\nthe other references are shown for scale. Why they differ: "
               "docs/references.md.\n";
    }
    write_summary(out, report, summary_only);
    return out;
}

} // namespace impulse::harness
