// The scale each compared value is measured at (channel_scale.h).
#include "channel_scale.h"

#include "tolerance.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>

namespace impulse::harness {

namespace {

// Turning by dθ moves a point at R by R dθ: an angle's rounding is absolute.
constexpr double angle_scale_floor = 1.0; // rad

double column_maximum(const Trajectory& gold, std::size_t column) {
    double scale = 0.0;
    for (const std::vector<double>& frame : gold.frames) {
        if (column < frame.size() && std::isfinite(frame[column])) {
            scale = std::max(scale, std::fabs(frame[column]));
        }
    }
    return scale;
}

// The component a column shares its scale with ("x" with "y", "vx" with
// "vy"); empty for a quantity with no partner.
std::string partner_quantity(const std::string& quantity) {
    if (quantity == "x") {
        return "y";
    }
    if (quantity == "y") {
        return "x";
    }
    if (quantity == "vx") {
        return "vy";
    }
    if (quantity == "vy") {
        return "vx";
    }
    return {};
}

} // namespace

std::vector<double> column_scales(const Trajectory& gold) {
    std::vector<double> scales(gold.columns.size(), 0.0);
    std::map<std::string, std::size_t> index;
    for (std::size_t c = 0; c < gold.columns.size(); ++c) {
        scales[c] = column_maximum(gold, c);
        index.emplace(gold.columns[c], c);
    }
    std::vector<double> shared = scales;
    for (std::size_t c = 0; c < gold.columns.size(); ++c) {
        const std::string& column = gold.columns[c];
        const std::optional<Channel> channel = column_channel(column);
        if (channel == Channel::angle) {
            shared[c] = std::max(scales[c], angle_scale_floor);
            continue;
        }
        // The last dot, as column_channel reads it: a body name may hold dots.
        const std::size_t dot = column.rfind('.');
        if (!channel || dot == std::string::npos) {
            continue;
        }
        const std::string partner = partner_quantity(column.substr(dot + 1));
        if (partner.empty()) {
            continue;
        }
        const auto other = index.find(column.substr(0, dot + 1) + partner);
        if (other != index.end()) {
            shared[c] = std::max(scales[c], scales[other->second]);
        }
    }
    return shared;
}

double position_scale(const Trajectory& gold) {
    double scale = 0.0;
    for (std::size_t c = 0; c < gold.columns.size(); ++c) {
        if (column_channel(gold.columns[c]) == Channel::position) {
            scale = std::max(scale, column_maximum(gold, c));
        }
    }
    return scale;
}

} // namespace impulse::harness
