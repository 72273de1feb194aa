// The world in the picture (viewport.h).
#include "viewport.h"

#include "rotation.h"
#include "shape.h"

#include <cstddef>
#include <utility>

namespace impulse::harness::picture {

namespace {

constexpr double two_pi = 6.283185307179586;

} // namespace

std::vector<Vec2> world_outline(const Shape& shape, Vec2 position, double angle,
                                int circle_segments) {
    const Rotation q = rotation_of(angle);
    std::vector<Vec2> points;
    if (shape.type == ShapeType::circle) {
        for (int k = 0; k < circle_segments; ++k) {
            const Rotation step = rotation_of(two_pi * k / circle_segments);
            points.push_back(position + rotate(step, Vec2{shape.radius, 0.0}));
        }
        return points;
    }
    for (int i = 0; i < shape.polygon.count; ++i) {
        points.push_back(position + rotate(q, shape.polygon.vertices[static_cast<std::size_t>(i)]));
    }
    return points;
}

Box box_of(const std::vector<Vec2>& points) {
    Box b;
    for (const Vec2 p : points) {
        b.add(p.x, p.y);
    }
    return b;
}

std::vector<Vec2> clip_to(const std::vector<Vec2>& polygon, const Box& r) {
    std::vector<Vec2> current = polygon;
    for (int side = 0; side < 4 && !current.empty(); ++side) {
        auto inside = [&](Vec2 p) {
            switch (side) {
            case 0:
                return p.x >= r.x0;
            case 1:
                return p.x <= r.x1;
            case 2:
                return p.y >= r.y0;
            default:
                return p.y <= r.y1;
            }
        };
        auto crossing = [&](Vec2 a, Vec2 b) {
            double s = 0.0;
            switch (side) {
            case 0:
                s = (r.x0 - a.x) / (b.x - a.x);
                break;
            case 1:
                s = (r.x1 - a.x) / (b.x - a.x);
                break;
            case 2:
                s = (r.y0 - a.y) / (b.y - a.y);
                break;
            default:
                s = (r.y1 - a.y) / (b.y - a.y);
                break;
            }
            return a + s * (b - a);
        };
        std::vector<Vec2> next;
        for (std::size_t i = 0; i < current.size(); ++i) {
            const Vec2 a = current[i];
            const Vec2 b = current[(i + 1) % current.size()];
            if (inside(a)) {
                next.push_back(a);
                if (!inside(b)) {
                    next.push_back(crossing(a, b));
                }
            } else if (inside(b)) {
                next.push_back(crossing(a, b));
            }
        }
        current = std::move(next);
    }
    return current;
}

View fit_view(Box b, double max_width, double max_height) {
    if (b.empty()) {
        b = {-1.0, -1.0, 1.0, 1.0};
    }
    double w = b.width(), h = b.height();
    if (!(w > 0.0) && !(h > 0.0)) {
        b = b.grown(1.0);
        w = b.width();
        h = b.height();
    }
    const double cx = 0.5 * (b.x0 + b.x1), cy = 0.5 * (b.y0 + b.y1);
    constexpr double narrowest = 0.8, widest = 2.4; // width / height
    if (w < narrowest * h) {
        w = narrowest * h;
    }
    if (w > widest * h) {
        h = w / widest;
    }
    View view;
    view.x0 = cx - 0.5 * w;
    view.x1 = cx + 0.5 * w;
    view.y0 = cy - 0.5 * h;
    view.y1 = cy + 0.5 * h;
    view.scale = std::min(max_width / w, max_height / h);
    return view;
}

// 1, 2 or 5 times a power of ten, at least `raw`.
double nice_step(double raw) {
    if (!(raw > 0.0) || !std::isfinite(raw)) {
        return 1.0;
    }
    double p = 1.0;
    while (p * 10.0 <= raw) {
        p *= 10.0;
    }
    while (p > raw) {
        p /= 10.0;
    }
    for (const double m : {1.0, 2.0, 5.0}) {
        if (m * p >= raw) {
            return m * p;
        }
    }
    return 10.0 * p;
}

// Multiples of step within [lo, hi]: at most a few dozen.
std::vector<double> ticks(double lo, double hi, double step) {
    std::vector<double> values;
    const double first = std::ceil(lo / step - 1e-9);
    for (double k = first; k * step <= hi + 1e-9 * step && values.size() < 60; k += 1.0) {
        values.push_back(k * step);
    }
    return values;
}

void draw_frame_and_grid(std::string& out, const View& view, const char* x_name,
                         const char* y_name) {
    const double l = view.left, t = view.top, r = view.left + view.width(),
                 b = view.top + view.height();
    out += "<g class=\"grid\">\n";
    out += "<rect" + attr("x", f2(l)) + attr("y", f2(t)) + attr("width", f2(view.width())) +
           attr("height", f2(view.height())) + " fill=\"#fcfcfc\" stroke=\"none\"/>\n";
    const double step = nice_step(std::max(view.x1 - view.x0, view.y1 - view.y0) / 7.0);
    std::string lines;
    for (const double x : ticks(view.x0, view.x1, step)) {
        lines += "M" + f2(view.sx(x)) + " " + f2(t) + "V" + f2(b);
        text_at(out, view.sx(x), b + 14.0, readable(x), small_size, muted,
                " text-anchor=\"middle\"");
    }
    for (const double y : ticks(view.y0, view.y1, step)) {
        lines += "M" + f2(l) + " " + f2(view.sy(y)) + "H" + f2(r);
        text_at(out, l - 6.0, view.sy(y) + 3.5, readable(y), small_size, muted,
                " text-anchor=\"end\"");
    }
    out += "<path" + attr("d", lines) + " stroke=\"" + grid_colour +
           "\" stroke-width=\"1\" fill=\"none\"/>\n";
    text_at(out, r, b + 28.0, x_name, small_size, muted, " text-anchor=\"end\"");
    text_at(out, l - 6.0, t - 7.0, y_name, small_size, muted, " text-anchor=\"end\"");
    out += "</g>\n";
}

void draw_plot_border(std::string& out, const View& view) {
    out += "<rect class=\"border\"" + attr("x", f2(view.left)) + attr("y", f2(view.top)) +
           attr("width", f2(view.width())) + attr("height", f2(view.height())) +
           " fill=\"none\" stroke=\"#bbbbbb\" stroke-width=\"1\"/>\n";
}
} // namespace impulse::harness::picture
