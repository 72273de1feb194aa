// What the pictures read from a trajectory (tracks.h).
#include "tracks.h"

#include "text.h"
#include "trajectory_columns.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

namespace impulse::harness::picture {

namespace {

std::string solver_value(const Trajectory& trajectory, const std::string& key) {
    for (const auto& [k, v] : trajectory.solver) {
        if (k == key) {
            std::string text = v;
            if (text.size() >= 2 && text.front() == '"' && text.back() == '"') {
                text = text.substr(1, text.size() - 2);
            }
            return text;
        }
    }
    return "";
}

} // namespace

std::size_t column_index(const Trajectory& trajectory, const std::string& name) {
    for (std::size_t i = 1; i < trajectory.columns.size(); ++i) {
        if (trajectory.columns[i] == name) {
            return i;
        }
    }
    return npos;
}

ColumnLookup::ColumnLookup(const Trajectory& trajectory) {
    index_.reserve(trajectory.columns.size());
    for (std::size_t i = 1; i < trajectory.columns.size(); ++i) {
        index_.emplace(trajectory.columns[i], i); // the first of a repeated name, as the scan
    }
}

std::size_t ColumnLookup::operator()(const std::string& name) const {
    const auto it = index_.find(name);
    return it == index_.end() ? npos : it->second;
}

std::vector<Track> tracks_of(const Trajectory& trajectory, const Scene* scene) {
    const ColumnLookup column(trajectory);
    std::unordered_map<std::string, const SceneBody*> dynamic_bodies;
    if (scene != nullptr) {
        for (const SceneBody& body : scene->bodies) {
            if (!body.is_static) {
                dynamic_bodies[body.name] = &body; // the last of a name, as the scan did
            }
        }
    }
    std::vector<Track> tracks;
    for (std::size_t i = 1; i < trajectory.columns.size(); ++i) {
        const std::string& column_name = trajectory.columns[i];
        const std::string x_suffix = body_channel_suffixes[0];
        if (column_name.size() <= x_suffix.size() ||
            column_name.compare(column_name.size() - x_suffix.size(), x_suffix.size(), x_suffix) !=
                0) {
            continue;
        }
        Track track;
        track.name = column_name.substr(0, column_name.size() - x_suffix.size());
        track.x = i;
        track.y = column(track.name + body_channel_suffixes[1]);
        if (track.y == npos) {
            continue;
        }
        track.angle = column(track.name + body_channel_suffixes[2]);
        const auto body = dynamic_bodies.find(track.name);
        if (body != dynamic_bodies.end()) {
            track.body = body->second;
        }
        track.colour = palette[tracks.size() % palette.size()];
        tracks.push_back(std::move(track));
    }
    return tracks;
}

std::vector<Track> tracks_in(const Trajectory& trajectory, const std::vector<Track>& tracks) {
    const ColumnLookup column(trajectory);
    std::vector<Track> found;
    found.reserve(tracks.size());
    for (const Track& track : tracks) {
        Track t = track;
        t.x = column(track.name + body_channel_suffixes[0]);
        t.y = column(track.name + body_channel_suffixes[1]);
        t.angle = column(track.name + body_channel_suffixes[2]);
        found.push_back(std::move(t));
    }
    return found;
}

bool has_position(const Track& track) {
    return track.x != npos && track.y != npos;
}

bool pose_at(const Trajectory& trajectory, const Track& track, std::size_t frame, Pose& pose) {
    const std::vector<double>& row = trajectory.frames[frame];
    if (track.x >= row.size() || track.y >= row.size()) {
        return false;
    }
    pose.p = {row[track.x], row[track.y]};
    pose.angle = track.angle < row.size() ? row[track.angle] : 0.0;
    return std::isfinite(pose.p.x) && std::isfinite(pose.p.y) && std::isfinite(pose.angle);
}

Box motion_bounds(const Trajectory& trajectory, const std::vector<Track>& tracks) {
    Box b;
    for (const Track& track : tracks) {
        for (std::size_t k = 0; k < trajectory.frames.size(); ++k) {
            Pose pose;
            if (!pose_at(trajectory, track, k, pose)) {
                continue;
            }
            if (track.body == nullptr) {
                b.add(pose.p.x, pose.p.y);
            } else if (track.body->shape.type == ShapeType::circle) {
                b.add(pose.p.x, pose.p.y, track.body->shape.radius);
            } else {
                b.add(box_of(world_outline(track.body->shape, pose.p, pose.angle)));
            }
        }
    }
    for (const TrajectoryEvent& event : trajectory.events) {
        b.add(event.point[0], event.point[1]);
    }
    return b;
}

// The largest coordinate a picture frames: beyond it a width overflows to
// infinity; a body further out is drawn past the edge.
constexpr double farthest_framed = 1e300;
// The smallest span a picture frames, relative to where it is: below it the
// scale to pixels overflows (an outside review's body moving 1e-320 m drew a
// 0 x 0 picture), and nothing smaller than rounding is there to see.
constexpr double least_relative_span = 1e-9;

Box framed(Box motion, const Scene* scene) {
    if (motion.empty()) {
        motion = {-1.0, -1.0, 1.0, 1.0};
    }
    motion =
        motion.intersection({-farthest_framed, -farthest_framed, farthest_framed, farthest_framed});
    const double extent = std::max(
        {std::abs(motion.x0), std::abs(motion.x1), std::abs(motion.y0), std::abs(motion.y1), 1.0});
    const double span = std::max(motion.width(), motion.height());
    const double margin =
        span > least_relative_span * extent ? 0.08 * span : std::max(0.5, 1e-3 * extent);
    Box b = motion.grown(margin);
    if (scene != nullptr) {
        const Box near = motion.grown(std::max(2.0 * margin, 0.12 * span));
        for (const SceneBody& body : scene->bodies) {
            if (body.is_static) {
                const Box part =
                    box_of(world_outline(body.shape, body.position, body.angle)).intersection(near);
                b.add(part);
            }
        }
    }
    return b;
}

std::string path_points(const View& view, const Trajectory& trajectory, const Track& track) {
    std::string text;
    double last_x = infinity, last_y = infinity;
    std::string pending;
    for (std::size_t k = 0; k < trajectory.frames.size(); ++k) {
        Pose pose;
        if (!pose_at(trajectory, track, k, pose)) {
            continue;
        }
        const double x = view.sx(pose.p.x), y = view.sy(pose.p.y);
        const std::string point = f2(x) + "," + f2(y);
        if (std::abs(x - last_x) < 0.5 && std::abs(y - last_y) < 0.5) {
            pending = point;
            continue;
        }
        text += (text.empty() ? "" : " ") + point;
        pending.clear();
        last_x = x;
        last_y = y;
    }
    if (!pending.empty()) {
        text += " " + pending;
    }
    return text;
}

std::vector<std::size_t> key_frames(std::size_t count, std::size_t wanted) {
    std::vector<std::size_t> frames;
    if (count == 0) {
        return frames;
    }
    if (count <= wanted) {
        for (std::size_t k = 0; k < count; ++k) {
            frames.push_back(k);
        }
        return frames;
    }
    for (std::size_t k = 0; k < wanted; ++k) {
        frames.push_back((k * (count - 1) + (wanted - 1) / 2) / (wanted - 1));
    }
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    return frames;
}

std::string run_info(const Trajectory& trajectory) {
    std::string info = trajectory.engine;
    const std::string integrator = solver_value(trajectory, "integrator");
    if (!integrator.empty()) {
        info += ", " + integrator;
    }
    const std::size_t n = trajectory.frames.size();
    info += " \u00b7 " + plural(n, "frame", "frames");
    if (n > 0 && !trajectory.frames.front().empty()) {
        info += " (t = " + readable(trajectory.frames.front()[0]) + " to " +
                readable(trajectory.frames.back()[0]) + " s)";
    }
    info += " \u00b7 " + plural(trajectory.events.size(), "collision", "collisions");
    return info;
}

} // namespace impulse::harness::picture
