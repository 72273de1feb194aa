// The world's things as SVG: static bodies, a body's outline at one pose,
// contact points with their normals, and the arrow they are drawn with.
// Arrowheads are paths rather than markers, so the pictures need no element
// ids and several can be inlined in one HTML page.
#pragma once

#include "scene.h"
#include "tracks.h"
#include "trajectory.h"
#include "vec2.h"
#include "viewport.h"

#include <cstddef>
#include <string>
#include <vector>

namespace impulse::harness::picture {

// "x,y x,y ...": the points in picture pixels.
std::string polygon_points(const View& view, const std::vector<Vec2>& points);

// The scene's static bodies, each clipped to the view.
void draw_static_bodies(std::string& out, const View& view, const Scene* scene);

// The body's outline at one pose; a circle with a radius line so that its
// rotation shows. Without a shape, a small ring with a line at the body's angle.
void draw_outline(std::string& out, const View& view, const Track& track, const Pose& pose,
                  double stroke_opacity, double fill_opacity, const std::string& style,
                  std::size_t frame, double t);

// An arrow from `from` (picture pixels) along the world direction `d`, as one
// path: the shaft, then a closed head.
std::string arrow_d(double fx, double fy, Vec2 d, double length);

// "t = 0.4667 s", or "t = 0.4515, 1.174 s" for several times at one place.
std::string time_text(const std::vector<double>& times);
// A time label in small grey type with a white halo, its left end at (x, y)
// (picture pixels): the time a key frame or a contact mark shows.
void draw_time_label(std::string& out, double x, double y, const std::string& text);

// Each event's contact point as a dot and its normal (pointing toward body a)
// as a short arrow; `hollow` draws golden events as rings.
void draw_events(std::string& out, const View& view, const std::vector<TrajectoryEvent>& events,
                 bool hollow, const char* extra_class);

} // namespace impulse::harness::picture
