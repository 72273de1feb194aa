// Comparing a new trajectory with a golden (docs/design.md, "Comparing and the
// golden workflow"): first the shape (scene, columns, frame and event counts,
// event bodies), then every value that both trajectories have.
#include "compare.h"

#include "channel_scale.h"
#include "number_format.h"
#include "scaled_difference.h"
#include "trajectory_columns.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>

namespace impulse::harness {

namespace {

// A report stays readable when hundreds of columns differ.
constexpr std::size_t max_divergence_lines = 40;
constexpr std::size_t max_listed_columns = 10;

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

std::optional<std::size_t> index_of(const std::vector<std::string>& names,
                                    const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) {
        return std::nullopt;
    }
    return static_cast<std::size_t>(it - names.begin());
}

// Where each name first stands in `names`, as std::find would find it: one
// lookup per column instead of a scan, for trajectories of 600,001 columns.
class ColumnIndex {
  public:
    explicit ColumnIndex(const std::vector<std::string>& names) {
        for (std::size_t i = 0; i < names.size(); ++i) {
            positions_.emplace(names[i], i);
        }
    }
    std::optional<std::size_t> operator()(const std::string& name) const {
        const auto it = positions_.find(name);
        if (it == positions_.end()) {
            return std::nullopt;
        }
        return it->second;
    }

  private:
    std::map<std::string, std::size_t> positions_;
};

std::size_t channel_index(Channel channel) {
    return static_cast<std::size_t>(channel);
}

// "a, b, c" or "a, b, ... and 7 more".
std::string join_names(const std::vector<std::string>& names) {
    std::string text;
    for (std::size_t i = 0; i < names.size() && i < max_listed_columns; ++i) {
        text += (i == 0 ? "" : ", ") + names[i];
    }
    if (names.size() > max_listed_columns) {
        text += " and " + std::to_string(names.size() - max_listed_columns) + " more";
    }
    return text;
}

std::vector<std::string> missing_from(const std::vector<std::string>& names,
                                      const std::vector<std::string>& other) {
    std::vector<std::string> missing;
    const ColumnIndex in_other(other);
    for (const std::string& name : names) {
        if (!in_other(name)) {
            missing.push_back(name);
        }
    }
    return missing;
}

// The common columns in the order `names` has them.
std::vector<std::string> common_in_order(const std::vector<std::string>& names,
                                         const std::vector<std::string>& other) {
    std::vector<std::string> common;
    const ColumnIndex in_other(other);
    for (const std::string& name : names) {
        if (in_other(name)) {
            common.push_back(name);
        }
    }
    return common;
}

std::string bodies(const TrajectoryEvent& event) {
    return event.a + " and " + event.b;
}

// Column gc of gold and column vc of value hold the same bits in every frame
// both have (a short frame, reported as structural, is skipped).
bool same_column_values(const Trajectory& gold, std::size_t gc, const Trajectory& value,
                        std::size_t vc) {
    const std::size_t frames = std::min(gold.frames.size(), value.frames.size());
    for (std::size_t k = 0; k < frames; ++k) {
        const std::vector<double>& g = gold.frames[k];
        const std::vector<double>& v = value.frames[k];
        if (gc < g.size() && vc < v.size() && !same_bits(g[gc], v[vc])) {
            return false;
        }
    }
    return true;
}

void check_columns(const Trajectory& gold, const Trajectory& value,
                   std::vector<std::string>& structural) {
    const std::vector<std::string> only_gold = missing_from(gold.columns, value.columns);
    const std::vector<std::string> only_new = missing_from(value.columns, gold.columns);
    if (!only_gold.empty()) {
        structural.push_back("columns only in the golden: " + join_names(only_gold));
    }
    if (!only_new.empty()) {
        structural.push_back("columns only in the new trajectory: " + join_names(only_new));
    }
    // Values are matched by column name, so an order change alone still
    // compares; but the format fixes the order, so it is a difference.
    if (common_in_order(gold.columns, value.columns) !=
        common_in_order(value.columns, gold.columns)) {
        structural.push_back("the columns are in a different order (values are compared by name)");
    }
    // A column without a channel has no tolerance, so it is compared bit for
    // bit only, and is a difference only when its values differ: a trajectory
    // is still identical to itself (found by fuzz/fuzz_diff).
    std::vector<std::string> unknown;
    const ColumnIndex in_value(value.columns);
    for (std::size_t gc = 0; gc < gold.columns.size(); ++gc) {
        const std::string& column = gold.columns[gc];
        const std::optional<std::size_t> vc = in_value(column);
        if (vc && !column_channel(column) && !same_column_values(gold, gc, value, *vc)) {
            unknown.push_back(column);
        }
    }
    if (!unknown.empty()) {
        structural.push_back("columns that are neither t nor BODY.x, .y, .angle, .vx, .vy or "
                             ".omega differ, and no tolerance applies to them: " +
                             join_names(unknown));
    }
}

// A frame whose length does not match the columns cannot come from
// read_trajectory, but a hand-built trajectory can have one; report the first.
void check_frame_lengths(const Trajectory& trajectory, const char* which,
                         std::vector<std::string>& structural) {
    for (std::size_t k = 0; k < trajectory.frames.size(); ++k) {
        if (trajectory.frames[k].size() != trajectory.columns.size()) {
            structural.push_back(std::string(which) + " frames[" + std::to_string(k) + "] has " +
                                 std::to_string(trajectory.frames[k].size()) + " values for " +
                                 std::to_string(trajectory.columns.size()) + " columns");
            return;
        }
    }
}

void check_events(const Trajectory& gold, const Trajectory& value,
                  std::vector<std::string>& structural) {
    const std::size_t common = std::min(gold.events.size(), value.events.size());
    if (gold.events.size() != value.events.size()) {
        structural.push_back("event counts differ: golden " + std::to_string(gold.events.size()) +
                             ", new " + std::to_string(value.events.size()) + "; the first " +
                             std::to_string(common) + " are compared");
    }
    // Once one event pairs other bodies, the later ones usually do too: one
    // sentence for the first and a count of the rest.
    std::optional<std::size_t> first;
    std::size_t later = 0;
    for (std::size_t k = 0; k < common; ++k) {
        const TrajectoryEvent& g = gold.events[k];
        const TrajectoryEvent& v = value.events[k];
        if (g.a != v.a || g.b != v.b) {
            if (first) {
                ++later;
            } else {
                first = k;
            }
        }
    }
    if (first) {
        std::string sentence = "events[" + std::to_string(*first) + "] is between " +
                               bodies(gold.events[*first]) + " in the golden but between " +
                               bodies(value.events[*first]) + " in the new trajectory";
        if (later > 0) {
            sentence += ", and " + std::to_string(later) + " later event" +
                        (later == 1 ? " also pairs" : "s also pair") + " other bodies";
        }
        structural.push_back(sentence + "; events with other bodies are not compared");
    }
}

std::string exact_text(double value);

std::vector<std::string> structural_differences(const Trajectory& gold, const Trajectory& value) {
    std::vector<std::string> structural;
    if (gold.scene != value.scene) {
        structural.push_back("the scene names differ: golden '" + gold.scene + "', new '" +
                             value.scene + "'");
    }
    // A stopped run is never a golden, and never matches one.
    for (const auto& [which, trajectory] :
         {std::pair{"the golden", &gold}, {"the new run", &value}}) {
        if (trajectory->partial) {
            structural.push_back(
                std::string(which) +
                " is partial: it stopped at t = " + exact_text(trajectory->partial->t) + " s (" +
                trajectory->partial->reason + "); a partial trajectory is never a golden");
        }
    }
    check_columns(gold, value, structural);
    if (gold.frames.size() != value.frames.size()) {
        structural.push_back("frame counts differ: golden " + std::to_string(gold.frames.size()) +
                             ", new " + std::to_string(value.frames.size()) + "; the first " +
                             std::to_string(std::min(gold.frames.size(), value.frames.size())) +
                             " are compared");
    }
    check_frame_lengths(gold, "golden", structural);
    check_frame_lengths(value, "new", structural);
    check_events(gold, value, structural);
    return structural;
}

// The largest finite |value| among `values`: a channel's scale.
void widen_scale(double& scale, double value) {
    if (std::isfinite(value)) {
        scale = std::max(scale, std::fabs(value));
    }
}

// Compares one value and counts it in its channel. The maxima cover every
// compared value, not only the failing ones, so a tolerance-mode pass still
// shows how close it came. Returns the divergence (column, frame and t left
// for the caller) when the value fails: in exact mode when any bit differs,
// in tolerance mode when it is outside the channel's tolerance.
std::optional<Divergence> compare_value(Comparison& result,
                                        const std::optional<Tolerances>& tolerances,
                                        Channel channel, double gold, double value, double scale) {
    Divergence d;
    d.channel = channel;
    d.gold = gold;
    d.value = value;
    d.abs_diff = std::fabs(value - gold);
    d.rel_diff = relative_at_scale(gold, value, scale);
    d.ulp = ulp_at_scale(gold, value, scale);

    ChannelSummary& summary = result.channels[channel_index(channel)];
    ++summary.compared;
    summary.max_abs = std::max(summary.max_abs, d.abs_diff);
    summary.max_rel = std::max(summary.max_rel, d.rel_diff);
    summary.max_ulp = std::max(summary.max_ulp, d.ulp);

    const bool same = same_bits(gold, value);
    result.identical = result.identical && same;
    // The ULP bound also holds at the channel's scale, the ULP the report
    // shows; that count is never above the one within() takes.
    const bool fails =
        tolerances
            ? !(within(*(*tolerances)[channel], gold, value) ||
                (!std::isnan(gold) && !std::isnan(value) && d.ulp <= (*tolerances)[channel]->ulp))
            : !same;
    if (!fails) {
        return std::nullopt;
    }
    ++summary.differing;
    return d;
}

void compare_frames(const Trajectory& gold, const Trajectory& value,
                    const std::optional<Tolerances>& tolerances, Comparison& result) {
    const std::size_t frames = std::min(gold.frames.size(), value.frames.size());
    const std::optional<std::size_t> gold_t = index_of(gold.columns, "t");
    const ColumnIndex in_value(value.columns);
    const std::vector<double> scales = column_scales(gold);
    for (std::size_t gc = 0; gc < gold.columns.size(); ++gc) {
        const std::string& column = gold.columns[gc];
        const std::optional<std::size_t> vc = in_value(column);
        const std::optional<Channel> channel = column_channel(column);
        if (!vc || !channel) {
            continue; // reported as structural
        }
        const double scale = scales[gc];
        bool diverged = false;
        for (std::size_t k = 0; k < frames; ++k) {
            const std::vector<double>& g = gold.frames[k];
            const std::vector<double>& v = value.frames[k];
            if (gc >= g.size() || *vc >= v.size()) {
                continue; // a short frame, reported as structural
            }
            std::optional<Divergence> d =
                compare_value(result, tolerances, *channel, g[gc], v[*vc], scale);
            if (d && !diverged) {
                diverged = true;
                d->column = column;
                d->frame = k;
                d->t = gold_t && *gold_t < g.size() ? g[*gold_t]
                                                    : std::numeric_limits<double>::quiet_NaN();
                result.first_divergences.push_back(*d);
            }
        }
    }
}

struct EventField {
    const char* name;
    Channel channel;
};

// In file order; the channel mapping is tolerance.h's.
constexpr std::array<EventField, 8> event_fields = {{
    {"t", Channel::event_time},
    {"point.x", Channel::position},
    {"point.y", Channel::position},
    {"normal.x", Channel::angle},
    {"normal.y", Channel::angle},
    {"impulse", Channel::impulse},
    {"vn_before", Channel::velocity},
    {"vn_after", Channel::velocity},
}};

std::array<double, 8> event_values(const TrajectoryEvent& e) {
    return {e.t,         e.point[0], e.point[1],  e.normal[0],
            e.normal[1], e.impulse,  e.vn_before, e.vn_after};
}

void compare_events(const Trajectory& gold, const Trajectory& value,
                    const std::optional<Tolerances>& tolerances, Comparison& result) {
    const std::size_t common = std::min(gold.events.size(), value.events.size());
    std::array<double, event_fields.size()> scales{};
    // A contact point is a position in the scene: measured at the scale of the
    // bodies' positions too, so a point on a floor at y = 0 (its y 1e-12 or
    // so, rounding) does not count its rounding in ULPs of 1e-12.
    const double positions = position_scale(gold);
    scales[1] = positions;
    scales[2] = positions;
    for (const TrajectoryEvent& e : gold.events) {
        const std::array<double, 8> values = event_values(e);
        for (std::size_t f = 0; f < scales.size(); ++f) {
            widen_scale(scales[f], values[f]);
        }
    }
    bool recorded = false; // only the first divergent event is listed
    for (std::size_t k = 0; k < common; ++k) {
        const TrajectoryEvent& ge = gold.events[k];
        const TrajectoryEvent& ve = value.events[k];
        if (ge.a != ve.a || ge.b != ve.b) {
            continue; // reported as structural
        }
        const std::array<double, 8> g = event_values(ge);
        const std::array<double, 8> v = event_values(ve);
        for (std::size_t f = 0; f < event_fields.size(); ++f) {
            std::optional<Divergence> d =
                compare_value(result, tolerances, event_fields[f].channel, g[f], v[f], scales[f]);
            if (d && !recorded) {
                recorded = true;
                d->column = "events[" + std::to_string(k) + "]." + event_fields[f].name;
                d->frame = k;
                d->t = ge.t;
                result.first_divergences.push_back(*d);
            }
        }
    }
}

// --- describe ---

// format_double for golden and new values; it refuses non-finite values,
// which only a hand-built trajectory can hold.
std::string exact_text(double value) {
    if (std::isnan(value)) {
        return "nan";
    }
    if (std::isinf(value)) {
        return value > 0 ? "inf" : "-inf";
    }
    return format_double(value);
}

// Two significant digits: differences are read for their size.
std::string rough_text(double value) {
    if (std::isnan(value)) {
        return "nan";
    }
    if (std::isinf(value)) {
        return value > 0 ? "inf" : "-inf";
    }
    char buffer[32];
    const std::to_chars_result r =
        std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 2);
    return std::string(buffer, r.ptr);
}

// Rows of cells, each column padded to its widest cell, two spaces apart.
std::string aligned(const std::vector<std::vector<std::string>>& rows) {
    std::vector<std::size_t> widths;
    for (const auto& row : rows) {
        widths.resize(std::max(widths.size(), row.size()), 0);
        for (std::size_t c = 0; c < row.size(); ++c) {
            widths[c] = std::max(widths[c], row[c].size());
        }
    }
    std::string text;
    for (const auto& row : rows) {
        std::string line = " ";
        for (std::size_t c = 0; c < row.size(); ++c) {
            line += " " + row[c];
            if (c + 1 < row.size()) {
                line += std::string(widths[c] - row[c].size() + 1, ' ');
            }
        }
        text += line + "\n";
    }
    return text;
}

std::string divergence_section(const std::vector<Divergence>& divergences) {
    std::vector<std::vector<std::string>> rows;
    for (std::size_t i = 0; i < divergences.size() && i < max_divergence_lines; ++i) {
        const Divergence& d = divergences[i];
        rows.push_back({d.column, "t = " + exact_text(d.t), "golden " + exact_text(d.gold),
                        "new " + exact_text(d.value), "abs " + rough_text(d.abs_diff),
                        "rel " + rough_text(d.rel_diff), "ulp " + std::to_string(d.ulp)});
    }
    std::string text = "first divergence per body and channel:\n" + aligned(rows);
    if (divergences.size() > max_divergence_lines) {
        text +=
            "  ... and " + std::to_string(divergences.size() - max_divergence_lines) + " more\n";
    }
    return text;
}

std::string channel_section(const std::array<ChannelSummary, channel_count>& channels) {
    std::vector<std::vector<std::string>> rows;
    for (std::size_t i = 0; i < channels.size(); ++i) {
        const ChannelSummary& s = channels[i];
        if (s.compared == 0) {
            continue;
        }
        rows.push_back(
            {channel_names[i],
             std::to_string(s.differing) + "/" + std::to_string(s.compared) + " values differ",
             "max abs " + rough_text(s.max_abs), "max rel " + rough_text(s.max_rel),
             "max ulp " + std::to_string(s.max_ulp)});
    }
    return rows.empty() ? "" : "per channel:\n" + aligned(rows);
}

} // namespace

Comparison compare(const Trajectory& gold, const Trajectory& value,
                   const std::optional<Tolerances>& tolerances) {
    if (tolerances) {
        // No silent defaults: callers check channels_without_tolerance first
        // and report the missing channels as bad input.
        const std::vector<Channel> missing = channels_without_tolerance(gold, *tolerances);
        if (!missing.empty()) {
            throw std::invalid_argument(std::string("compare: no tolerance for channel '") +
                                        channel_names[channel_index(missing.front())] + "'");
        }
    }
    Comparison result;
    result.structural = structural_differences(gold, value);
    compare_frames(gold, value, tolerances, result);
    compare_events(gold, value, tolerances, result);
    result.event_time_slack = event_time_slack(gold);

    bool values_pass = true;
    for (const ChannelSummary& summary : result.channels) {
        values_pass = values_pass && summary.differing == 0;
    }
    result.identical = result.identical && result.structural.empty();
    result.passed = result.structural.empty() && values_pass;
    return result;
}

std::string describe(const Comparison& comparison) {
    if (comparison.identical) {
        return "identical\n";
    }
    std::string text;
    if (!comparison.structural.empty()) {
        text += "the trajectories differ in shape:\n";
        for (const std::string& sentence : comparison.structural) {
            text += "  " + sentence + "\n";
        }
    }
    if (!comparison.first_divergences.empty()) {
        text += divergence_section(comparison.first_divergences);
    }
    return text + channel_section(comparison.channels);
}

} // namespace impulse::harness
