// The sweep's plot (impulse sweep --svg): error against cost, both on log
// scales, as an SVG built by hand so the same result gives the same bytes.
#include "sweep_plot.h"

#include "markup.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace impulse::harness {

namespace {

// Errors of exactly 0 (and anything below) are drawn at this floor.
constexpr double plot_error_floor = 1e-17;

double log_cost(const SweepPoint& p) {
    return std::log10(p.cost_median);
}

double log_error(const SweepPoint& p) {
    return std::log10(std::max(p.error, plot_error_floor));
}

constexpr std::string_view ccd_suffix = "+ccd";

bool is_ccd(const std::string& f) {
    return f.size() > ccd_suffix.size() &&
           f.compare(f.size() - ccd_suffix.size(), ccd_suffix.size(), ccd_suffix) == 0;
}

std::string base_of(const std::string& f) {
    return is_ccd(f) ? f.substr(0, f.size() - ccd_suffix.size()) : f;
}

std::string dashes(const std::string& f) {
    if (f == "box2d") {
        return " stroke-dasharray=\"8 4\"";
    }
    return is_ccd(f) ? " stroke-dasharray=\"2 3\"" : "";
}

// The plot's size, the points drawn and the whole decades around them.
struct SweepLayout {
    static constexpr double height = 560, left = 80, top = 50, bottom = 60, plot_w = 550;
    double width = 0.0, plot_h = 0.0;
    std::vector<const SweepPoint*> drawn;
    double x0 = 0, x1 = 1, y0 = 0, y1 = 1;

    double px(double v) const { return left + (v - x0) / (x1 - x0) * plot_w; }
    double py(double v) const { return top + (y1 - v) / (y1 - y0) * plot_h; }
};

SweepLayout sweep_layout(const SweepResult& r) {
    SweepLayout l;
    // The legend's column as wide as its longest label needs (about 7 px a
    // character at 12 px): "impulse symplectic-euler/bisection+ccd" is long.
    std::size_t longest = 0;
    for (const SweepPoint& p : r.points) {
        longest = std::max(longest, p.box2d ? std::string("Box2D 2.4.1").size() : p.family.size());
    }
    const double right = std::max(250.0, 50.0 + 7.0 * static_cast<double>(longest));
    l.width = SweepLayout::left + SweepLayout::plot_w + right;
    l.plot_h = SweepLayout::height - SweepLayout::top - SweepLayout::bottom;
    for (const SweepPoint& p : r.points) {
        if (p.ok && std::isfinite(p.error) && p.cost_median > 0.0) {
            l.drawn.push_back(&p);
        }
    }
    if (!l.drawn.empty()) {
        l.x0 = l.y0 = 1e300;
        l.x1 = l.y1 = -1e300;
        for (const SweepPoint* p : l.drawn) {
            l.x0 = std::min(l.x0, log_cost(*p));
            l.x1 = std::max(l.x1, log_cost(*p));
            l.y0 = std::min(l.y0, log_error(*p));
            l.y1 = std::max(l.y1, log_error(*p));
        }
        l.x0 = std::floor(l.x0);
        l.x1 = std::max(std::ceil(l.x1), l.x0 + 1);
        l.y0 = std::floor(l.y0);
        l.y1 = std::max(std::ceil(l.y1), l.y0 + 1);
    }
    return l;
}

// Families in first-appearance order.
std::vector<std::string> families_of(const SweepResult& r) {
    std::vector<std::string> families;
    for (const SweepPoint& p : r.points) {
        if (std::find(families.begin(), families.end(), p.family) == families.end()) {
            families.push_back(p.family);
        }
    }
    return families;
}

// Box2D in red; a "+ccd" family in its sibling's colour.
std::map<std::string, std::string> family_colours(const std::vector<std::string>& families) {
    const char* palette[] = {"#1f77b4", "#aec7e8", "#ff7f0e", "#ffbb78", "#2ca02c",
                             "#98df8a", "#9467bd", "#c5b0d5", "#8c564b", "#e377c2"};
    std::map<std::string, std::string> base_colour;
    std::size_t next = 0;
    for (const std::string& f : families) {
        const std::string base = base_of(f);
        if (base_colour.count(base) == 0) {
            base_colour[base] = base == "box2d" ? "#d62728" : palette[next++ % 10];
        }
    }
    std::map<std::string, std::string> colour;
    for (const std::string& f : families) {
        colour[f] = base_colour[base_of(f)];
    }
    return colour;
}

// The document, its title and the plot's frame.
void draw_header(std::ostringstream& s, const SweepLayout& l, const SweepResult& r) {
    const double left = SweepLayout::left, top = SweepLayout::top, height = SweepLayout::height;
    s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << fixed_text(l.width, 0)
      << "\" height=\"" << fixed_text(height, 0) << "\" viewBox=\"0 0 " << fixed_text(l.width, 0)
      << " " << fixed_text(height, 0) << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    s << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    s << "<text x=\"" << fixed_text(left, 0) << "\" y=\"24\" font-size=\"15\">"
      << xml_escape("impulse sweep: " + r.scene + ", error against cost") << "</text>\n";
    s << "<text x=\"" << fixed_text(left, 0) << "\" y=\"40\" font-size=\"10\" fill=\"#555\">"
      << xml_escape(r.against_exact ? "error against the scene's exact answers"
                                    : "error against a reference run at the finest settings")
      << "</text>\n";
    // Axes and decade ticks.
    s << "<rect x=\"" << fixed_text(left, 1) << "\" y=\"" << fixed_text(top, 1) << "\" width=\""
      << fixed_text(SweepLayout::plot_w, 1) << "\" height=\"" << fixed_text(l.plot_h, 1)
      << "\" fill=\"none\" stroke=\"#333\"/>\n";
}

// Decade grid lines with their labels, and the axes' names.
void draw_axes(std::ostringstream& s, const SweepLayout& l, const SweepResult& r) {
    const double left = SweepLayout::left, top = SweepLayout::top, plot_w = SweepLayout::plot_w;
    const double plot_h = l.plot_h;
    // Integer tick counts: the ends are whole decades, and a floating-point
    // loop counter could gain or lose a tick to rounding.
    const int x_ticks = static_cast<int>(std::lround(l.x1 - l.x0));
    for (int k = 0; k <= x_ticks; ++k) {
        const double d = l.x0 + k;
        s << "<line x1=\"" << fixed_text(l.px(d), 1) << "\" y1=\"" << fixed_text(top, 1)
          << "\" x2=\"" << fixed_text(l.px(d), 1) << "\" y2=\"" << fixed_text(top + plot_h, 1)
          << "\" stroke=\"#ddd\"/>\n";
        s << "<text x=\"" << fixed_text(l.px(d), 1) << "\" y=\"" << fixed_text(top + plot_h + 16, 1)
          << "\" text-anchor=\"middle\">1e" << fixed_text(d, 0) << "</text>\n";
    }
    const double ystep = l.y1 - l.y0 > 12 ? 2.0 : 1.0;
    const int y_ticks = static_cast<int>(std::lround(l.y1 - l.y0)) / static_cast<int>(ystep);
    for (int k = 0; k <= y_ticks; ++k) {
        const double d = l.y0 + k * ystep;
        s << "<line x1=\"" << fixed_text(left, 1) << "\" y1=\"" << fixed_text(l.py(d), 1)
          << "\" x2=\"" << fixed_text(left + plot_w, 1) << "\" y2=\"" << fixed_text(l.py(d), 1)
          << "\" stroke=\"#ddd\"/>\n";
        s << "<text x=\"" << fixed_text(left - 6, 1) << "\" y=\"" << fixed_text(l.py(d) + 4, 1)
          << "\" text-anchor=\"end\">1e" << fixed_text(d, 0) << "</text>\n";
    }
    s << "<text x=\"" << fixed_text(left + plot_w / 2, 1) << "\" y=\""
      << fixed_text(SweepLayout::height - 16, 1)
      << "\" text-anchor=\"middle\">"
      // Another engine's cost is what it reports or the process's wall time:
      // the caption says which (the sweep's cost_source).
      << xml_escape(r.cost_source.empty() ? "cost: wall time"
                                          : r.cost_source.substr(0, r.cost_source.find(';')))
      << " per simulated second (s/s, log)</text>\n";
    s << "<text transform=\"translate(20," << fixed_text(top + plot_h / 2, 1)
      << ") rotate(-90)\" text-anchor=\"middle\">error (relative, log; 0 drawn at 1e-17)</text>\n";
}

// All points, faint.
void draw_points(std::ostringstream& s, const SweepLayout& l,
                 std::map<std::string, std::string>& colour) {
    for (const SweepPoint* p : l.drawn) {
        s << "<circle cx=\"" << fixed_text(l.px(log_cost(*p)), 2) << "\" cy=\""
          << fixed_text(l.py(log_error(*p)), 2) << "\" r=\"2.5\" fill=\"" << colour[p->family]
          << "\" fill-opacity=\"0.25\"/>\n";
    }
}

// Each family's front, Box2D's thick and dashed.
void draw_fronts(std::ostringstream& s, const SweepLayout& l,
                 const std::vector<std::string>& families,
                 std::map<std::string, std::string>& colour) {
    for (const std::string& f : families) {
        std::vector<const SweepPoint*> front;
        for (const SweepPoint* p : l.drawn) {
            if (p->family == f && p->on_front) {
                front.push_back(p);
            }
        }
        if (front.empty()) {
            continue;
        }
        std::sort(front.begin(), front.end(), [&](const SweepPoint* a, const SweepPoint* b) {
            return log_cost(*a) < log_cost(*b);
        });
        const bool box2d = f == "box2d";
        s << "<polyline fill=\"none\" stroke=\"" << colour[f] << "\" stroke-width=\""
          << (box2d ? "3" : "1.5") << "\"" << dashes(f) << " points=\"";
        for (std::size_t i = 0; i < front.size(); ++i) {
            s << (i ? " " : "") << fixed_text(l.px(log_cost(*front[i])), 2) << ","
              << fixed_text(l.py(log_error(*front[i])), 2);
        }
        s << "\"/>\n";
        for (const SweepPoint* p : front) {
            s << "<circle cx=\"" << fixed_text(l.px(log_cost(*p)), 2) << "\" cy=\""
              << fixed_text(l.py(log_error(*p)), 2) << "\" r=\"" << (box2d ? "4" : "3")
              << "\" fill=\"" << colour[f] << "\"/>\n";
        }
    }
}

void draw_sweep_legend(std::ostringstream& s, const std::vector<std::string>& families,
                       std::map<std::string, std::string>& colour) {
    double ly0 = SweepLayout::top + 10;
    const double lx0 = SweepLayout::left + SweepLayout::plot_w + 20;
    for (const std::string& f : families) {
        const bool box2d = f == "box2d";
        s << "<line x1=\"" << fixed_text(lx0, 1) << "\" y1=\"" << fixed_text(ly0, 1) << "\" x2=\""
          << fixed_text(lx0 + 24, 1) << "\" y2=\"" << fixed_text(ly0, 1) << "\" stroke=\""
          << colour[f] << "\" stroke-width=\"" << (box2d ? "3" : "1.5") << "\"" << dashes(f)
          << "/>\n";
        s << "<text x=\"" << fixed_text(lx0 + 30, 1) << "\" y=\"" << fixed_text(ly0 + 4, 1) << "\">"
          << xml_escape(box2d ? "Box2D 2.4.1" : f) << "</text>\n";
        ly0 += 18;
    }
    s << "<text x=\"" << fixed_text(lx0, 1) << "\" y=\"" << fixed_text(ly0 + 8, 1)
      << "\" font-size=\"10\" fill=\"#555\">lines: Pareto fronts"
      << (std::any_of(families.begin(), families.end(), is_ccd) ? " (dotted: +ccd)" : "")
      << "; dots: all points</text>\n";
}

} // namespace

std::string sweep_svg(const SweepResult& r) {
    const SweepLayout layout = sweep_layout(r);
    // Families in first-appearance order; Box2D drawn last and distinct; a
    // "+ccd" family in its sibling's colour, dotted.
    const std::vector<std::string> families = families_of(r);
    std::map<std::string, std::string> colour = family_colours(families);
    std::ostringstream s;
    draw_header(s, layout, r);
    draw_axes(s, layout, r);
    draw_points(s, layout, colour);
    draw_fronts(s, layout, families, colour);
    draw_sweep_legend(s, families, colour);
    s << "</svg>\n";
    return s.str();
}

} // namespace impulse::harness
