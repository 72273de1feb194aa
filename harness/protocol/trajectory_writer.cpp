// The trajectory is written by the harness's own writer (write_trajectory), so
// an engine's output reads exactly like a golden; only the cost block, which
// a golden never holds, is added after it.
#include "trajectory_writer.h"

#include "number_format.h"

#include <cmath>
#include <stdexcept>

namespace impulse::protocol {

namespace {

// A JSON string literal of a setting's value. Setting values are names
// ("rk4", "bisection"); quotes and backslashes are still escaped.
std::string json_string(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
        }
        out += c;
    }
    return out + '"';
}

} // namespace

TrajectoryWriter::TrajectoryWriter(const harness::Scene& scene, const std::string& engine)
    : dt_(scene.dt) {
    trajectory_.scene = scene.name;
    // The harness ignores it and writes its own; this one keeps the text a
    // valid golden for `impulse diff`.
    trajectory_.scene_sha256 = scene.sha256;
    trajectory_.engine = engine;
    trajectory_.columns = {"t"};
    for (const harness::SceneBody& body : scene.bodies) {
        if (!body.is_static) {
            for (const char* channel : {".x", ".y", ".angle", ".vx", ".vy", ".omega"}) {
                trajectory_.columns.push_back(body.name + channel);
            }
            ++dynamic_bodies_;
        }
    }
    frames_expected_ = static_cast<std::size_t>(harness::step_count(scene)) + 1;
}

void TrajectoryWriter::setting(const std::string& key, const std::string& value) {
    trajectory_.solver.emplace_back(key, json_string(value));
}

void TrajectoryWriter::setting(const std::string& key, const char* value) {
    setting(key, std::string(value));
}

void TrajectoryWriter::setting(const std::string& key, double value) {
    if (!std::isfinite(value)) {
        throw std::logic_error("the setting '" + key + "' is not a finite number");
    }
    trajectory_.solver.emplace_back(key, harness::format_double(value));
}

void TrajectoryWriter::frame(const std::vector<BodyState>& dynamic_bodies) {
    if (dynamic_bodies.size() != dynamic_bodies_) {
        throw std::logic_error("a frame needs the state of each of the scene's " +
                               std::to_string(dynamic_bodies_) + " dynamic bodies, got " +
                               std::to_string(dynamic_bodies.size()));
    }
    if (trajectory_.frames.size() == frames_expected_) {
        throw std::logic_error("the scene has " + std::to_string(frames_expected_) +
                               " frames (steps + 1); one more was written");
    }
    // k * dt, never a running sum: the protocol checks t against k * dt.
    std::vector<double> row = {static_cast<double>(trajectory_.frames.size()) * dt_};
    row.reserve(1 + 6 * dynamic_bodies_);
    for (const BodyState& s : dynamic_bodies) {
        row.insert(row.end(), {s.x, s.y, s.angle, s.vx, s.vy, s.omega});
    }
    // JSON has no NaN or infinity: said here, where the engine can still be
    // named and the value placed, not when the text is written.
    for (std::size_t i = 1; i < row.size(); ++i) {
        if (!std::isfinite(row[i])) {
            throw std::domain_error("frame " + std::to_string(trajectory_.frames.size()) +
                                    " (t = " + harness::format_double(row[0]) +
                                    " s): " + trajectory_.columns[i] + " is " +
                                    harness::significant_text(row[i], 3) +
                                    "; JSON has no such number (stop with a sentence, or throw "
                                    "protocol::Unsupported if the scene is beyond the engine)");
        }
    }
    trajectory_.frames.push_back(std::move(row));
}

void TrajectoryWriter::event(const harness::TrajectoryEvent& event) {
    const double values[] = {event.t,         event.point[0], event.point[1],  event.normal[0],
                             event.normal[1], event.impulse,  event.vn_before, event.vn_after};
    for (const double v : values) {
        if (!std::isfinite(v)) {
            throw std::domain_error("the collision of '" + event.a + "' and '" + event.b +
                                    "' at t = " + harness::significant_text(event.t, 17) +
                                    " s has a value that is " + harness::significant_text(v, 3) +
                                    "; JSON has no such number");
        }
    }
    trajectory_.events.push_back(event);
}

void TrajectoryWriter::cost(double seconds, std::optional<long long> steps) {
    // The harness refuses any other cost: better said here, by the engine.
    if (!std::isfinite(seconds) || seconds < 0.0 || (steps && *steps < 0)) {
        throw std::logic_error("a cost is seconds >= 0 and steps >= 0");
    }
    cost_seconds_ = seconds;
    cost_steps_ = steps;
}

std::string TrajectoryWriter::text() const {
    if (trajectory_.frames.size() != frames_expected_) {
        throw std::logic_error("the scene has " + std::to_string(frames_expected_) +
                               " frames (steps + 1); " + std::to_string(trajectory_.frames.size()) +
                               " were written");
    }
    std::string text = harness::write_trajectory(trajectory_);
    if (cost_seconds_) {
        // write_trajectory ends the object with "\n}\n": the cost goes before it.
        std::string cost = ",\n  \"cost\": {\"seconds\": " + harness::format_double(*cost_seconds_);
        if (cost_steps_) {
            cost += ", \"steps\": " + std::to_string(*cost_steps_);
        }
        text.insert(text.size() - 3, cost + "}");
    }
    return text;
}

} // namespace impulse::protocol
