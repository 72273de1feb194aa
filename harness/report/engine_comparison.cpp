// What the three forms of impulse compare's output share (engine_comparison.h):
// which column is judged, whether a scene passed, an engine's worst error.
#include "engine_comparison.h"

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
