// What the three forms of impulse compare's output share (engine_comparison.h):
// which column is judged, whether a scene passed, an engine's worst error.
#include "engine_comparison.h"

#include "text.h"

#include <algorithm>
#include <cmath>

namespace impulse::harness {

std::optional<std::size_t> judged_column(const EngineComparison& c) {
    for (std::size_t i = 1; i < c.engines.size(); ++i) {
        if (c.engines[i].name == judged_reference && c.engines[i].run) {
            return i;
        }
    }
    return std::nullopt;
}

std::size_t rows_outside(const EngineComparison& c) {
    const std::optional<std::size_t> column = judged_column(c);
    if (!column) {
        return 0;
    }
    return static_cast<std::size_t>(
        std::count_if(c.rows.begin(), c.rows.end(),
                      [&](const ObservableReadings& r) { return !r.within(*column); }));
}

bool comparison_passed(const ComparisonReport& report) {
    return std::all_of(report.scenes.begin(), report.scenes.end(),
                       [](const EngineComparison& c) { return rows_outside(c) == 0; });
}

SceneStatus scene_status(const EngineComparison& c) {
    if (c.nothing_declared()) {
        return SceneStatus::no_observables;
    }
    if (c.skipped()) {
        return SceneStatus::skipped;
    }
    return rows_outside(c) > 0 ? SceneStatus::failed : SceneStatus::passed;
}

const char* status_name(SceneStatus status) {
    switch (status) {
    case SceneStatus::passed:
        return "passed";
    case SceneStatus::failed:
        return "failed";
    case SceneStatus::skipped:
        return "skipped";
    case SceneStatus::no_observables:
        return "no observables";
    }
    return "";
}

std::string scene_totals(std::size_t scenes, std::size_t passed, std::size_t failed,
                         std::size_t skipped, std::size_t no_observables) {
    return plural(scenes, "scene", "scenes") + ": " + std::to_string(passed) + " passed, " +
           std::to_string(failed) + " failed" +
           (skipped > 0 ? ", " + std::to_string(skipped) + " skipped" : "") +
           (no_observables > 0 ? ", " + std::to_string(no_observables) + " with no observables"
                               : "");
}

std::optional<WorstError> worst_error(const std::vector<EngineComparison>& scenes,
                                      const std::string& engine) {
    std::optional<WorstError> worst;
    for (const EngineComparison& c : scenes) {
        for (std::size_t i = 0; i < c.engines.size(); ++i) {
            if (c.engines[i].name != engine) {
                continue;
            }
            for (const ObservableReadings& r : c.rows) {
                if (!r.exact || *r.exact == 0.0 || !r.values[i]) {
                    continue;
                }
                const double relative = std::abs(*r.values[i] - *r.exact) / std::abs(*r.exact);
                // NaN is the worst of all: a run that blew up.
                if (!worst || relative > worst->relative || std::isnan(relative)) {
                    worst = WorstError{relative, c.name, r.name};
                }
            }
        }
    }
    return worst;
}

} // namespace impulse::harness
