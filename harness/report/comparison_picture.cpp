// The golden-versus-new picture (comparison_picture.h).
#include "comparison_picture.h"

#include "error_plot.h"
#include "first_divergence.h"
#include "legend.h"
#include "svg.h"
#include "tracks.h"
#include "viewport.h"
#include "world_marks.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace impulse::harness {

namespace {

using namespace picture;

bool is_event_column(const std::string& column) {
    return column.rfind("events[", 0) == 0;
}

// The two runs and each golden body's columns in both.
struct Runs {
    const Scene* scene;
    const Trajectory& gold;
    const Trajectory& value;
    std::vector<Track> tracks;     // the golden run's
    std::vector<Track> new_tracks; // the same bodies in the new run, one for one
    std::vector<Track> present;    // the new run's tracks that it has

    Runs(const Scene* scene_, const Trajectory& gold_, const Trajectory& value_)
        : scene(scene_), gold(gold_), value(value_), tracks(tracks_of(gold_, scene_)),
          new_tracks(tracks_in(value_, tracks)) {
        for (const Track& t : new_tracks) {
            if (has_position(t)) {
                present.push_back(t);
            }
        }
    }
};

// Both runs' motion, at least as wide as the error panel below: more world on
// either side.
View comparison_view(const Runs& runs) {
    Box motion = motion_bounds(runs.gold, runs.tracks);
    motion.add(motion_bounds(runs.value, runs.present));
    View view = fit_view(framed(motion, runs.scene), 620.0, 400.0);
    constexpr double narrowest_panel = 480.0;
    if (view.width() < narrowest_panel) {
        const double extra = (narrowest_panel - view.width()) / view.scale;
        view.x0 -= 0.5 * extra;
        view.x1 += 0.5 * extra;
    }
    return view;
}

std::string verdict_of(const Comparison& comparison, const Divergence* first) {
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
                   " s (" + (is_event_column(first->column) ? "event " : "frame ") +
                   std::to_string(first->frame) + "): golden " + readable(first->gold, 10) +
                   ", new " + readable(first->value, 10) + ", |difference| " +
                   readable(first->abs_diff, 3) + ", " + std::to_string(first->ulp) + " ULP.";
    }
    return verdict;
}

// The words at the top: the verdict, the first divergence and any structural difference.
std::vector<std::string> comparison_paragraphs(const Scene* scene, const Comparison& comparison,
                                               const Divergence* first) {
    std::vector<std::string> paragraphs;
    if (scene != nullptr && !scene->description.empty()) {
        paragraphs.push_back(scene->description);
    }
    paragraphs.push_back(verdict_of(comparison, first));
    for (std::size_t i = 0; i < comparison.structural.size() && i < 4; ++i) {
        paragraphs.push_back(comparison.structural[i]);
    }
    if (comparison.structural.size() > 4) {
        paragraphs.push_back("... and " + std::to_string(comparison.structural.size() - 4) +
                             " more structural differences.");
    }
    return paragraphs;
}

// The last frame's outline of each run, when the shapes are known.
void draw_last_outlines(std::string& body, const View& view, const Runs& runs) {
    const Trajectory& gold = runs.gold;
    const Trajectory& value = runs.value;
    for (std::size_t b = 0; b < runs.tracks.size(); ++b) {
        if (runs.tracks[b].body == nullptr) {
            continue;
        }
        Pose pose;
        if (!gold.frames.empty() && pose_at(gold, runs.tracks[b], gold.frames.size() - 1, pose)) {
            draw_outline(body, view, runs.tracks[b], pose, 0.35, 0.06, " stroke-width=\"1.2\"",
                         gold.frames.size() - 1, gold.frames.back()[0]);
        }
        if (has_position(runs.new_tracks[b]) && !value.frames.empty() &&
            pose_at(value, runs.new_tracks[b], value.frames.size() - 1, pose)) {
            draw_outline(body, view, runs.new_tracks[b], pose, 0.9, 0.0,
                         " stroke-width=\"1.2\" stroke-dasharray=\"5 3\"", value.frames.size() - 1,
                         value.frames.back()[0]);
        }
    }
}

// The golden paths wide and light, the new ones thin and dashed.
void draw_both_paths(std::string& body, const View& view, const Runs& runs) {
    for (const Track& track : runs.tracks) {
        body += "<polyline class=\"path gold\"" + attr("data-body", esc(track.name)) +
                attr("points", path_points(view, runs.gold, track)) + attr("stroke", track.colour) +
                " stroke-width=\"6\" stroke-opacity=\"0.3\" fill=\"none\" "
                "stroke-linejoin=\"round\" stroke-linecap=\"round\"/>\n";
    }
    for (const Track& track : runs.present) {
        body += "<polyline class=\"path new\"" + attr("data-body", esc(track.name)) +
                attr("points", path_points(view, runs.value, track)) +
                attr("stroke", track.colour) +
                " stroke-width=\"1.8\" stroke-dasharray=\"6 4\" fill=\"none\" "
                "stroke-linejoin=\"round\"/>\n";
    }
}

// Where the first divergence is in each run: the event's point or the body's
// position at the frame; infinite where a run has none.
void divergence_places(const Runs& runs, const Divergence& first, Vec2& g, Vec2& v) {
    const Trajectory& gold = runs.gold;
    const Trajectory& value = runs.value;
    if (is_event_column(first.column)) {
        if (first.frame < gold.events.size()) {
            g = {gold.events[first.frame].point[0], gold.events[first.frame].point[1]};
        }
        if (first.frame < value.events.size()) {
            v = {value.events[first.frame].point[0], value.events[first.frame].point[1]};
        }
        return;
    }
    const std::size_t dot = first.column.rfind('.');
    const std::string body_name = first.column.substr(0, dot);
    for (std::size_t b = 0; b < runs.tracks.size(); ++b) {
        Pose pose;
        if (runs.tracks[b].name != body_name) {
            continue;
        }
        if (first.frame < gold.frames.size() && pose_at(gold, runs.tracks[b], first.frame, pose)) {
            g = pose.p;
        }
        if (has_position(runs.new_tracks[b]) && first.frame < value.frames.size() &&
            pose_at(value, runs.new_tracks[b], first.frame, pose)) {
            v = pose.p;
        }
    }
}

// A ring around the new position (or event point), joined to the golden one.
void draw_divergence(std::string& body, const View& view, const Runs& runs,
                     const Divergence& first) {
    Vec2 g{infinity, infinity}, v{infinity, infinity};
    divergence_places(runs, first, g, v);
    const Vec2 at = std::isfinite(v.x) ? v : g;
    if (!std::isfinite(at.x)) {
        return;
    }
    body += "<g class=\"divergence\">";
    if (std::isfinite(g.x) && std::isfinite(v.x)) {
        body += "<path" +
                attr("d", "M" + f2(view.sx(g.x)) + " " + f2(view.sy(g.y)) + "L" + f2(view.sx(v.x)) +
                              " " + f2(view.sy(v.y))) +
                " stroke=\"" + divergence_colour + "\" stroke-width=\"1.5\"/>";
    }
    body += "<circle" + attr("cx", f2(view.sx(at.x))) + attr("cy", f2(view.sy(at.y))) +
            " r=\"9\" fill=\"none\" stroke=\"" + divergence_colour + "\" stroke-width=\"2.2\"/>";
    body += "</g>\n";
    text_at(body, view.sx(at.x) + 12.0, view.sy(at.y) - 10.0,
            "first divergence, t = " + readable(first.t) + " s", small_size, divergence_colour,
            " font-weight=\"bold\" stroke=\"#ffffff\" stroke-width=\"3\" "
            "paint-order=\"stroke\" stroke-linejoin=\"round\"");
}

std::vector<LegendItem> paths_legend(const Runs& runs, const Divergence* first) {
    std::vector<LegendItem> legend = body_legend(runs.tracks);
    legend.push_back({LegendItem::Kind::line, "golden path", "#888888", "", true});
    legend.push_back({LegendItem::Kind::line, "new path", "#555555", "6 4", false});
    legend.push_back({LegendItem::Kind::ring, "golden contact", ink, "", false});
    legend.push_back({LegendItem::Kind::contact, "new contact", ink, "", false});
    legend.push_back({LegendItem::Kind::normal, "normal (toward a)", ink, "", false});
    if (first != nullptr) {
        legend.push_back({LegendItem::Kind::divergence, "first divergence", ink, "", false});
    }
    if (runs.scene != nullptr) {
        // The time of the outlines, so the picture says when they were drawn;
        // no-break spaces keep "t = T s" on one line of the wrapped note.
        std::string when;
        if (!runs.gold.frames.empty()) {
            when = ", t\u00a0=\u00a0" + readable(runs.gold.frames.back()[0]) + "\u00a0s";
        }
        legend.push_back({LegendItem::Kind::note,
                          "Outlines at the last frame" + when + ": golden solid, new dashed.",
                          muted, "", false});
    }
    return legend;
}

// Panel 1: the paths, from y down; returns the bottom of the panel or its legend.
double draw_paths_panel(std::string& body, View& view, double y, double legend_x, const Runs& runs,
                        const Divergence* first) {
    y += 4.0;
    text_at(body, pad, y, "Paths of the centres of mass", text_size, ink, " font-weight=\"bold\"");
    y += 30.0;
    view.left = pad + axis_left;
    view.top = y;
    draw_frame_and_grid(body, view, "x (m)", "y (m)");
    draw_static_bodies(body, view, runs.scene);
    draw_last_outlines(body, view, runs);
    draw_both_paths(body, view, runs);
    draw_events(body, view, runs.gold.events, true, " gold");
    draw_events(body, view, runs.value.events, false, " new");
    if (first != nullptr) {
        draw_divergence(body, view, runs, *first);
    }
    draw_plot_border(body, view);
    const double legend_end = draw_legend(body, legend_x, view.top, paths_legend(runs, first));
    return std::max(view.top + view.height() + axis_bottom, legend_end);
}

// Panel 2: the error over time, from y down; returns the bottom of the panel or its legend.
double draw_error_section(std::string& body, double y, double legend_x, const Runs& runs,
                          const Divergence* first) {
    const Trajectory& gold = runs.gold;
    const Trajectory& value = runs.value;
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
    const double error_bottom =
        draw_error_panel(body, error_series(gold, value), error_left, y, error_width, 220.0, first);
    std::vector<LegendItem> channels;
    for (std::size_t c = 0; c < frame_channel_count; ++c) {
        channels.push_back({LegendItem::Kind::line, channel_label(c), channel_colours[c],
                            channel_dashes[c], false});
    }
    if (first != nullptr) {
        channels.push_back(
            {LegendItem::Kind::note, "Dashed red line: the first divergence.", muted, "", false});
    }
    const double legend_end = draw_legend(body, legend_x, y, channels);
    return std::max(error_bottom + axis_bottom, legend_end);
}

} // namespace

std::string render_comparison_svg(const Scene* scene, const Trajectory& gold,
                                  const Trajectory& value, const Comparison& comparison) {
    const Runs runs(scene, gold, value);
    View view = comparison_view(runs);
    const double width = pad + axis_left + view.width() + legend_gap + legend_width + pad;
    // The one first divergence of the gate (first_divergence.h), so the picture
    // marks what the terminal, JUnit, summary.md and the page name.
    const Divergence* first = earliest_divergence(comparison);

    std::string body;
    const std::string name = scene != nullptr ? scene->name : gold.scene;
    const double y = draw_title(body, width, name + ": golden vs new",
                                comparison_paragraphs(scene, comparison, first),
                                {"golden: " + run_info(gold), "new: " + run_info(value)});
    const double legend_x = width - pad - legend_width;
    const double paths_end = draw_paths_panel(body, view, y, legend_x, runs, first);
    const double error_end = draw_error_section(body, paths_end + 26.0, legend_x, runs, first);
    return svg_document(width, error_end + pad, body);
}

} // namespace impulse::harness
