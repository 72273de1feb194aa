#include "trajectory_columns.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace impulse::harness {

namespace {

std::optional<std::size_t> column_index(const Trajectory& trajectory, const std::string& name) {
    const auto it = std::find(trajectory.columns.begin(), trajectory.columns.end(), name);
    if (it == trajectory.columns.end()) {
        return std::nullopt;
    }
    return static_cast<std::size_t>(it - trajectory.columns.begin());
}

} // namespace

std::optional<BodyColumns> body_columns(const Trajectory& trajectory, const std::string& body) {
    std::size_t found[6] = {};
    for (std::size_t i = 0; i < 6; ++i) {
        const std::optional<std::size_t> index =
            column_index(trajectory, body + body_channel_suffixes[i]);
        if (!index) {
            return std::nullopt;
        }
        found[i] = *index;
    }
    return BodyColumns{found[0], found[1], found[2], found[3], found[4], found[5]};
}

double value_at(const std::vector<double>& frame, std::size_t column) {
    return column < frame.size() ? frame[column] : std::numeric_limits<double>::quiet_NaN();
}

double frame_time(const std::vector<double>& frame) {
    return value_at(frame, 0);
}

double event_time_slack(const Trajectory& trajectory) {
    const auto t = std::find(trajectory.columns.begin(), trajectory.columns.end(), "t");
    if (t == trajectory.columns.end() || trajectory.frames.size() < 2) {
        return 0.0;
    }
    const auto column = static_cast<std::size_t>(t - trajectory.columns.begin());
    const double step =
        value_at(trajectory.frames[1], column) - value_at(trajectory.frames[0], column);
    return std::isfinite(step) && step > 0.0 ? 1e-9 * step : 0.0;
}

bool involves(const TrajectoryEvent& event, const std::string& body) {
    return event.a == body || event.b == body;
}

std::vector<std::size_t> events_of(const Trajectory& trajectory, const std::string& body) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < trajectory.events.size(); ++i) {
        if (involves(trajectory.events[i], body)) {
            out.push_back(i);
        }
    }
    return out;
}

} // namespace impulse::harness
