// The world in the picture: rectangles in metres, the view that maps them to
// pixels (the world's y axis points up and the picture's down, and View::sy is
// where the flip happens), clipping, and the framed grid with its ticks.
// Rotations use the engine's rotation_of, not libm.
#pragma once

#include "shape.h"
#include "svg.h"
#include "vec2.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace impulse::harness::picture {

inline constexpr double infinity = std::numeric_limits<double>::infinity();

struct Box {
    double x0 = infinity, y0 = infinity, x1 = -infinity, y1 = -infinity;

    bool empty() const { return !(x0 <= x1 && y0 <= y1); }
    double width() const { return x1 - x0; }
    double height() const { return y1 - y0; }
    void add(double x, double y, double r = 0.0) {
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(r)) {
            return;
        }
        x0 = std::min(x0, x - r);
        y0 = std::min(y0, y - r);
        x1 = std::max(x1, x + r);
        y1 = std::max(y1, y + r);
    }
    void add(const Box& b) {
        if (!b.empty()) {
            add(b.x0, b.y0);
            add(b.x1, b.y1);
        }
    }
    Box grown(double m) const { return {x0 - m, y0 - m, x1 + m, y1 + m}; }
    Box intersection(const Box& b) const {
        return {std::max(x0, b.x0), std::max(y0, b.y0), std::min(x1, b.x1), std::min(y1, b.y1)};
    }
};

// The shape's outline in world coordinates; a circle becomes a polygon.
std::vector<Vec2> world_outline(const Shape& shape, Vec2 position, double angle,
                                int circle_segments = 96);
Box box_of(const std::vector<Vec2>& points);
// Sutherland-Hodgman: the part of a convex polygon inside the rectangle.
// Static bodies are clipped here rather than with an SVG clip path, so the
// pictures need no element ids and several can be inlined in one HTML page.
std::vector<Vec2> clip_to(const std::vector<Vec2>& polygon, const Box& r);

struct View {
    double x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0; // the world rectangle shown, metres
    double scale = 1.0;                            // pixels per metre
    double left = 0.0, top = 0.0;                  // where (x0, y1) lands in the picture

    double width() const { return (x1 - x0) * scale; }
    double height() const { return (y1 - y0) * scale; }
    double sx(double x) const { return left + (x - x0) * scale; }
    // y points up in the world and down in the picture.
    double sy(double y) const { return top + (y1 - y) * scale; }
    std::string point(Vec2 p) const { return f2(sx(p.x)) + "," + f2(sy(p.y)); }
    Box world() const { return {x0, y0, x1, y1}; }
};

// Fits the world rectangle into max_width x max_height pixels at one scale for
// both axes, first widening the narrow side so the picture is never a sliver.
View fit_view(Box b, double max_width, double max_height);

// 1, 2 or 5 times a power of ten, at least `raw`.
double nice_step(double raw);
// Multiples of step within [lo, hi]: at most a few dozen.
std::vector<double> ticks(double lo, double hi, double step);

void draw_frame_and_grid(std::string& out, const View& view, const char* x_name,
                         const char* y_name);
void draw_plot_border(std::string& out, const View& view);

} // namespace impulse::harness::picture
