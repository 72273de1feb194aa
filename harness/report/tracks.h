// What the pictures read from a trajectory: each dynamic body's columns (a
// track), its pose at a frame, where the motion goes, its path, the key
// frames, and the run's information line.
#pragma once

#include "scene.h"
#include "trajectory.h"
#include "vec2.h"
#include "viewport.h"

#include <cstddef>
#include <string>
#include <unordered_map>
#include <vector>

namespace impulse::harness::picture {

inline constexpr std::size_t npos = static_cast<std::size_t>(-1);

// A dynamic body as the trajectory's columns describe it.
struct Track {
    std::string name;
    std::size_t x = 0, y = 0, angle = npos;
    const SceneBody* body = nullptr; // its shape, when the scene is known
    const char* colour = "";
};

// The index of the column `name` (never "t"), npos when there is none.
std::size_t column_index(const Trajectory& trajectory, const std::string& name);

// Every column's index by name, built once: a picture of N bodies looks up
// 3 N columns, and a scan per lookup made render quadratic (an outside
// review: 10,000 bodies 1.2 s, 100,000 not done in two minutes).
class ColumnLookup {
  public:
    explicit ColumnLookup(const Trajectory& trajectory);
    // As column_index: never "t", npos when there is none.
    std::size_t operator()(const std::string& name) const;

  private:
    std::unordered_map<std::string, std::size_t> index_;
};
// Every body with .x and .y columns, in column order, each in its palette colour.
std::vector<Track> tracks_of(const Trajectory& trajectory, const Scene* scene);
// The same bodies' columns in another trajectory, one for one (x and y npos
// for a body it lacks).
std::vector<Track> tracks_in(const Trajectory& trajectory, const std::vector<Track>& tracks);
bool has_position(const Track& track);

struct Pose {
    Vec2 p;
    double angle = 0.0;
};

// False when the frame lacks the body's values or they are not finite.
bool pose_at(const Trajectory& trajectory, const Track& track, std::size_t frame, Pose& pose);

// Where the dynamic bodies go, shapes included, and where the collisions are.
Box motion_bounds(const Trajectory& trajectory, const std::vector<Track>& tracks);
// The motion with a margin, and the static bodies close to it (a 50 m ground
// contributes only the strip under the motion).
Box framed(Box motion, const Scene* scene);

// The polyline of the centre of mass, leaving out points closer than half a
// pixel to the last one kept (the picture cannot show them) but always
// keeping the last.
std::string path_points(const View& view, const Trajectory& trajectory, const Track& track);

// First, last and evenly spaced frames in between: about `wanted` of them.
std::vector<std::size_t> key_frames(std::size_t count, std::size_t wanted = 8);

// "impulse 0.1.0, verlet · 91 frames (t = 0 to 1.5 s) · 3 collisions".
std::string run_info(const Trajectory& trajectory);

} // namespace impulse::harness::picture
