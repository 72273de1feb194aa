// The report page's plots over time (time_series.h).
#include "time_series.h"

#include "exact_answers.h"
#include "first_divergence.h"
#include "page_json.h"
#include "tracks.h"
#include "trajectory_columns.h"

#include <algorithm>
#include <cmath>

namespace impulse::harness {

namespace {

// The diverging frame columns, earliest first, then in column order.
std::vector<const Divergence*> diverging_channels(const Trajectory& gold,
                                                  const Comparison& comparison) {
    std::vector<const Divergence*> found;
    for (const Divergence& d : comparison.first_divergences) {
        if (!is_event_divergence(d) && picture::column_index(gold, d.column) != picture::npos) {
            found.push_back(&d);
        }
    }
    std::stable_sort(found.begin(), found.end(),
                     [](const Divergence* a, const Divergence* b) { return a->t < b->t; });
    return found;
}

std::string one_channel(const Trajectory& gold, const Trajectory& value, const std::string& name,
                        const std::vector<std::size_t>& frames) {
    const std::size_t g = picture::column_index(gold, name);
    const std::size_t v = picture::column_index(value, name);
    std::vector<double> t, golden, fresh, diff;
    for (const std::size_t k : frames) {
        const double a = value_at(gold.frames[k], g);
        const double b = v == picture::npos ? std::nan("") : value_at(value.frames[k], v);
        t.push_back(frame_time(gold.frames[k]));
        golden.push_back(a);
        fresh.push_back(b);
        diff.push_back(std::fabs(b - a));
    }
    return "{\"name\":" + json_string(name) + ",\"t\":" + json_numbers(t, 7) +
           ",\"gold\":" + json_numbers(golden, 8) + ",\"new\":" + json_numbers(fresh, 8) +
           ",\"diff\":" + json_numbers(diff, 3) + "}";
}

} // namespace

std::string channel_series_json(const Trajectory& gold, const Trajectory& value,
                                const Comparison& comparison,
                                const std::vector<std::size_t>& frames) {
    const std::vector<const Divergence*> channels = diverging_channels(gold, comparison);
    std::string out = "{\"list\":[";
    const std::size_t shown = std::min(channels.size(), max_plotted_channels);
    for (std::size_t i = 0; i < shown; ++i) {
        out += (i > 0 ? "," : "") + one_channel(gold, value, channels[i]->column, frames);
    }
    return out + "],\"more\":" + std::to_string(channels.size() - shown) + "}";
}

std::string totals_json(const Scene* scene, const Trajectory& run,
                        const std::vector<std::size_t>& frames) {
    if (scene == nullptr) {
        return "null";
    }
    std::string missing;
    const std::optional<std::vector<Mass>> masses = masses_of(*scene, run, missing);
    if (!masses) {
        return "null";
    }
    std::vector<double> t, energy, px, py, angular;
    for (const std::size_t k : frames) {
        const Totals totals = totals_in(run.frames[k], *masses, scene->gravity);
        t.push_back(frame_time(run.frames[k]));
        energy.push_back(totals.energy);
        px.push_back(totals.momentum.x);
        py.push_back(totals.momentum.y);
        angular.push_back(totals.angular_momentum);
    }
    return "{\"t\":" + json_numbers(t, 7) + ",\"E\":" + json_numbers(energy, 10) +
           ",\"px\":" + json_numbers(px, 10) + ",\"py\":" + json_numbers(py, 10) +
           ",\"L\":" + json_numbers(angular, 10) + "}";
}

} // namespace impulse::harness
