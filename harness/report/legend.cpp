// A picture's legend (legend.h).
#include "legend.h"

#include "shape.h"
#include "vec2.h"
#include "world_marks.h"

namespace impulse::harness::picture {

std::vector<LegendItem> body_legend(const std::vector<Track>& tracks) {
    std::vector<LegendItem> legend;
    for (const Track& track : tracks) {
        LegendItem item{LegendItem::Kind::body, track.name, track.colour, "", false};
        item.circle = track.body == nullptr || track.body->shape.type == ShapeType::circle;
        legend.push_back(item);
    }
    return legend;
}

namespace {

// A disc or ring in the middle of the swatch; `rest` is its radius and paint.
std::string swatch_circle(double x, double cy, const std::string& rest) {
    return "<circle" + attr("cx", f2(x + 13.0)) + attr("cy", f2(cy)) + rest + "/>\n";
}

// The radius and paint of the marks drawn as circles: a contact point, a
// golden contact (a ring) and the first divergence.
std::string circle_paint(LegendItem::Kind kind) {
    if (kind == LegendItem::Kind::contact) {
        return std::string(" r=\"3.5\" fill=\"") + event_colour + "\"";
    }
    if (kind == LegendItem::Kind::ring) {
        return std::string(" r=\"5\" fill=\"none\" stroke=\"") + event_colour +
               "\" stroke-width=\"1.2\" opacity=\"0.6\"";
    }
    return std::string(" r=\"6\" fill=\"none\" stroke=\"") + divergence_colour +
           "\" stroke-width=\"2\"";
}

// A line, with a body's disc or square on it.
void line_swatch(std::string& out, const LegendItem& item, double x, double cy) {
    const std::string& c = item.colour;
    out += "<path" + attr("d", "M" + f2(x) + " " + f2(cy) + "H" + f2(x + 26.0)) +
           attr("stroke", c) + attr("stroke-width", item.wide ? "6" : "2.2") +
           (item.wide ? " stroke-opacity=\"0.3\" stroke-linecap=\"round\"" : "") +
           (item.dash.empty() ? "" : attr("stroke-dasharray", item.dash)) + " fill=\"none\"/>\n";
    if (item.kind == LegendItem::Kind::body && item.circle) {
        out += swatch_circle(
            x, cy, " r=\"5.5\"" + attr("stroke", c) + " fill=\"#ffffff\" stroke-width=\"1.4\"");
    } else if (item.kind == LegendItem::Kind::body) {
        out += "<rect" + attr("x", f2(x + 8.0)) + attr("y", f2(cy - 5.0)) +
               " width=\"10\" height=\"10\"" + attr("stroke", c) +
               " fill=\"#ffffff\" stroke-width=\"1.4\"/>\n";
    }
}

void swatch(std::string& out, const LegendItem& item, double x, double cy) {
    using Kind = LegendItem::Kind;
    switch (item.kind) {
    case Kind::line:
    case Kind::body:
        line_swatch(out, item, x, cy);
        break;
    case Kind::static_body:
        out += "<rect" + attr("x", f2(x)) + attr("y", f2(cy - 5.0)) +
               " width=\"26\" height=\"10\" fill=\"" + static_fill + "\" stroke=\"" +
               static_stroke + "\"/>\n";
        break;
    case Kind::contact:
    case Kind::ring:
    case Kind::divergence:
        out += swatch_circle(x, cy, circle_paint(item.kind));
        break;
    case Kind::normal:
        out += "<path" + attr("d", arrow_d(x + 2.0, cy, Vec2{1.0, 0.0}, 24.0)) + " stroke=\"" +
               event_colour + "\" stroke-width=\"1.4\" fill=\"" + event_colour + "\"/>\n";
        break;
    case Kind::note:
        break;
    }
}

} // namespace

double draw_legend(std::string& out, double x, double y, const std::vector<LegendItem>& items) {
    out += "<g class=\"legend\">\n";
    for (const LegendItem& item : items) {
        const double cy = y + 6.0;
        swatch(out, item, x, cy);
        if (item.kind == LegendItem::Kind::note) {
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

} // namespace impulse::harness::picture
