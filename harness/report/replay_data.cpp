// A failed scene's data for the report page (replay_data.h).
#include "replay_data.h"

#include "first_divergence.h"
#include "page_json.h"
#include "time_series.h"
#include "tracks.h"
#include "trajectory_columns.h"
#include "viewport.h"

#include <algorithm>
#include <cmath>

namespace impulse::harness {

namespace {

using picture::Track;

// Golden and new events beyond this many are left out of the replay (they
// are dots; a gas has a few hundred).
constexpr std::size_t max_events = 5000;

std::string shape_json(const Track& track) {
    std::string out = "{\"name\":" + json_string(track.name);
    if (track.body == nullptr) {
        return out + ",\"r\":0}";
    }
    const Shape& shape = track.body->shape;
    if (shape.type == ShapeType::circle) {
        return out + ",\"r\":" + json_number(shape.radius, 7) + "}";
    }
    std::vector<double> points;
    for (int i = 0; i < shape.polygon.count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        points.push_back(shape.polygon.vertices[k].x);
        points.push_back(shape.polygon.vertices[k].y);
    }
    return out + ",\"v\":" + json_numbers(points, 7) + "}";
}

std::string statics_json(const Scene* scene) {
    std::string out = "[";
    if (scene != nullptr) {
        bool first = true;
        for (const SceneBody& body : scene->bodies) {
            if (!body.is_static) {
                continue;
            }
            std::vector<double> points;
            for (const Vec2 p : picture::world_outline(body.shape, body.position, body.angle, 48)) {
                points.push_back(p.x);
                points.push_back(p.y);
            }
            out += (first ? "" : ",") + json_numbers(points, 7);
            first = false;
        }
    }
    return out + "]";
}

// One run at its frames: times, every body's x, y, angle per frame, its
// collisions (t, point, normal).
std::string run_json(const char* label, const Trajectory& run, const std::vector<Track>& tracks,
                     const std::vector<std::size_t>& frames) {
    const std::vector<Track> own = picture::tracks_in(run, tracks);
    std::vector<double> t;
    std::string poses = "[";
    for (std::size_t i = 0; i < frames.size(); ++i) {
        t.push_back(frame_time(run.frames[frames[i]]));
        std::vector<double> values;
        for (const Track& track : own) {
            picture::Pose pose;
            const bool known = picture::pose_at(run, track, frames[i], pose);
            values.push_back(known ? pose.p.x : std::nan(""));
            values.push_back(known ? pose.p.y : std::nan(""));
            values.push_back(known ? pose.angle : 0.0);
        }
        poses += (i > 0 ? "," : "") + json_numbers(values, 7);
    }
    std::string events = "[";
    const std::size_t shown = std::min(run.events.size(), max_events);
    for (std::size_t i = 0; i < shown; ++i) {
        const TrajectoryEvent& e = run.events[i];
        events += (i > 0 ? "," : "") +
                  json_numbers({e.t, e.point[0], e.point[1], e.normal[0], e.normal[1]}, 7);
    }
    return "{\"label\":" + json_string(label) + ",\"count\":" + std::to_string(run.frames.size()) +
           ",\"t\":" + json_numbers(t, 7) + ",\"pose\":" + poses + "],\"events\":" + events +
           "],\"events_total\":" + std::to_string(run.events.size()) + "}";
}

std::string first_json(const Divergence* first) {
    if (first == nullptr) {
        return "null";
    }
    return "{\"t\":" + json_number(first->t, 10) + ",\"column\":" + json_string(first->column) +
           "}";
}

} // namespace

std::size_t replay_frames_for(std::size_t bodies, std::size_t budget) {
    const std::size_t per_frame = 3 * std::max<std::size_t>(bodies, 1);
    return std::min(budget, std::max(replay_min_frames, replay_value_budget / per_frame));
}

std::string replay_json(const SceneCheck& check, std::size_t budget) {
    if (!check.gold || !check.value || check.gold->frames.empty() || check.value->frames.empty()) {
        return "";
    }
    const Scene* scene = check.scene ? &*check.scene : nullptr;
    const Trajectory& gold = *check.gold;
    const Trajectory& value = *check.value;
    const Divergence* first = check.comparison ? earliest_divergence(*check.comparison) : nullptr;
    const bool frame_divergence = first != nullptr && !is_event_divergence(*first);
    const std::size_t keep = frame_divergence ? first->frame : picture::npos;

    const std::vector<Track> tracks = picture::tracks_of(gold, scene);
    picture::Box motion = picture::motion_bounds(gold, tracks);
    const std::vector<Track> value_tracks = picture::tracks_in(value, tracks);
    motion.add(picture::motion_bounds(value, value_tracks));
    const picture::Box view = picture::framed(motion, scene);

    budget = replay_frames_for(tracks.size(), budget);
    const std::vector<std::size_t> gold_frames = sampled_frames(gold.frames.size(), budget, keep);
    const std::vector<std::size_t> value_frames = sampled_frames(value.frames.size(), budget, keep);
    const std::size_t common = std::min(gold.frames.size(), value.frames.size());
    const std::vector<std::size_t> shared = sampled_frames(common, budget, keep);

    std::string out = "{\"view\":" + json_numbers({view.x0, view.y0, view.x1, view.y1}, 7);
    out += ",\"bodies\":[";
    for (std::size_t i = 0; i < tracks.size(); ++i) {
        out += (i > 0 ? "," : "") + shape_json(tracks[i]);
    }
    out += "],\"statics\":" + statics_json(scene);
    out += ",\"runs\":[" + run_json("golden", gold, tracks, gold_frames) + "," +
           run_json("new", value, tracks, value_frames) + "]";
    out += ",\"first\":" + first_json(first);
    out += ",\"channels\":" + (check.comparison
                                   ? channel_series_json(gold, value, *check.comparison, shared)
                                   : std::string("{\"list\":[],\"more\":0}"));
    out += ",\"totals\":[" + totals_json(scene, gold, gold_frames) + "," +
           totals_json(scene, value, value_frames) + "]}";
    return out;
}

} // namespace impulse::harness
