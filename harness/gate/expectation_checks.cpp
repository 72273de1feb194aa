// Reading a trajectory for the expectations (expectation_checks.h).
#include "expectation_checks.h"

#include "trajectory_columns.h"

#include <algorithm>
#include <limits>
#include <map>

namespace impulse::harness {

namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

} // namespace

double field_of(const Motion& m, const std::string& field) {
    if (field == "x") {
        return m.position.x;
    }
    if (field == "y") {
        return m.position.y;
    }
    if (field == "angle") {
        return m.angle;
    }
    if (field == "vx") {
        return m.velocity.x;
    }
    if (field == "vy") {
        return m.velocity.y;
    }
    return field == "omega" ? m.omega : not_a_number;
}

double field_of(const TrajectoryEvent& e, const std::string& field) {
    if (field == "t") {
        return e.t;
    }
    if (field == "impulse") {
        return e.impulse;
    }
    if (field == "vn_before") {
        return e.vn_before;
    }
    if (field == "vn_after") {
        return e.vn_after;
    }
    if (field == "point.x" || field == "point.y") {
        return e.point[field == "point.x" ? 0 : 1];
    }
    if (field == "normal.x" || field == "normal.y") {
        return e.normal[field == "normal.x" ? 0 : 1];
    }
    return not_a_number;
}

const std::vector<double>* frame_after_event(const Trajectory& trajectory, std::size_t index,
                                             const std::vector<std::string>& bodies) {
    const double t = trajectory.events[index].t;
    const auto frame =
        std::find_if(trajectory.frames.begin(), trajectory.frames.end(),
                     [t](const std::vector<double>& f) { return frame_time(f) > t; });
    if (frame == trajectory.frames.end()) {
        return nullptr;
    }
    for (std::size_t k = index + 1; k < trajectory.events.size(); ++k) {
        const TrajectoryEvent& later = trajectory.events[k];
        if (later.t > frame_time(*frame)) {
            break;
        }
        for (const std::string& body : bodies) {
            if (involves(later, body)) {
                return nullptr;
            }
        }
    }
    return &*frame;
}

const SceneBody* scene_body(const Scene& scene, const std::string& name) {
    for (const SceneBody& body : scene.bodies) {
        if (body.name == name) {
            return &body;
        }
    }
    return nullptr;
}

// Every dynamic body with its columns; empty (after a failure) when the
// trajectory lacks a body's columns. The same as exact_answers.h's masses_of,
// with the columns found through an index: a gas of 10,000 bodies has 60,001
// columns, and searching them once per body takes over a second.
std::optional<std::vector<Mass>> masses_of(const Scene& scene, const Trajectory& trajectory,
                                           Checks& checks) {
    std::map<std::string, std::size_t> index;
    for (std::size_t c = 0; c < trajectory.columns.size(); ++c) {
        index.emplace(trajectory.columns[c], c); // the first of a repeated name, as std::find
    }
    std::vector<Mass> masses;
    for (const SceneBody& body : scene.bodies) {
        if (body.is_static) {
            continue;
        }
        std::size_t found[body_channel_suffixes.size()] = {};
        for (std::size_t i = 0; i < body_channel_suffixes.size(); ++i) {
            const auto it = index.find(body.name + body_channel_suffixes[i]);
            if (it == index.end()) {
                checks.failure("", "the trajectory has no columns for " + single_quoted(body.name));
                return std::nullopt;
            }
            found[i] = it->second;
        }
        const BodyColumns columns{found[0], found[1], found[2], found[3], found[4], found[5]};
        masses.push_back({&body, columns, body.rotation ? body.inertia : 0.0});
    }
    if (trajectory.frames.empty()) {
        checks.failure("", "the trajectory has no frames");
        return std::nullopt;
    }
    return masses;
}

} // namespace impulse::harness
