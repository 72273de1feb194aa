// The world's things as SVG (world_marks.h).
#include "world_marks.h"

#include "rotation.h"
#include "shape.h"

#include <cmath>

namespace impulse::harness::picture {

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

void draw_outline(std::string& out, const View& view, const Track& track, const Pose& pose,
                  double stroke_opacity, double fill_opacity, const std::string& style,
                  std::size_t frame, double t) {
    const Rotation q = rotation_of(pose.angle);
    const std::string common = attr("data-body", esc(track.name)) +
                               attr("data-frame", std::to_string(frame)) +
                               attr("data-t", readable(t, 6));
    const std::string tip =
        "<title>" +
        esc(track.name + " at t = " + readable(t, 6) + " s (frame " + std::to_string(frame) + ")") +
        "</title>";
    const std::string paint = " stroke=\"" + std::string(track.colour) + "\"" +
                              attr("stroke-opacity", f2(stroke_opacity)) + " fill=\"" +
                              track.colour + "\"" + attr("fill-opacity", f2(fill_opacity)) + style;
    if (track.body == nullptr) {
        const double r = 5.0;
        const Vec2 u = rotate(q, Vec2{1.0, 0.0});
        const double cx = view.sx(pose.p.x), cy = view.sy(pose.p.y);
        out += "<g class=\"outline\"" + common + paint + ">" + tip;
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
        out += "<g class=\"outline\"" + common + paint + ">" + tip;
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
           ">" + tip + "</polygon>\n";
}

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

std::string time_text(const std::vector<double>& times) {
    std::string text;
    for (const double t : times) {
        text += (text.empty() ? "t = " : ", ") + readable(t);
    }
    return text + " s";
}

void draw_time_label(std::string& out, double x, double y, const std::string& text) {
    text_at(out, x, y, text, small_size, muted,
            " class=\"time\" stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\" "
            "stroke-linejoin=\"round\"");
}

void draw_events(std::string& out, const View& view, const std::vector<TrajectoryEvent>& events,
                 bool hollow, const char* extra_class) {
    out += "<g class=\"events\">\n";
    for (std::size_t i = 0; i < events.size(); ++i) {
        const TrajectoryEvent& e = events[i];
        const double x = view.sx(e.point[0]), y = view.sy(e.point[1]);
        const std::string data = attr("data-event", std::to_string(i)) +
                                 attr("data-t", readable(e.t, 6)) +
                                 attr("data-bodies", esc(e.a + "/" + e.b));
        const std::string tip = "<title>" +
                                esc("t = " + readable(e.t, 6) + " s: " + e.a + " and " + e.b +
                                    ", impulse " + readable(e.impulse)) +
                                "</title>";
        const std::string d = arrow_d(x, y, Vec2{e.normal[0], e.normal[1]}, 30.0);
        if (!d.empty()) {
            out += std::string("<path class=\"normal") + extra_class + "\"" + data + attr("d", d) +
                   " stroke=\"" + event_colour + "\" stroke-width=\"1.4\" fill=\"" + event_colour +
                   "\" stroke-linejoin=\"round\"" + (hollow ? " opacity=\"0.45\"" : "") + ">" +
                   tip + "</path>\n";
        }
        out += std::string("<circle class=\"contact") + extra_class + "\"" + data +
               attr("cx", f2(x)) + attr("cy", f2(y)) + attr("r", hollow ? "5" : "3.5") +
               (hollow ? std::string(" fill=\"none\" stroke=\"") + event_colour +
                             "\" stroke-width=\"1.2\" opacity=\"0.6\""
                       : std::string(" fill=\"") + event_colour +
                             "\" stroke=\"#ffffff\" stroke-width=\"1\"") +
               ">" + tip + "</circle>\n";
    }
    out += "</g>\n";
}

} // namespace impulse::harness::picture
