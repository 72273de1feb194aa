// The picture of one run (motion_picture.h).
#include "motion_picture.h"

#include "legend.h"
#include "progress.h"
#include "svg.h"
#include "tracks.h"
#include "viewport.h"
#include "world_marks.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace impulse::harness {

namespace {

using namespace picture;

// Contact marks get a visible time label only while they stay few enough to
// read; every one has its time in its tooltip.
constexpr std::size_t labelled_events = 12;

std::string stop_sentence(const TrajectoryPartial& partial) {
    return "Stopped early at t = " + readable(partial.t, 6) + " s: " + partial.reason;
}

// The scene's name and description, or the trajectory's scene name and why
// there are no shapes; returns the y below the title.
double draw_motion_title(std::string& body, double width, const Scene* scene,
                         const Trajectory& trajectory) {
    std::vector<std::string> paragraphs;
    if (trajectory.partial) {
        // First: the picture shows a run that did not reach the scene's end.
        paragraphs.push_back(stop_sentence(*trajectory.partial));
    }
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
    return draw_title(body, width, title, paragraphs, {run_info(trajectory)});
}

// Every body's outline at the key frames, older ones fainter; the first
// body's outlines carry the key frame's time (the others share it).
void draw_key_frames(std::string& body, const View& view, const Trajectory& trajectory,
                     const std::vector<Track>& tracks, const std::vector<std::size_t>& keys) {
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
            const double t = trajectory.frames[keys[i]][0];
            draw_outline(body, view, track, pose, 0.22 + 0.78 * age, 0.02 + 0.06 * age,
                         last ? " stroke-width=\"2\"" : " stroke-width=\"1.3\"", keys[i], t);
            if (&track == &tracks.front()) {
                draw_time_label(body, view.sx(pose.p.x) + 8.0, view.sy(pose.p.y) - 6.0, t);
            }
        }
    }
}

void draw_event_times(std::string& body, const View& view,
                      const std::vector<TrajectoryEvent>& events) {
    if (events.size() > labelled_events) {
        return;
    }
    for (const TrajectoryEvent& e : events) {
        draw_time_label(body, view.sx(e.point[0]) + 6.0, view.sy(e.point[1]) + 14.0, e.t);
    }
}

// Where a partial run stopped: a ring around every body at the last frame,
// and the time and reason beside the first.
void draw_stop(std::string& body, const View& view, const Trajectory& trajectory,
               const std::vector<Track>& tracks) {
    if (!trajectory.partial || trajectory.frames.empty()) {
        return;
    }
    const std::size_t last = trajectory.frames.size() - 1;
    const std::string t = readable(trajectory.partial->t, 6);
    body += "<g class=\"stop\"" + attr("data-t", t) + attr("data-frame", std::to_string(last)) +
            "><title>" + esc(stop_sentence(*trajectory.partial)) + "</title>";
    bool labelled = false;
    std::string label;
    for (const Track& track : tracks) {
        Pose pose;
        if (!pose_at(trajectory, track, last, pose)) {
            continue;
        }
        const double x = view.sx(pose.p.x), y = view.sy(pose.p.y);
        body += "<circle" + attr("data-body", esc(track.name)) + attr("cx", f2(x)) +
                attr("cy", f2(y)) + " r=\"9\" fill=\"none\" stroke=\"" + divergence_colour +
                "\" stroke-width=\"2.2\"/>";
        if (!labelled) {
            labelled = true;
            text_at(label, x + 12.0, y - 10.0, "stopped, t = " + t + " s", small_size,
                    divergence_colour,
                    " font-weight=\"bold\" stroke=\"#ffffff\" stroke-width=\"3\" "
                    "paint-order=\"stroke\" stroke-linejoin=\"round\"");
        }
    }
    body += "</g>\n" + label;
}

void draw_paths(std::string& body, const View& view, const Trajectory& trajectory,
                const std::vector<Track>& tracks) {
    for (std::size_t k = 0; k < tracks.size(); ++k) {
        const Track& track = tracks[k];
        body += "<polyline class=\"path\"" + attr("data-body", esc(track.name)) +
                attr("points", path_points(view, trajectory, track)) +
                attr("stroke", track.colour) +
                " stroke-width=\"2\" fill=\"none\" stroke-linejoin=\"round\"/>\n";
        note_drawn(k + 1, tracks.size()); // for the progress bar only
    }
}

std::vector<LegendItem> motion_legend(const Scene* scene, const Trajectory& trajectory,
                                      const std::vector<Track>& tracks, std::size_t key_count) {
    std::vector<LegendItem> legend = body_legend(tracks);
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
    if (trajectory.partial) {
        legend.push_back({LegendItem::Kind::divergence, "where the run stopped", ink, "", false});
        legend.push_back(
            {LegendItem::Kind::note,
             "Red rings: the bodies at the last frame, t = " + readable(trajectory.partial->t, 6) +
                 " s; why the run stopped is under the title.",
             muted, "", false});
    }
    legend.push_back({LegendItem::Kind::note,
                      "Lines: paths of the centres of mass. " +
                          std::string(scene != nullptr ? "Outlines"
                                                       : "Rings with a line at the "
                                                         "body's angle") +
                          " at " + std::to_string(key_count) +
                          " key frames, older ones fainter, with their times.",
                      muted, "", false});
    return legend;
}

std::string render_motion(const Scene* scene, const Trajectory& trajectory) {
    const std::vector<Track> tracks = tracks_of(trajectory, scene);
    View view = fit_view(framed(motion_bounds(trajectory, tracks), scene), 620.0, 470.0);
    const double width = pad + axis_left + view.width() + legend_gap + legend_width + pad;

    std::string body;
    view.left = pad + axis_left;
    view.top = draw_motion_title(body, width, scene, trajectory);
    draw_frame_and_grid(body, view, "x (m)", "y (m)");
    draw_static_bodies(body, view, scene);
    const std::vector<std::size_t> keys = key_frames(trajectory.frames.size());
    draw_key_frames(body, view, trajectory, tracks, keys);
    draw_paths(body, view, trajectory, tracks);
    draw_events(body, view, trajectory.events, false, "");
    draw_event_times(body, view, trajectory.events);
    draw_stop(body, view, trajectory, tracks);
    draw_plot_border(body, view);

    const double legend_x = view.left + view.width() + legend_gap;
    const double legend_end = draw_legend(body, legend_x, view.top,
                                          motion_legend(scene, trajectory, tracks, keys.size()));
    const double height = std::max(view.top + view.height() + axis_bottom, legend_end) + pad;
    return svg_document(width, height, body);
}

} // namespace

std::string render_svg(const Scene& scene, const Trajectory& trajectory) {
    return render_motion(&scene, trajectory);
}

std::string render_svg(const Trajectory& trajectory) {
    return render_motion(nullptr, trajectory);
}

} // namespace impulse::harness
