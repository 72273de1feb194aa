// The sweep's plot (impulse sweep --svg): error against cost, both on log
// scales, as an SVG built by hand so the same result gives the same bytes.
// Written for a reader who has never seen the project: every family has its
// own colour and marker (Okabe and Ito's colour-blind-safe palette), the front
// points carry their time steps, the legend says what the axes are and that
// lower-left is better, and the verdicts under the plot say in words how
// accurate impulse is at each reference's cost.
#include "sweep_plot.h"

#include "markup.h"
#include "sweep_verdict.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace impulse::harness {

namespace {

// Errors of exactly 0 (and anything below) are drawn at this floor.
constexpr double plot_error_floor = 1e-17;

constexpr std::string_view ccd_suffix = "+ccd";

bool is_ccd(const std::string& f) {
    return f.size() > ccd_suffix.size() &&
           f.compare(f.size() - ccd_suffix.size(), ccd_suffix.size(), ccd_suffix) == 0;
}

bool starts_with(const std::string& text, std::string_view prefix) {
    return text.compare(0, prefix.size(), prefix) == 0;
}

// How one family is drawn and named in the legend.
struct FamilyStyle {
    std::string family;
    std::string colour;
    std::string marker; // circle, square, triangle, triangle-down, diamond, cross, plus
    bool hollow = false;
    std::string dash;  // the front line's stroke-dasharray, empty for solid
    std::string label; // for a stranger
    bool reference = false;
};

// Okabe and Ito's palette (2008), safe for the common colour blindnesses;
// its yellow is left out, too pale on white.
constexpr const char* sky_blue = "#56B4E9";
constexpr const char* bluish_green = "#009E73";
constexpr const char* blue = "#0072B2";
constexpr const char* black = "#000000";
constexpr const char* vermillion = "#D55E00";
constexpr const char* reddish_purple = "#CC79A7";
constexpr const char* orange = "#E69F00";
constexpr const char* grey = "#7F7F7F";

// impulse's families: colour by integrator, marker by time-of-impact method,
// hollow and dotted with ccd. "impulse verlet/secant+ccd".
FamilyStyle impulse_style(const std::string& family) {
    FamilyStyle s;
    const std::string base = is_ccd(family) ? family.substr(0, family.size() - 4) : family;
    const std::size_t space = base.find(' '), slash = base.find('/');
    const std::string integrator =
        base.substr(space + 1, slash == std::string::npos ? std::string::npos : slash - space - 1);
    const std::string toi = slash == std::string::npos ? "" : base.substr(slash + 1);
    s.colour = integrator == "euler"              ? sky_blue
               : integrator == "symplectic-euler" ? bluish_green
               : integrator == "verlet"           ? blue
                                                  : black;
    s.marker = toi == "bisection" ? "square" : "circle";
    s.hollow = is_ccd(family);
    s.dash = s.hollow ? "2 3" : "";
    s.label = base.substr(0, space) + ", " + integrator + " integrator" +
              (toi.empty() ? "" : ", " + toi + " time of impact") + (s.hollow ? ", ccd on" : "");
    return s;
}

FamilyStyle reference_style(const std::string& family, const std::string& title,
                            std::size_t other) {
    FamilyStyle s;
    s.reference = true;
    s.dash = "8 4";
    s.label = title + " (reference)";
    if (family == "box2d") {
        s.colour = vermillion;
        s.marker = "triangle";
    } else if (starts_with(family, "box2d-3")) {
        s.colour = reddish_purple;
        s.marker = "diamond";
    } else if (family == "chipmunk") {
        s.colour = orange;
        s.marker = "triangle-down";
    } else if (family == "rapier") {
        s.colour = grey;
        s.marker = "cross";
    } else {
        const char* colours[] = {grey, orange, reddish_purple, vermillion};
        s.colour = colours[other % 4];
        s.marker = "plus";
    }
    return s;
}

// Families in first-appearance order, each with its style.
std::vector<FamilyStyle> family_styles(const SweepResult& r) {
    std::vector<FamilyStyle> styles;
    std::size_t other = 0;
    for (const SweepPoint& p : r.points) {
        if (std::any_of(styles.begin(), styles.end(),
                        [&](const FamilyStyle& s) { return s.family == p.family; })) {
            continue;
        }
        FamilyStyle s;
        if (is_reference_point(p)) {
            std::string title = p.box2d ? "Box2D 2.4.1" : p.family;
            for (const auto& [family, t] : r.references) {
                title = family == p.family ? t : title;
            }
            s = reference_style(p.family, title, other++);
        } else if (p.kind == EngineSpec::Kind::impulse) {
            s = impulse_style(p.family);
        } else {
            // Another engine under study: its integrators in impulse's colours.
            s = impulse_style("x " + std::string(integrator_name(p.integrator)));
            s.marker = "plus";
            s.label = p.family + " (the engine under study)";
        }
        s.family = p.family;
        styles.push_back(s);
    }
    return styles;
}

const FamilyStyle& style_of(const std::vector<FamilyStyle>& styles, const std::string& family) {
    return *std::find_if(styles.begin(), styles.end(),
                         [&](const FamilyStyle& s) { return s.family == family; });
}

// One marker centred at (x, y), `r` its half-size.
void draw_marker(std::ostringstream& s, const FamilyStyle& style, double x, double y, double r,
                 const std::string& extra) {
    const std::string paint =
        style.hollow ? "fill=\"white\" stroke=\"" + style.colour + "\" stroke-width=\"1.5\""
                     : "fill=\"" + style.colour + "\"";
    const auto pt = [](double a, double b) { return fixed_text(a, 2) + "," + fixed_text(b, 2); };
    const std::string& m = style.marker;
    if (m == "circle") {
        s << "<circle cx=\"" << fixed_text(x, 2) << "\" cy=\"" << fixed_text(y, 2) << "\" r=\""
          << fixed_text(r, 1) << "\" " << paint;
    } else if (m == "square") {
        s << "<rect x=\"" << fixed_text(x - r, 2) << "\" y=\"" << fixed_text(y - r, 2)
          << "\" width=\"" << fixed_text(2 * r, 1) << "\" height=\"" << fixed_text(2 * r, 1)
          << "\" " << paint;
    } else if (m == "triangle" || m == "triangle-down" || m == "diamond") {
        const double k = m == "triangle-down" ? -1.0 : 1.0;
        const std::string points = m == "diamond" ? pt(x, y - r * 1.3) + " " + pt(x + r, y) + " " +
                                                        pt(x, y + r * 1.3) + " " + pt(x - r, y)
                                                  : pt(x, y - k * r * 1.2) + " " +
                                                        pt(x + r * 1.1, y + k * r * 0.8) + " " +
                                                        pt(x - r * 1.1, y + k * r * 0.8);
        s << "<polygon points=\"" << points << "\" " << paint;
    } else {
        // cross (x) or plus (+): strokes only.
        const bool x_shape = m == "cross";
        const double a = x_shape ? r : 0.0, b = r * 1.2;
        s << "<path d=\"M" << pt(x - (x_shape ? a : b), y - a) << " L"
          << pt(x + (x_shape ? a : b), y + a) << " M" << pt(x - a, y + (x_shape ? a : -b)) << " L"
          << pt(x + a, y - (x_shape ? a : -b)) << "\" fill=\"none\" stroke=\"" << style.colour
          << "\" stroke-width=\"2\"";
    }
    s << extra << "/>\n";
}

// One panel: error (or energy gained) against cost.
struct Panel {
    static constexpr double left = 90, plot_w = 520, plot_h = 360;
    double top = 0.0;
    SweepAxis axis = SweepAxis::error;
    std::vector<const SweepPoint*> drawn;
    double x0 = 0, x1 = 1, y0 = 0, y1 = 1;

    double px(double v) const { return left + (v - x0) / (x1 - x0) * plot_w; }
    double py(double v) const { return top + (y1 - v) / (y1 - y0) * plot_h; }
    double log_cost(const SweepPoint& p) const { return std::log10(p.cost_median); }
    double log_error(const SweepPoint& p) const {
        return std::log10(std::max(axis_value(p, axis), plot_error_floor));
    }
};

Panel panel_for(const SweepResult& r, SweepAxis axis, double top) {
    Panel l;
    l.top = top;
    l.axis = axis;
    for (const SweepPoint& p : r.points) {
        if (p.ok && std::isfinite(axis_value(p, axis)) && p.cost_median > 0.0) {
            l.drawn.push_back(&p);
        }
    }
    if (!l.drawn.empty()) {
        l.x0 = l.y0 = 1e300;
        l.x1 = l.y1 = -1e300;
        for (const SweepPoint* p : l.drawn) {
            l.x0 = std::min(l.x0, l.log_cost(*p));
            l.x1 = std::max(l.x1, l.log_cost(*p));
            l.y0 = std::min(l.y0, l.log_error(*p));
            l.y1 = std::max(l.y1, l.log_error(*p));
        }
        l.x0 = std::floor(l.x0);
        l.x1 = std::max(std::ceil(l.x1), l.x0 + 1);
        l.y0 = std::floor(l.y0);
        l.y1 = std::max(std::ceil(l.y1), l.y0 + 1);
    }
    return l;
}

std::string cost_axis_name(const SweepResult& r) {
    if (r.pile) {
        return "cost: wall-clock seconds per body-step (log)";
    }
    // Another engine's cost is what it reports or the process's wall time.
    return (r.cost_source.empty() ? std::string("cost: wall time")
                                  : r.cost_source.substr(0, r.cost_source.find(';'))) +
           " per simulated second (s/s, log)";
}

std::string error_axis_name(const SweepResult& r, SweepAxis axis) {
    if (r.pile) {
        return axis == SweepAxis::error ? "deepest overlap of any pair, any frame (m, log)"
                                        : "energy gained over the run (relative, log)";
    }
    return r.against_exact ? "error against the exact answers (relative, log)"
                           : "error against a fine reference run (relative, log)";
}

// Frame, decade grid lines with their labels, and the axes' names.
void draw_axes(std::ostringstream& s, const Panel& l, const SweepResult& r) {
    const double left = Panel::left, top = l.top, plot_w = Panel::plot_w, plot_h = Panel::plot_h;
    // Integer tick counts: the ends are whole decades, and a floating-point
    // loop counter could gain or lose a tick to rounding.
    const int x_ticks = static_cast<int>(std::lround(l.x1 - l.x0));
    for (int k = 0; k <= x_ticks; ++k) {
        const double d = l.x0 + k;
        s << "<line x1=\"" << fixed_text(l.px(d), 1) << "\" y1=\"" << fixed_text(top, 1)
          << "\" x2=\"" << fixed_text(l.px(d), 1) << "\" y2=\"" << fixed_text(top + plot_h, 1)
          << "\" stroke=\"#e4e4e4\"/>\n";
        s << "<text x=\"" << fixed_text(l.px(d), 1) << "\" y=\"" << fixed_text(top + plot_h + 16, 1)
          << "\" text-anchor=\"middle\">1e" << fixed_text(d, 0) << "</text>\n";
    }
    const double ystep = l.y1 - l.y0 > 12 ? 2.0 : 1.0;
    const int y_ticks = static_cast<int>(std::lround(l.y1 - l.y0)) / static_cast<int>(ystep);
    for (int k = 0; k <= y_ticks; ++k) {
        const double d = l.y0 + k * ystep;
        s << "<line x1=\"" << fixed_text(left, 1) << "\" y1=\"" << fixed_text(l.py(d), 1)
          << "\" x2=\"" << fixed_text(left + plot_w, 1) << "\" y2=\"" << fixed_text(l.py(d), 1)
          << "\" stroke=\"#e4e4e4\"/>\n";
        s << "<text x=\"" << fixed_text(left - 6, 1) << "\" y=\"" << fixed_text(l.py(d) + 4, 1)
          << "\" text-anchor=\"end\">1e" << fixed_text(d, 0) << "</text>\n";
    }
    s << "<rect x=\"" << fixed_text(left, 1) << "\" y=\"" << fixed_text(top, 1) << "\" width=\""
      << fixed_text(plot_w, 1) << "\" height=\"" << fixed_text(plot_h, 1)
      << "\" fill=\"none\" stroke=\"#333\"/>\n";
    s << "<text x=\"" << fixed_text(left + plot_w / 2, 1) << "\" y=\""
      << fixed_text(top + plot_h + 36, 1) << "\" text-anchor=\"middle\">"
      << xml_escape(cost_axis_name(r)) << "</text>\n";
    s << "<text transform=\"translate(22," << fixed_text(top + plot_h / 2, 1)
      << ") rotate(-90)\" text-anchor=\"middle\">" << xml_escape(error_axis_name(r, l.axis))
      << "</text>\n";
    s << "<text x=\"" << fixed_text(left + plot_w - 6, 1) << "\" y=\"" << fixed_text(top + 14, 1)
      << "\" text-anchor=\"end\" font-size=\"11\" fill=\"#555\">better: towards the lower "
         "left</text>\n";
}

// Every point faint, then each family's front: a line, full markers and the
// time step of each front point beside it.
void draw_families(std::ostringstream& s, const Panel& l, const std::vector<FamilyStyle>& styles) {
    for (const SweepPoint* p : l.drawn) {
        draw_marker(s, style_of(styles, p->family), l.px(l.log_cost(*p)), l.py(l.log_error(*p)),
                    2.5, " opacity=\"0.3\"");
    }
    for (std::size_t k = 0; k < styles.size(); ++k) {
        const FamilyStyle& style = styles[k];
        std::vector<const SweepPoint*> members;
        std::vector<std::pair<double, double>> cost_error;
        for (const SweepPoint* p : l.drawn) {
            if (p->family == style.family) {
                members.push_back(p);
                cost_error.emplace_back(p->cost_median, axis_value(*p, l.axis));
            }
        }
        std::vector<const SweepPoint*> front;
        for (const std::size_t i : pareto_front(cost_error)) {
            front.push_back(members[i]);
        }
        if (front.empty()) {
            continue;
        }
        s << "<polyline class=\"front\" data-family=\"" << xml_escape(style.family, true)
          << "\" fill=\"none\" stroke=\"" << style.colour << "\" stroke-width=\""
          << (style.reference ? "2.5" : "1.5") << "\""
          << (style.dash.empty() ? "" : " stroke-dasharray=\"" + style.dash + "\"") << " points=\"";
        for (std::size_t i = 0; i < front.size(); ++i) {
            s << (i ? " " : "") << fixed_text(l.px(l.log_cost(*front[i])), 2) << ","
              << fixed_text(l.py(l.log_error(*front[i])), 2);
        }
        s << "\"/>\n";
        // Labels alternate above and below by family, so neighbours overlap less.
        const double dy = k % 2 == 0 ? -7.0 : 13.0;
        for (const SweepPoint* p : front) {
            const double x = l.px(l.log_cost(*p)), y = l.py(l.log_error(*p));
            draw_marker(s, style, x, y, style.reference ? 5.0 : 4.0, "");
            s << "<text class=\"dt-label\" x=\"" << fixed_text(x + 5, 2) << "\" y=\""
              << fixed_text(y + dy, 2) << "\" font-size=\"9\" fill=\"" << style.colour << "\">"
              << sweep_dt_label(p->dt) << "</text>\n";
        }
    }
}

// What a stranger needs to read the plot, then one entry per family.
void draw_legend(std::ostringstream& s, const SweepResult& r,
                 const std::vector<FamilyStyle>& styles, double x) {
    double y = 100;
    const auto line = [&](const std::string& text, const char* colour = "#333") {
        s << "<text x=\"" << fixed_text(x, 1) << "\" y=\"" << fixed_text(y, 1) << "\" fill=\""
          << colour << "\">" << xml_escape(text) << "</text>\n";
        y += 16;
    };
    line("How to read this plot:");
    line("each mark is one run of the scene with one set of settings;");
    line("lower left is better: cheaper and more accurate.");
    line("A line joins a family's Pareto front: the runs no other run");
    line("of that family beats on both cost and error.");
    line("Labels give the time step in seconds (1/60: 60 steps a second).");
    line("Errors of 0 are drawn at 1e-17. Faint marks: the other runs.");
    line("Dashed lines: the reference engines.");
    y += 10;
    for (const FamilyStyle& style : styles) {
        s << "<g class=\"legend-entry\" data-family=\"" << xml_escape(style.family, true)
          << "\" data-colour=\"" << style.colour << "\" data-marker=\"" << style.marker
          << (style.hollow ? "-hollow" : "") << "\">\n";
        s << "<line x1=\"" << fixed_text(x, 1) << "\" y1=\"" << fixed_text(y - 4, 1) << "\" x2=\""
          << fixed_text(x + 28, 1) << "\" y2=\"" << fixed_text(y - 4, 1) << "\" stroke=\""
          << style.colour << "\" stroke-width=\"" << (style.reference ? "2.5" : "1.5") << "\""
          << (style.dash.empty() ? "" : " stroke-dasharray=\"" + style.dash + "\"") << "/>\n";
        draw_marker(s, style, x + 14, y - 4, style.reference ? 5.0 : 4.0, "");
        s << "<text x=\"" << fixed_text(x + 36, 1) << "\" y=\"" << fixed_text(y, 1) << "\">"
          << xml_escape(style.label) << "</text>\n</g>\n";
        y += 18;
    }
    (void)r;
}

// `text` in lines of at most `width` characters, broken at spaces.
std::vector<std::string> wrapped(const std::string& text, std::size_t width) {
    std::vector<std::string> lines{""};
    std::size_t start = 0;
    while (start < text.size()) {
        const std::size_t end = std::min(text.find(' ', start), text.size());
        const std::string word = text.substr(start, end - start);
        if (!lines.back().empty() && lines.back().size() + 1 + word.size() > width) {
            lines.emplace_back();
        }
        lines.back() += (lines.back().empty() ? "" : " ") + word;
        start = end + 1;
    }
    return lines;
}

// The verdict lines: per reference (and per axis on a pile), in words.
std::vector<std::string> verdict_lines(const SweepResult& r) {
    std::vector<std::string> lines;
    const std::vector<SweepAxis> axes =
        r.pile ? std::vector<SweepAxis>{SweepAxis::error, SweepAxis::energy}
               : std::vector<SweepAxis>{SweepAxis::error};
    for (const SweepAxis axis : axes) {
        for (const ReferenceVerdict& v : reference_verdicts(r, axis)) {
            std::string text = verdict_headline(r, v, axis);
            if (v.front_size > 0) {
                text += v.dominates() ? "; its front dominates " + v.title + "'s"
                                      : "; its front does not dominate " + v.title + "'s";
            }
            lines.push_back(text);
        }
    }
    return lines;
}

} // namespace

std::string sweep_svg(const SweepResult& r) {
    const std::vector<FamilyStyle> styles = family_styles(r);
    std::vector<Panel> panels{panel_for(r, SweepAxis::error, 96)};
    if (r.pile) {
        panels.push_back(panel_for(r, SweepAxis::energy, 96 + Panel::plot_h + 70));
    }
    const std::vector<std::string> verdicts = verdict_lines(r);
    std::size_t longest = 0;
    for (const FamilyStyle& style : styles) {
        longest = std::max(longest, style.label.size());
    }
    const double legend_x = Panel::left + Panel::plot_w + 30;
    const double width = legend_x + std::max(400.0, 50.0 + 6.5 * static_cast<double>(longest));
    const double panels_end = panels.back().top + Panel::plot_h + 50;
    const double legend_end = 100 + 16 * 8 + 10 + 18 * static_cast<double>(styles.size());
    const double verdict_top = std::max(panels_end, legend_end) + 10;
    const double height = verdict_top + 18 * static_cast<double>(verdicts.size()) + 20;

    std::ostringstream s;
    s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << fixed_text(width, 0)
      << "\" height=\"" << fixed_text(height, 0) << "\" viewBox=\"0 0 " << fixed_text(width, 0)
      << " " << fixed_text(height, 0) << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    s << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    s << "<text x=\"" << fixed_text(Panel::left, 0) << "\" y=\"26\" font-size=\"16\">"
      << xml_escape("impulse sweep: " + r.scene + ", accuracy against cost") << "</text>\n";
    double y = 44;
    for (const std::string& line :
         wrapped(r.error_reference + (r.pile ? "; " + r.energy_reference : ""),
                 static_cast<std::size_t>(width / 6.2) - 20)) {
        s << "<text x=\"" << fixed_text(Panel::left, 0) << "\" y=\"" << fixed_text(y, 0)
          << "\" font-size=\"11\" fill=\"#555\">" << xml_escape(line) << "</text>\n";
        y += 14;
    }
    for (const Panel& panel : panels) {
        draw_axes(s, panel, r);
        draw_families(s, panel, styles);
    }
    draw_legend(s, r, styles, legend_x);
    y = verdict_top;
    for (const std::string& line : verdicts) {
        s << "<text class=\"verdict\" x=\"" << fixed_text(Panel::left, 0) << "\" y=\""
          << fixed_text(y, 1) << "\" font-size=\"13\">" << xml_escape(line) << "</text>\n";
        y += 18;
    }
    s << "</svg>\n";
    return s.str();
}

} // namespace impulse::harness
