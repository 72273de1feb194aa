// SVG pictures of motion (render.h), written by hand as text.
//
// Every coordinate is computed here in picture pixels: the world's y axis
// points up and the picture's down, and View::sy is where the flip happens.
// Coordinates are written with two decimals (a hundredth of a pixel) and
// nothing depends on the clock, the locale or addresses, so the same input
// always gives the same bytes. Rotations use the engine's rotation_of, not libm.
// There are no element ids (static bodies are clipped here, arrowheads are
// drawn as paths), so several pictures can be inlined in one HTML page.
#include "render.h"

#include "markup.h"
#include "progress.h"
#include "rotation.h"
#include "shape.h"
#include "text.h"
#include "vec2.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace impulse::harness {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr std::size_t npos = static_cast<std::size_t>(-1);
constexpr double two_pi = 6.283185307179586;

// ---- numbers ----------------------------------------------------------------

std::string without_trailing_zeros(std::string text) {
    if (text.find('.') != std::string::npos && text.find('e') == std::string::npos) {
        while (!text.empty() && text.back() == '0') {
            text.pop_back();
        }
        if (!text.empty() && text.back() == '.') {
            text.pop_back();
        }
    }
    if (text == "-0") {
        text = "0";
    }
    return text;
}

// A picture coordinate or length: two decimals, trailing zeros dropped.
std::string f2(double value) {
    if (!std::isfinite(value)) {
        value = 0.0;
    }
    value = std::clamp(value, -1e6, 1e6);
    char buffer[64];
    const auto result =
        std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, 2);
    return without_trailing_zeros(std::string(buffer, result.ptr));
}

// A number for people: at most `digits` significant digits ("0.7667", "3", "1.5e-07").
std::string readable(double value, int digits = 4) {
    if (std::isnan(value)) {
        return "NaN";
    }
    if (std::isinf(value)) {
        return value > 0 ? "inf" : "-inf";
    }
    char buffer[64];
    const auto result =
        std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, digits);
    std::string text(buffer, result.ptr);
    return text == "-0" ? "0" : text;
}

// ---- SVG text -----------------------------------------------------------------

std::string attr(const char* name, const std::string& value) {
    return std::string(" ") + name + "=\"" + value + "\"";
}

std::string esc(const std::string& text) {
    return xml_escape(text, false);
}

void open_svg(std::string& out, double width, double height) {
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\"" + attr("width", f2(width)) +
           attr("height", f2(height)) + attr("viewBox", "0 0 " + f2(width) + " " + f2(height)) +
           " font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n";
    out += "<rect class=\"background\"" + attr("width", f2(width)) + attr("height", f2(height)) +
           " fill=\"#ffffff\"/>\n";
}

// `extra` is further attributes, each starting with a space.
void text_at(std::string& out, double x, double y, const std::string& content, double size,
             const char* fill, const std::string& extra = "") {
    out += "<text" + attr("x", f2(x)) + attr("y", f2(y)) + attr("font-size", f2(size)) +
           attr("fill", fill) + extra + ">" + esc(content) + "</text>\n";
}

// Greedy word wrap to at most `width` characters a line (UTF-8 aware enough:
// continuation bytes do not count).
std::vector<std::string> wrap(const std::string& text, std::size_t width) {
    auto length = [](const std::string& s) {
        std::size_t n = 0;
        for (const char c : s) {
            n += (static_cast<unsigned char>(c) & 0xC0U) != 0x80U ? 1 : 0;
        }
        return n;
    };
    std::vector<std::string> lines;
    std::string line;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find_first_of(" \n", start);
        if (end == std::string::npos) {
            end = text.size();
        }
        const std::string word = text.substr(start, end - start);
        if (!word.empty()) {
            if (!line.empty() && length(line) + 1 + length(word) > width) {
                lines.push_back(line);
                line.clear();
            }
            line += (line.empty() ? "" : " ") + word;
        }
        if (end < text.size() && text[end] == '\n' && !line.empty()) {
            lines.push_back(line);
            line.clear();
        }
        start = end + 1;
    }
    if (!line.empty()) {
        lines.push_back(line);
    }
    return lines;
}

std::string shortened(const std::string& text, std::size_t width) {
    if (text.size() <= width) {
        return text;
    }
    std::size_t cut = width - 1;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U) {
        --cut;
    }
    return text.substr(0, cut) + "\u2026";
}

// ---- layout -------------------------------------------------------------------

constexpr double pad = 18.0;         // around everything
constexpr double axis_left = 44.0;   // room for the y tick labels
constexpr double axis_bottom = 34.0; // room for the x tick labels and the axis name
constexpr double legend_gap = 26.0;
constexpr double legend_width = 200.0;
constexpr double title_size = 18.0;
constexpr double text_size = 12.0;
constexpr double small_size = 10.5;
constexpr double char_width = 6.9; // DejaVu Sans at 12 px, on average
constexpr const char* ink = "#222222";
constexpr const char* muted = "#666666";
constexpr const char* grid_colour = "#ebebeb";
constexpr const char* static_fill = "#c9c9c9";
constexpr const char* static_stroke = "#9a9a9a";
constexpr const char* event_colour = "#111111";
constexpr const char* divergence_colour = "#e0115f";

// Colours told apart in print and by most colour-blind readers; grey is kept
// for static bodies.
constexpr std::array<const char*, 9> palette = {"#1f77b4", "#e8710a", "#2ca02c",
                                                "#9467bd", "#d62728", "#17becf",
                                                "#8c564b", "#e377c2", "#bcbd22"};

// Title, wrapped description lines and a grey information line; returns the y below them.
double draw_title(std::string& out, double width, const std::string& title,
                  const std::vector<std::string>& paragraphs,
                  const std::vector<std::string>& info) {
    double y = pad + title_size;
    text_at(out, pad, y, title, title_size, ink, " font-weight=\"bold\" class=\"title\"");
    const auto columns = static_cast<std::size_t>(std::max(20.0, (width - 2 * pad) / char_width));
    for (const std::string& paragraph : paragraphs) {
        for (const std::string& line : wrap(paragraph, columns)) {
            y += 17.0;
            text_at(out, pad, y, line, text_size, "#444444", " class=\"description\"");
        }
    }
    for (const std::string& line : info) {
        y += 15.0;
        text_at(out, pad, y, line, small_size, muted, " class=\"info\"");
    }
    return y + 22.0;
}

// ---- geometry -----------------------------------------------------------------

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
                                int circle_segments = 96) {
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

// Sutherland-Hodgman: the part of a convex polygon inside the rectangle.
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

// ---- the world in the picture -------------------------------------------------

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

// ---- bodies -------------------------------------------------------------------

// A dynamic body as the trajectory's columns describe it.
struct Track {
    std::string name;
    std::size_t x = 0, y = 0, angle = npos;
    const SceneBody* body = nullptr; // its shape, when the scene is known
    const char* colour = "";
};

std::size_t column_index(const Trajectory& trajectory, const std::string& name) {
    for (std::size_t i = 1; i < trajectory.columns.size(); ++i) {
        if (trajectory.columns[i] == name) {
            return i;
        }
    }
    return npos;
}

std::vector<Track> tracks_of(const Trajectory& trajectory, const Scene* scene) {
    std::vector<Track> tracks;
    for (std::size_t i = 1; i < trajectory.columns.size(); ++i) {
        const std::string& column = trajectory.columns[i];
        if (column.size() < 3 || column.compare(column.size() - 2, 2, ".x") != 0) {
            continue;
        }
        Track track;
        track.name = column.substr(0, column.size() - 2);
        track.x = i;
        track.y = column_index(trajectory, track.name + ".y");
        if (track.y == npos) {
            continue;
        }
        track.angle = column_index(trajectory, track.name + ".angle");
        if (scene != nullptr) {
            for (const SceneBody& body : scene->bodies) {
                if (body.name == track.name && !body.is_static) {
                    track.body = &body;
                }
            }
        }
        track.colour = palette[tracks.size() % palette.size()];
        tracks.push_back(std::move(track));
    }
    return tracks;
}

struct Pose {
    Vec2 p;
    double angle = 0.0;
};

bool pose_at(const Trajectory& trajectory, const Track& track, std::size_t frame, Pose& pose) {
    const std::vector<double>& row = trajectory.frames[frame];
    if (track.x >= row.size() || track.y >= row.size()) {
        return false;
    }
    pose.p = {row[track.x], row[track.y]};
    pose.angle = track.angle < row.size() ? row[track.angle] : 0.0;
    return std::isfinite(pose.p.x) && std::isfinite(pose.p.y) && std::isfinite(pose.angle);
}

// Where the dynamic bodies go, shapes included, and where the collisions are.
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

// The motion with a margin, and the static bodies close to it (a 50 m ground
// contributes only the strip under the motion).
Box framed(Box motion, const Scene* scene) {
    if (motion.empty()) {
        motion = {-1.0, -1.0, 1.0, 1.0};
    }
    const double span = std::max(motion.width(), motion.height());
    const double margin = span > 0.0 ? 0.08 * span : 0.5;
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

std::string polygon_points(const View& view, const std::vector<Vec2>& points) {
    std::string text;
    for (const Vec2 p : points) {
        text += (text.empty() ? "" : " ") + view.point(p);
    }
    return text;
}

void draw_static_bodies(std::string& out, const View& view, const Scene* scene) {
    if (scene == nullptr) {
        return;
    }
    for (const SceneBody& body : scene->bodies) {
        if (!body.is_static) {
            continue;
        }
        const std::vector<Vec2> part =
            clip_to(world_outline(body.shape, body.position, body.angle), view.world());
        if (part.size() < 3) {
            continue;
        }
        out += "<polygon class=\"static\"" + attr("data-body", esc(body.name)) +
               attr("points", polygon_points(view, part)) + " fill=\"" + static_fill +
               "\" stroke=\"" + static_stroke + "\" stroke-width=\"1\"/>\n";
    }
}

// The polyline of the centre of mass, leaving out points closer than half a
// pixel to the last one kept (the picture cannot show them) but always
// keeping the last.
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

// First, last and evenly spaced frames in between: about `wanted` of them.
std::vector<std::size_t> key_frames(std::size_t count, std::size_t wanted = 8) {
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

// The body's outline at one pose; a circle with a radius line so that its
// rotation shows. Without a shape, a small ring with a line at the body's angle.
void draw_outline(std::string& out, const View& view, const Track& track, const Pose& pose,
                  double stroke_opacity, double fill_opacity, const std::string& style,
                  std::size_t frame, double t) {
    const Rotation q = rotation_of(pose.angle);
    const std::string common = attr("data-body", esc(track.name)) +
                               attr("data-frame", std::to_string(frame)) +
                               attr("data-t", readable(t, 6));
    const std::string paint = " stroke=\"" + std::string(track.colour) + "\"" +
                              attr("stroke-opacity", f2(stroke_opacity)) + " fill=\"" +
                              track.colour + "\"" + attr("fill-opacity", f2(fill_opacity)) + style;
    if (track.body == nullptr) {
        const double r = 5.0;
        const Vec2 u = rotate(q, Vec2{1.0, 0.0});
        const double cx = view.sx(pose.p.x), cy = view.sy(pose.p.y);
        out += "<g class=\"outline\"" + common + paint + ">";
        out += "<circle" + attr("cx", f2(cx)) + attr("cy", f2(cy)) + attr("r", f2(r)) + "/>";
        out += "<path" +
               attr("d", "M" + f2(cx) + " " + f2(cy) + "L" + f2(cx + 2.0 * r * u.x) + " " +
                             f2(cy - 2.0 * r * u.y)) +
               "/></g>\n";
        return;
    }
    const Shape& shape = track.body->shape;
    if (shape.type == ShapeType::circle) {
        const Vec2 edge = pose.p + rotate(q, Vec2{shape.radius, 0.0});
        out += "<g class=\"outline\"" + common + paint + ">";
        out += "<circle" + attr("cx", f2(view.sx(pose.p.x))) + attr("cy", f2(view.sy(pose.p.y))) +
               attr("r", f2(shape.radius * view.scale)) + "/>";
        out += "<path" +
               attr("d", "M" + f2(view.sx(pose.p.x)) + " " + f2(view.sy(pose.p.y)) + "L" +
                             f2(view.sx(edge.x)) + " " + f2(view.sy(edge.y))) +
               "/></g>\n";
        return;
    }
    out += "<polygon class=\"outline\"" + common +
           attr("points", polygon_points(view, world_outline(shape, pose.p, pose.angle))) + paint +
           "/>\n";
}

// An arrow from `from` (picture pixels) along the world direction `d`, as one
// path: the shaft, then a closed head.
std::string arrow_d(double fx, double fy, Vec2 d, double length) {
    const double n = std::sqrt(d.x * d.x + d.y * d.y);
    if (!(n > 0.0) || !std::isfinite(n)) {
        return "";
    }
    const double ux = d.x / n, uy = -d.y / n; // the picture's y points down
    const double head = 7.0, half = 3.5;
    const double tx = fx + length * ux, ty = fy + length * uy;
    const double bx = tx - head * ux, by = ty - head * uy;
    return "M" + f2(fx) + " " + f2(fy) + "L" + f2(bx) + " " + f2(by) + "M" + f2(bx - half * uy) +
           " " + f2(by + half * ux) + "L" + f2(tx) + " " + f2(ty) + "L" + f2(bx + half * uy) + " " +
           f2(by - half * ux) + "Z";
}

// Each event's contact point as a dot and its normal (pointing toward body a)
// as a short arrow; `hollow` draws golden events as rings.
void draw_events(std::string& out, const View& view, const std::vector<TrajectoryEvent>& events,
                 bool hollow, const char* extra_class) {
    out += "<g class=\"events\">\n";
    for (std::size_t i = 0; i < events.size(); ++i) {
        const TrajectoryEvent& e = events[i];
        const double x = view.sx(e.point[0]), y = view.sy(e.point[1]);
        const std::string data = attr("data-event", std::to_string(i)) +
                                 attr("data-t", readable(e.t, 6)) +
                                 attr("data-bodies", esc(e.a + "/" + e.b));
        const std::string d = arrow_d(x, y, Vec2{e.normal[0], e.normal[1]}, 30.0);
        if (!d.empty()) {
            out += std::string("<path class=\"normal") + extra_class + "\"" + data + attr("d", d) +
                   " stroke=\"" + event_colour + "\" stroke-width=\"1.4\" fill=\"" + event_colour +
                   "\" stroke-linejoin=\"round\"" + (hollow ? " opacity=\"0.45\"" : "") + "/>\n";
        }
        out += std::string("<circle class=\"contact") + extra_class + "\"" + data +
               attr("cx", f2(x)) + attr("cy", f2(y)) + attr("r", hollow ? "5" : "3.5") +
               (hollow ? std::string(" fill=\"none\" stroke=\"") + event_colour +
                             "\" stroke-width=\"1.2\" opacity=\"0.6\""
                       : std::string(" fill=\"") + event_colour +
                             "\" stroke=\"#ffffff\" stroke-width=\"1\"") +
               "/>\n";
    }
    out += "</g>\n";
}

// ---- legend -------------------------------------------------------------------

struct LegendItem {
    enum class Kind { line, body, static_body, contact, ring, normal, divergence, note };
    Kind kind = Kind::line;
    std::string label;
    std::string colour = ink;
    std::string dash;    // stroke-dasharray; empty for a solid line
    bool wide = false;   // the golden path: wide and light
    bool circle = false; // a body's swatch: a disc rather than a square
};

// Draws the items from (x, y) down; returns the y below the last.
double draw_legend(std::string& out, double x, double y, const std::vector<LegendItem>& items) {
    out += "<g class=\"legend\">\n";
    for (const LegendItem& item : items) {
        const double cy = y + 6.0;
        using Kind = LegendItem::Kind;
        const std::string c = item.colour;
        switch (item.kind) {
        case Kind::line:
        case Kind::body:
            out += "<path" + attr("d", "M" + f2(x) + " " + f2(cy) + "H" + f2(x + 26.0)) +
                   attr("stroke", c) + attr("stroke-width", item.wide ? "6" : "2.2") +
                   (item.wide ? " stroke-opacity=\"0.3\" stroke-linecap=\"round\"" : "") +
                   (item.dash.empty() ? "" : attr("stroke-dasharray", item.dash)) +
                   " fill=\"none\"/>\n";
            if (item.kind == Kind::body && item.circle) {
                out += "<circle" + attr("cx", f2(x + 13.0)) + attr("cy", f2(cy)) + " r=\"5.5\"" +
                       attr("stroke", c) + " fill=\"#ffffff\" stroke-width=\"1.4\"/>\n";
            } else if (item.kind == Kind::body) {
                out += "<rect" + attr("x", f2(x + 8.0)) + attr("y", f2(cy - 5.0)) +
                       " width=\"10\" height=\"10\"" + attr("stroke", c) +
                       " fill=\"#ffffff\" stroke-width=\"1.4\"/>\n";
            }
            break;
        case Kind::static_body:
            out += "<rect" + attr("x", f2(x)) + attr("y", f2(cy - 5.0)) +
                   " width=\"26\" height=\"10\" fill=\"" + static_fill + "\" stroke=\"" +
                   static_stroke + "\"/>\n";
            break;
        case Kind::contact:
            out += "<circle" + attr("cx", f2(x + 13.0)) + attr("cy", f2(cy)) +
                   " r=\"3.5\" fill=\"" + event_colour + "\"/>\n";
            break;
        case Kind::ring:
            out += "<circle" + attr("cx", f2(x + 13.0)) + attr("cy", f2(cy)) +
                   " r=\"5\" fill=\"none\" stroke=\"" + event_colour +
                   "\" stroke-width=\"1.2\" opacity=\"0.6\"/>\n";
            break;
        case Kind::normal:
            out += "<path" + attr("d", arrow_d(x + 2.0, cy, Vec2{1.0, 0.0}, 24.0)) + " stroke=\"" +
                   event_colour + "\" stroke-width=\"1.4\" fill=\"" + event_colour + "\"/>\n";
            break;
        case Kind::divergence:
            out += "<circle" + attr("cx", f2(x + 13.0)) + attr("cy", f2(cy)) +
                   " r=\"6\" fill=\"none\" stroke=\"" + divergence_colour +
                   "\" stroke-width=\"2\"/>\n";
            break;
        case Kind::note:
            break;
        }
        if (item.kind == Kind::note) {
            double line_y = y + 9.5;
            for (const std::string& line : wrap(item.label, 32)) {
                text_at(out, x, line_y, line, small_size, muted);
                line_y += 14.0;
            }
            y = line_y + 4.0;
        } else {
            text_at(out, x + 34.0, cy + 4.0, shortened(item.label, 24), text_size, ink);
            y += 21.0;
        }
    }
    out += "</g>\n";
    return y;
}

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

// ---- one run ------------------------------------------------------------------

std::string render_motion(const Scene* scene, const Trajectory& trajectory) {
    const std::vector<Track> tracks = tracks_of(trajectory, scene);
    View view = fit_view(framed(motion_bounds(trajectory, tracks), scene), 620.0, 470.0);

    const double width = pad + axis_left + view.width() + legend_gap + legend_width + pad;
    std::vector<std::string> paragraphs;
    std::string title = trajectory.scene;
    if (scene != nullptr) {
        title = scene->name;
        if (!scene->description.empty()) {
            paragraphs.push_back(scene->description);
        }
    } else {
        paragraphs.push_back("Paths, contact points and normals only: the scene was not "
                             "available to draw the bodies' shapes.");
    }

    std::string body;
    const double top = draw_title(body, width, title, paragraphs, {run_info(trajectory)});
    view.left = pad + axis_left;
    view.top = top;

    draw_frame_and_grid(body, view, "x (m)", "y (m)");
    draw_static_bodies(body, view, scene);

    const std::vector<std::size_t> keys = key_frames(trajectory.frames.size());
    for (const Track& track : tracks) {
        for (std::size_t i = 0; i < keys.size(); ++i) {
            Pose pose;
            if (!pose_at(trajectory, track, keys[i], pose)) {
                continue;
            }
            const double age = keys.size() > 1
                                   ? static_cast<double>(i) / static_cast<double>(keys.size() - 1)
                                   : 1.0;
            const bool last = i + 1 == keys.size();
            draw_outline(body, view, track, pose, 0.22 + 0.78 * age, 0.02 + 0.06 * age,
                         last ? " stroke-width=\"2\"" : " stroke-width=\"1.3\"", keys[i],
                         trajectory.frames[keys[i]][0]);
        }
    }
    for (std::size_t k = 0; k < tracks.size(); ++k) {
        const Track& track = tracks[k];
        body += "<polyline class=\"path\"" + attr("data-body", esc(track.name)) +
                attr("points", path_points(view, trajectory, track)) +
                attr("stroke", track.colour) +
                " stroke-width=\"2\" fill=\"none\" stroke-linejoin=\"round\"/>\n";
        note_drawn(k + 1, tracks.size()); // for the progress bar only
    }
    draw_events(body, view, trajectory.events, false, "");
    draw_plot_border(body, view);

    std::vector<LegendItem> legend;
    for (const Track& track : tracks) {
        LegendItem item{LegendItem::Kind::body, track.name, track.colour, "", false};
        item.circle = track.body == nullptr || track.body->shape.type == ShapeType::circle;
        legend.push_back(item);
    }
    bool has_static = false;
    if (scene != nullptr) {
        for (const SceneBody& b : scene->bodies) {
            has_static = has_static || b.is_static;
        }
    }
    if (has_static) {
        legend.push_back({LegendItem::Kind::static_body, "static body", ink, "", false});
    }
    legend.push_back({LegendItem::Kind::contact, "contact point", ink, "", false});
    legend.push_back({LegendItem::Kind::normal, "normal (toward a)", ink, "", false});
    legend.push_back({LegendItem::Kind::note,
                      "Lines: paths of the centres of mass. " +
                          std::string(scene != nullptr ? "Outlines"
                                                       : "Rings with a line at the "
                                                         "body's angle") +
                          " at " + std::to_string(keys.size()) + " key frames, older ones fainter.",
                      muted, "", false});
    const double legend_x = view.left + view.width() + legend_gap;
    const double legend_end = draw_legend(body, legend_x, view.top, legend);

    const double height = std::max(view.top + view.height() + axis_bottom, legend_end) + pad;
    std::string out;
    open_svg(out, width, height);
    out += body;
    out += "</svg>\n";
    return out;
}

// ---- golden versus new --------------------------------------------------------

// Which of the four frame channels a column belongs to; -1 for "t" and others.
int frame_channel(const std::string& column) {
    const std::size_t dot = column.rfind('.');
    if (dot == std::string::npos) {
        return -1;
    }
    const std::string field = column.substr(dot + 1);
    if (field == "x" || field == "y") {
        return static_cast<int>(Channel::position);
    }
    if (field == "angle") {
        return static_cast<int>(Channel::angle);
    }
    if (field == "vx" || field == "vy") {
        return static_cast<int>(Channel::velocity);
    }
    if (field == "omega") {
        return static_cast<int>(Channel::angular_velocity);
    }
    return -1;
}

constexpr double error_floor = 1e-18;
constexpr std::array<const char*, 4> channel_colours = {"#1f77b4", "#e8710a", "#2ca02c", "#9467bd"};
constexpr std::array<const char*, 4> channel_dashes = {"", "7 3", "2 2", "9 3 2 3"};
constexpr std::array<const char*, 4> channel_labels = {"position", "angle", "velocity",
                                                       "angular velocity"};

struct ErrorSeries {
    std::vector<double> t;
    std::array<std::vector<double>, 4> error; // per frame channel: max |new - gold| over columns
};

ErrorSeries error_series(const Trajectory& gold, const Trajectory& value) {
    ErrorSeries series;
    std::vector<std::pair<std::size_t, std::size_t>> pairs; // gold column, new column
    std::vector<int> channel;
    for (std::size_t i = 1; i < gold.columns.size(); ++i) {
        const int c = frame_channel(gold.columns[i]);
        const std::size_t j = column_index(value, gold.columns[i]);
        if (c >= 0 && j != npos) {
            pairs.emplace_back(i, j);
            channel.push_back(c);
        }
    }
    const std::size_t n = std::min(gold.frames.size(), value.frames.size());
    for (std::size_t k = 0; k < n; ++k) {
        const std::vector<double>& g = gold.frames[k];
        const std::vector<double>& v = value.frames[k];
        if (g.empty()) {
            continue;
        }
        series.t.push_back(g[0]);
        std::array<double, 4> worst = {0.0, 0.0, 0.0, 0.0};
        for (std::size_t p = 0; p < pairs.size(); ++p) {
            if (pairs[p].first >= g.size() || pairs[p].second >= v.size()) {
                continue;
            }
            double e = std::abs(v[pairs[p].second] - g[pairs[p].first]);
            if (std::isnan(e)) {
                e = infinity;
            }
            auto& w = worst[static_cast<std::size_t>(channel[p])];
            w = std::max(w, e);
        }
        for (std::size_t c = 0; c < 4; ++c) {
            series.error[c].push_back(worst[c]);
        }
    }
    return series;
}

std::string decade_label(int e) {
    switch (e) {
    case -2:
        return "0.01";
    case -1:
        return "0.1";
    case 0:
        return "1";
    case 1:
        return "10";
    case 2:
        return "100";
    default:
        return "1e" + std::to_string(e);
    }
}

// Time on x, |new - gold| on a log y axis from error_floor up.
double draw_error_panel(std::string& out, const ErrorSeries& series, double left, double top,
                        double width, double height, const Divergence* first) {
    constexpr int floor_decade = -18;
    double worst = 0.0;
    for (const auto& channel : series.error) {
        for (const double e : channel) {
            worst = std::max(worst, e);
        }
    }
    int top_decade = -15;
    while (top_decade < 300 && std::pow(10.0, top_decade) < worst) {
        ++top_decade;
    }
    const double t0 = series.t.empty() ? 0.0 : series.t.front();
    double t1 = series.t.empty() ? 1.0 : series.t.back();
    if (!(t1 > t0)) {
        t1 = t0 + 1.0;
    }
    auto px = [&](double t) { return left + (t - t0) / (t1 - t0) * width; };
    auto py = [&](double e) {
        const double clamped = std::max(e, error_floor);
        const double l = std::isfinite(clamped) ? std::log10(clamped) : top_decade;
        const double s = (l - floor_decade) / (top_decade - floor_decade);
        return top + height - std::clamp(s, 0.0, 1.0) * height;
    };

    out += "<g class=\"error-panel\">\n";
    out += "<rect" + attr("x", f2(left)) + attr("y", f2(top)) + attr("width", f2(width)) +
           attr("height", f2(height)) + " fill=\"#fcfcfc\"/>\n";
    std::string lines;
    const int every =
        top_decade - floor_decade <= 10 ? 1 : (top_decade - floor_decade <= 30 ? 3 : 10);
    while ((top_decade - floor_decade) % every != 0) {
        ++top_decade; // labelled decades evenly spaced, the top one included
    }
    for (int e = floor_decade; e <= top_decade; ++e) {
        if ((e - floor_decade) % every != 0) {
            continue;
        }
        const double y = py(std::pow(10.0, e));
        lines += "M" + f2(left) + " " + f2(y) + "H" + f2(left + width);
        text_at(out, left - 6.0, y + 3.5, decade_label(e), small_size, muted,
                " text-anchor=\"end\"");
    }
    const double step = nice_step((t1 - t0) / 8.0);
    for (const double t : ticks(t0, t1, step)) {
        lines += "M" + f2(px(t)) + " " + f2(top) + "V" + f2(top + height);
        text_at(out, px(t), top + height + 14.0, readable(t), small_size, muted,
                " text-anchor=\"middle\"");
    }
    out += "<path" + attr("d", lines) + " stroke=\"" + grid_colour + "\" fill=\"none\"/>\n";
    text_at(out, left + width, top + height + 28.0, "t (s)", small_size, muted,
            " text-anchor=\"end\"");
    text_at(out, left, top - 8.0, "|new \u2212 gold|", small_size, muted, " text-anchor=\"start\"");

    if (first != nullptr && std::isfinite(first->t) && first->t >= t0 && first->t <= t1) {
        out += "<path class=\"divergence-time\"" +
               attr("d", "M" + f2(px(first->t)) + " " + f2(top) + "V" + f2(top + height)) +
               " stroke=\"" + divergence_colour +
               "\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\" fill=\"none\"/>\n";
    }

    // Per channel one polyline; frames that fall in the same pixel column keep
    // only their first, smallest, largest and last value, in time order.
    for (std::size_t c = 0; c < 4; ++c) {
        std::string points;
        std::vector<std::size_t> chosen;
        std::size_t k = 0;
        while (k < series.t.size()) {
            const auto column = static_cast<long long>(std::floor(px(series.t[k])));
            std::size_t lo = k, hi = k, end = k;
            while (end < series.t.size() &&
                   static_cast<long long>(std::floor(px(series.t[end]))) == column) {
                if (series.error[c][end] < series.error[c][lo]) {
                    lo = end;
                }
                if (series.error[c][end] > series.error[c][hi]) {
                    hi = end;
                }
                ++end;
            }
            std::array<std::size_t, 4> picks = {k, lo, hi, end - 1};
            std::sort(picks.begin(), picks.end());
            for (std::size_t i = 0; i < picks.size(); ++i) {
                if (i == 0 || picks[i] != picks[i - 1]) {
                    chosen.push_back(picks[i]);
                }
            }
            k = end;
        }
        for (const std::size_t i : chosen) {
            points += (points.empty() ? "" : " ") + f2(px(series.t[i])) + "," +
                      f2(py(series.error[c][i]));
        }
        out += "<polyline class=\"error\"" + attr("data-channel", channel_names[c]) +
               attr("points", points) + attr("stroke", channel_colours[c]) +
               " stroke-width=\"1.6\" fill=\"none\" stroke-linejoin=\"round\"" +
               (c == 0 ? std::string() : attr("stroke-dasharray", channel_dashes[c])) + "/>\n";
    }
    out += "<rect" + attr("x", f2(left)) + attr("y", f2(top)) + attr("width", f2(width)) +
           attr("height", f2(height)) + " fill=\"none\" stroke=\"#bbbbbb\"/>\n";
    out += "</g>\n";
    return top + height;
}

} // namespace

const Divergence* first_divergence(const Comparison& comparison) {
    const Divergence* best = nullptr;
    auto is_event = [](const Divergence& d) { return d.column.rfind("events[", 0) == 0; };
    for (const Divergence& d : comparison.first_divergences) {
        if (best == nullptr || d.t < best->t ||
            (d.t == best->t && is_event(*best) && !is_event(d))) {
            best = &d;
        }
    }
    return best;
}

std::string render_svg(const Scene& scene, const Trajectory& trajectory) {
    return render_motion(&scene, trajectory);
}

std::string render_svg(const Trajectory& trajectory) {
    return render_motion(nullptr, trajectory);
}

std::string render_comparison_svg(const Scene* scene, const Trajectory& gold,
                                  const Trajectory& value, const Comparison& comparison) {
    std::vector<Track> tracks = tracks_of(gold, scene);
    std::vector<Track> new_tracks;
    for (const Track& track : tracks) {
        Track t = track;
        t.x = column_index(value, track.name + ".x");
        t.y = column_index(value, track.name + ".y");
        t.angle = column_index(value, track.name + ".angle");
        new_tracks.push_back(t);
    }
    Box motion = motion_bounds(gold, tracks);
    std::vector<Track> present; // the new run's tracks that it has
    for (const Track& t : new_tracks) {
        if (t.x != npos && t.y != npos) {
            present.push_back(t);
        }
    }
    motion.add(motion_bounds(value, present));
    View view = fit_view(framed(motion, scene), 620.0, 400.0);
    // At least as wide as the error panel below: more world on either side.
    constexpr double narrowest_panel = 480.0;
    if (view.width() < narrowest_panel) {
        const double extra = (narrowest_panel - view.width()) / view.scale;
        view.x0 -= 0.5 * extra;
        view.x1 += 0.5 * extra;
    }
    const double width = pad + axis_left + view.width() + legend_gap + legend_width + pad;

    // The words at the top: the verdict, the first divergence and any structural difference.
    const Divergence* first = first_divergence(comparison);
    std::vector<std::string> paragraphs;
    if (scene != nullptr && !scene->description.empty()) {
        paragraphs.push_back(scene->description);
    }
    std::string verdict;
    if (comparison.identical) {
        verdict = "Identical to the golden, bit for bit.";
    } else if (comparison.passed) {
        verdict = "Within tolerance of the golden, though not bit-identical.";
    } else {
        verdict = "Differs from the golden.";
    }
    if (first != nullptr) {
        verdict += " First divergence: " + first->column + " at t = " + readable(first->t, 6) +
                   " s (" + (first->column.rfind("events[", 0) == 0 ? "event " : "frame ") +
                   std::to_string(first->frame) + "): golden " + readable(first->gold, 10) +
                   ", new " + readable(first->value, 10) + ", |difference| " +
                   readable(first->abs_diff, 3) + ", " + std::to_string(first->ulp) + " ULP.";
    }
    paragraphs.push_back(verdict);
    for (std::size_t i = 0; i < comparison.structural.size() && i < 4; ++i) {
        paragraphs.push_back(comparison.structural[i]);
    }
    if (comparison.structural.size() > 4) {
        paragraphs.push_back("... and " + std::to_string(comparison.structural.size() - 4) +
                             " more structural differences.");
    }

    std::string body;
    const std::string name = scene != nullptr ? scene->name : gold.scene;
    double y = draw_title(body, width, name + ": golden vs new", paragraphs,
                          {"golden: " + run_info(gold), "new: " + run_info(value)});

    // Panel 1: the paths.
    y += 4.0;
    text_at(body, pad, y, "Paths of the centres of mass", text_size, ink, " font-weight=\"bold\"");
    y += 30.0;
    view.left = pad + axis_left;
    view.top = y;
    draw_frame_and_grid(body, view, "x (m)", "y (m)");
    draw_static_bodies(body, view, scene);
    for (std::size_t b = 0; b < tracks.size(); ++b) {
        // The last frame's outline of each run, when the shapes are known.
        if (tracks[b].body == nullptr) {
            continue;
        }
        Pose pose;
        if (!gold.frames.empty() && pose_at(gold, tracks[b], gold.frames.size() - 1, pose)) {
            draw_outline(body, view, tracks[b], pose, 0.35, 0.06, " stroke-width=\"1.2\"",
                         gold.frames.size() - 1, gold.frames.back()[0]);
        }
        if (new_tracks[b].x != npos && new_tracks[b].y != npos && !value.frames.empty() &&
            pose_at(value, new_tracks[b], value.frames.size() - 1, pose)) {
            draw_outline(body, view, new_tracks[b], pose, 0.9, 0.0,
                         " stroke-width=\"1.2\" stroke-dasharray=\"5 3\"", value.frames.size() - 1,
                         value.frames.back()[0]);
        }
    }
    for (const Track& track : tracks) {
        body += "<polyline class=\"path gold\"" + attr("data-body", esc(track.name)) +
                attr("points", path_points(view, gold, track)) + attr("stroke", track.colour) +
                " stroke-width=\"6\" stroke-opacity=\"0.3\" fill=\"none\" "
                "stroke-linejoin=\"round\" stroke-linecap=\"round\"/>\n";
    }
    for (const Track& track : present) {
        body += "<polyline class=\"path new\"" + attr("data-body", esc(track.name)) +
                attr("points", path_points(view, value, track)) + attr("stroke", track.colour) +
                " stroke-width=\"1.8\" stroke-dasharray=\"6 4\" fill=\"none\" "
                "stroke-linejoin=\"round\"/>\n";
    }
    draw_events(body, view, gold.events, true, " gold");
    draw_events(body, view, value.events, false, " new");

    // The first divergence: a ring around the new position (or event point),
    // joined to the golden one.
    if (first != nullptr) {
        Vec2 g{infinity, infinity}, v{infinity, infinity};
        if (first->column.rfind("events[", 0) == 0) {
            if (first->frame < gold.events.size()) {
                g = {gold.events[first->frame].point[0], gold.events[first->frame].point[1]};
            }
            if (first->frame < value.events.size()) {
                v = {value.events[first->frame].point[0], value.events[first->frame].point[1]};
            }
        } else {
            const std::size_t dot = first->column.rfind('.');
            const std::string body_name = first->column.substr(0, dot);
            for (std::size_t b = 0; b < tracks.size(); ++b) {
                Pose pose;
                if (tracks[b].name != body_name) {
                    continue;
                }
                if (first->frame < gold.frames.size() &&
                    pose_at(gold, tracks[b], first->frame, pose)) {
                    g = pose.p;
                }
                if (new_tracks[b].x != npos && new_tracks[b].y != npos &&
                    first->frame < value.frames.size() &&
                    pose_at(value, new_tracks[b], first->frame, pose)) {
                    v = pose.p;
                }
            }
        }
        const Vec2 at = std::isfinite(v.x) ? v : g;
        if (std::isfinite(at.x)) {
            body += "<g class=\"divergence\">";
            if (std::isfinite(g.x) && std::isfinite(v.x)) {
                body += "<path" +
                        attr("d", "M" + f2(view.sx(g.x)) + " " + f2(view.sy(g.y)) + "L" +
                                      f2(view.sx(v.x)) + " " + f2(view.sy(v.y))) +
                        " stroke=\"" + divergence_colour + "\" stroke-width=\"1.5\"/>";
            }
            body += "<circle" + attr("cx", f2(view.sx(at.x))) + attr("cy", f2(view.sy(at.y))) +
                    " r=\"9\" fill=\"none\" stroke=\"" + divergence_colour +
                    "\" stroke-width=\"2.2\"/>";
            body += "</g>\n";
            text_at(body, view.sx(at.x) + 12.0, view.sy(at.y) - 10.0,
                    "first divergence, t = " + readable(first->t) + " s", small_size,
                    divergence_colour,
                    " font-weight=\"bold\" stroke=\"#ffffff\" stroke-width=\"3\" "
                    "paint-order=\"stroke\" stroke-linejoin=\"round\"");
        }
    }
    draw_plot_border(body, view);

    std::vector<LegendItem> legend;
    for (const Track& track : tracks) {
        LegendItem item{LegendItem::Kind::body, track.name, track.colour, "", false};
        item.circle = track.body == nullptr || track.body->shape.type == ShapeType::circle;
        legend.push_back(item);
    }
    legend.push_back({LegendItem::Kind::line, "golden path", "#888888", "", true});
    legend.push_back({LegendItem::Kind::line, "new path", "#555555", "6 4", false});
    legend.push_back({LegendItem::Kind::ring, "golden contact", ink, "", false});
    legend.push_back({LegendItem::Kind::contact, "new contact", ink, "", false});
    legend.push_back({LegendItem::Kind::normal, "normal (toward a)", ink, "", false});
    if (first != nullptr) {
        legend.push_back({LegendItem::Kind::divergence, "first divergence", ink, "", false});
    }
    if (scene != nullptr) {
        legend.push_back({LegendItem::Kind::note,
                          "Outlines at the last frame: golden solid, new dashed.", muted, "",
                          false});
    }
    const double legend_x = width - pad - legend_width;
    double legend_end = draw_legend(body, legend_x, view.top, legend);

    // Panel 2: the error over time.
    y = std::max(view.top + view.height() + axis_bottom, legend_end) + 26.0;
    text_at(body, pad, y, "Error over time: |new \u2212 gold| per frame, largest over the bodies",
            text_size, ink, " font-weight=\"bold\"");
    y += 16.0;
    std::string note = "Log scale; an exact zero is drawn at the floor, 1e-18.";
    if (gold.frames.size() != value.frames.size()) {
        note += " Frame counts differ (" + std::to_string(gold.frames.size()) + " golden, " +
                std::to_string(value.frames.size()) + " new): the first " +
                std::to_string(std::min(gold.frames.size(), value.frames.size())) +
                " are compared.";
    }
    text_at(body, pad, y, note, small_size, muted);
    y += 24.0;
    const double error_left = pad + 56.0;
    const double error_width = legend_x - legend_gap - error_left;
    const ErrorSeries series = error_series(gold, value);
    const double error_bottom =
        draw_error_panel(body, series, error_left, y, error_width, 220.0, first);
    std::vector<LegendItem> channels;
    for (std::size_t c = 0; c < 4; ++c) {
        channels.push_back({LegendItem::Kind::line, channel_labels[c], channel_colours[c],
                            channel_dashes[c], false});
    }
    if (first != nullptr) {
        channels.push_back(
            {LegendItem::Kind::note, "Dashed red line: the first divergence.", muted, "", false});
    }
    legend_end = draw_legend(body, legend_x, y, channels);

    const double height = std::max(error_bottom + axis_bottom, legend_end) + pad;
    std::string out;
    open_svg(out, width, height);
    out += body;
    out += "</svg>\n";
    return out;
}

} // namespace impulse::harness
