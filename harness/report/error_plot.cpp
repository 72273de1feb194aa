// The error over time (error_plot.h).
#include "error_plot.h"

#include "svg.h"
#include "tolerance.h"
#include "tracks.h"
#include "viewport.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

namespace impulse::harness::picture {

namespace {

constexpr double error_floor = 1e-18;
constexpr int floor_decade = -18;

// Which of the four frame channels a column belongs to; -1 for "t" and others.
int frame_channel(const std::string& column) {
    const std::optional<Channel> channel = column_channel(column);
    if (!channel || static_cast<std::size_t>(*channel) >= frame_channel_count) {
        return -1;
    }
    return static_cast<int>(*channel);
}

std::string decade_label(int e) {
    switch (e) {
    case -2:
        return "0.01";
    case -1:
        return "0.1";
    case 0:
        return "1";
    case 1:
        return "10";
    case 2:
        return "100";
    default:
        return "1e" + std::to_string(e);
    }
}

// Where a time and an error land in the panel: time linear from the first
// frame to the last, the error by decades from error_floor up to a top decade
// above the worst error, spaced so that the labelled decades include it.
struct ErrorScale {
    double left = 0.0, top = 0.0, width = 0.0, height = 0.0;
    double t0 = 0.0, t1 = 1.0;
    int top_decade = -15;
    int every = 1; // every how many decades a label

    ErrorScale(const ErrorSeries& series, double left_, double top_, double width_, double height_)
        : left(left_), top(top_), width(width_), height(height_) {
        double worst = 0.0;
        for (const auto& channel : series.error) {
            for (const double e : channel) {
                worst = std::max(worst, e);
            }
        }
        while (top_decade < 300 && std::pow(10.0, top_decade) < worst) {
            ++top_decade;
        }
        t0 = series.t.empty() ? 0.0 : series.t.front();
        t1 = series.t.empty() ? 1.0 : series.t.back();
        if (!(t1 > t0)) {
            t1 = t0 + 1.0;
        }
        const int decades = top_decade - floor_decade;
        every = decades <= 10 ? 1 : (decades <= 30 ? 3 : 10);
        while ((top_decade - floor_decade) % every != 0) {
            ++top_decade; // labelled decades evenly spaced, the top one included
        }
    }
    double px(double t) const { return left + (t - t0) / (t1 - t0) * width; }
    double py(double e) const {
        const double clamped = std::max(e, error_floor);
        const double l = std::isfinite(clamped) ? std::log10(clamped) : top_decade;
        const double s = (l - floor_decade) / (top_decade - floor_decade);
        return top + height - std::clamp(s, 0.0, 1.0) * height;
    }
};

void draw_error_grid(std::string& out, const ErrorScale& s) {
    const double left = s.left, top = s.top, width = s.width, height = s.height;
    out += "<rect" + attr("x", f2(left)) + attr("y", f2(top)) + attr("width", f2(width)) +
           attr("height", f2(height)) + " fill=\"#fcfcfc\"/>\n";
    std::string lines;
    for (int e = floor_decade; e <= s.top_decade; ++e) {
        if ((e - floor_decade) % s.every != 0) {
            continue;
        }
        const double y = s.py(std::pow(10.0, e));
        lines += "M" + f2(left) + " " + f2(y) + "H" + f2(left + width);
        text_at(out, left - 6.0, y + 3.5, decade_label(e), small_size, muted,
                " text-anchor=\"end\"");
    }
    const double step = nice_step((s.t1 - s.t0) / 8.0);
    for (const double t : ticks(s.t0, s.t1, step)) {
        lines += "M" + f2(s.px(t)) + " " + f2(top) + "V" + f2(top + height);
        text_at(out, s.px(t), top + height + 14.0, readable(t), small_size, muted,
                " text-anchor=\"middle\"");
    }
    out += "<path" + attr("d", lines) + " stroke=\"" + grid_colour + "\" fill=\"none\"/>\n";
    text_at(out, left + width, top + height + 28.0, "t (s)", small_size, muted,
            " text-anchor=\"end\"");
    text_at(out, left, top - 8.0, "|new \u2212 gold|", small_size, muted, " text-anchor=\"start\"");
}

// Frames that fall in the same pixel column keep only their first, smallest,
// largest and last value, in time order.
std::vector<std::size_t> frames_drawn(const ErrorScale& s, const ErrorSeries& series,
                                      std::size_t c) {
    std::vector<std::size_t> chosen;
    std::size_t k = 0;
    while (k < series.t.size()) {
        const auto column = static_cast<long long>(std::floor(s.px(series.t[k])));
        std::size_t lo = k, hi = k, end = k;
        while (end < series.t.size() &&
               static_cast<long long>(std::floor(s.px(series.t[end]))) == column) {
            if (series.error[c][end] < series.error[c][lo]) {
                lo = end;
            }
            if (series.error[c][end] > series.error[c][hi]) {
                hi = end;
            }
            ++end;
        }
        std::array<std::size_t, 4> picks = {k, lo, hi, end - 1};
        std::sort(picks.begin(), picks.end());
        for (std::size_t i = 0; i < picks.size(); ++i) {
            if (i == 0 || picks[i] != picks[i - 1]) {
                chosen.push_back(picks[i]);
            }
        }
        k = end;
    }
    return chosen;
}

// Per channel one polyline.
void draw_error_lines(std::string& out, const ErrorScale& s, const ErrorSeries& series) {
    for (std::size_t c = 0; c < frame_channel_count; ++c) {
        std::string points;
        for (const std::size_t i : frames_drawn(s, series, c)) {
            points += (points.empty() ? "" : " ") + f2(s.px(series.t[i])) + "," +
                      f2(s.py(series.error[c][i]));
        }
        out += "<polyline class=\"error\"" + attr("data-channel", channel_names[c]) +
               attr("points", points) + attr("stroke", channel_colours[c]) +
               " stroke-width=\"1.6\" fill=\"none\" stroke-linejoin=\"round\"" +
               (c == 0 ? std::string() : attr("stroke-dasharray", channel_dashes[c])) + "/>\n";
    }
}

} // namespace

std::string channel_label(std::size_t channel) {
    std::string label = channel_names[channel];
    std::replace(label.begin(), label.end(), '_', ' ');
    return label;
}

ErrorSeries error_series(const Trajectory& gold, const Trajectory& value) {
    ErrorSeries series;
    std::vector<std::pair<std::size_t, std::size_t>> pairs; // gold column, new column
    std::vector<int> channel;
    const ColumnLookup value_column(value);
    for (std::size_t i = 1; i < gold.columns.size(); ++i) {
        const int c = frame_channel(gold.columns[i]);
        const std::size_t j = value_column(gold.columns[i]);
        if (c >= 0 && j != npos) {
            pairs.emplace_back(i, j);
            channel.push_back(c);
        }
    }
    const std::size_t n = std::min(gold.frames.size(), value.frames.size());
    for (std::size_t k = 0; k < n; ++k) {
        const std::vector<double>& g = gold.frames[k];
        const std::vector<double>& v = value.frames[k];
        if (g.empty()) {
            continue;
        }
        series.t.push_back(g[0]);
        std::array<double, frame_channel_count> worst{};
        for (std::size_t p = 0; p < pairs.size(); ++p) {
            if (pairs[p].first >= g.size() || pairs[p].second >= v.size()) {
                continue;
            }
            double e = std::abs(v[pairs[p].second] - g[pairs[p].first]);
            if (std::isnan(e)) {
                e = infinity;
            }
            auto& w = worst[static_cast<std::size_t>(channel[p])];
            w = std::max(w, e);
        }
        for (std::size_t c = 0; c < frame_channel_count; ++c) {
            series.error[c].push_back(worst[c]);
        }
    }
    return series;
}

double draw_error_panel(std::string& out, const ErrorSeries& series, double left, double top,
                        double width, double height, const Divergence* first) {
    const ErrorScale s(series, left, top, width, height);
    out += "<g class=\"error-panel\">\n";
    draw_error_grid(out, s);
    if (first != nullptr && std::isfinite(first->t) && first->t >= s.t0 && first->t <= s.t1) {
        out += "<path class=\"divergence-time\"" +
               attr("d", "M" + f2(s.px(first->t)) + " " + f2(top) + "V" + f2(top + height)) +
               " stroke=\"" + divergence_colour +
               "\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\" fill=\"none\"/>\n";
    }
    draw_error_lines(out, s, series);
    out += "<rect" + attr("x", f2(left)) + attr("y", f2(top)) + attr("width", f2(width)) +
           attr("height", f2(height)) + " fill=\"none\" stroke=\"#bbbbbb\"/>\n";
    out += "</g>\n";
    return top + height;
}

} // namespace impulse::harness::picture
