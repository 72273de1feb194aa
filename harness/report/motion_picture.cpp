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
// At most this many times in one label of contacts at one place.
constexpr std::size_t times_per_label = 4;

// The time labels placed so far: a label that would overlap one is left out
// (its time stays in the mark's tooltip), so the ones drawn can be read.
struct Labels {
    struct Place {
        double x0, y0, x1, y1;
    };
    std::vector<Place> placed;

    void draw(std::string& out, double x, double y, const std::string& text) {
        // small_size type: about 0.6 em a character, 1.2 em a line.
        const Place p{x, y - small_size, x + 0.6 * small_size * static_cast<double>(text.size()),
                      y + 0.2 * small_size};
        for (const Place& q : placed) {
            if (p.x0 < q.x1 && q.x0 < p.x1 && p.y0 < q.y1 && q.y0 < p.y1) {
                return;
            }
        }
        placed.push_back(p);
        draw_time_label(out, x, y, text);
    }
};

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

// The first body's key frames carry their times (the other bodies share
// them): the first and the last before the ones between, so that those two
// are the ones kept where labels would overlap.
void label_key_frames(std::string& body, const View& view, const Trajectory& trajectory,
                      const Track& track, const std::vector<std::size_t>& keys, Labels& labels) {
    std::vector<std::size_t> order(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) {
        order[i] = i == 0 ? 0 : i == 1 ? keys.size() - 1 : i - 1;
    }
    for (const std::size_t i : order) {
        Pose pose;
        if (pose_at(trajectory, track, keys[i], pose)) {
            labels.draw(body, view.sx(pose.p.x) + 8.0, view.sy(pose.p.y) - 6.0,
                        time_text({trajectory.frames[keys[i]][0]}));
        }
    }
}

// Every body's outline at the key frames, older ones fainter.
void draw_key_frames(std::string& body, const View& view, const Trajectory& trajectory,
                     const std::vector<Track>& tracks, const std::vector<std::size_t>& keys,
                     Labels& labels) {
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
    if (!tracks.empty()) {
        label_key_frames(body, view, trajectory, tracks.front(), keys, labels);
    }
}

// Contacts at one place (the same pixel) share a label: "t = 0.4515, 1.174 s".
void draw_event_times(std::string& body, const View& view,
                      const std::vector<TrajectoryEvent>& events, Labels& labels) {
    if (events.size() > labelled_events) {
        return;
    }
    std::vector<bool> done(events.size(), false);
    for (std::size_t i = 0; i < events.size(); ++i) {
        if (done[i]) {
            continue;
        }
        const std::string at =
            f2(view.sx(events[i].point[0])) + "," + f2(view.sy(events[i].point[1]));
        std::vector<double> times;
        for (std::size_t k = i; k < events.size(); ++k) {
            if (!done[k] &&
                f2(view.sx(events[k].point[0])) + "," + f2(view.sy(events[k].point[1])) == at) {
                done[k] = true;
                times.push_back(events[k].t);
            }
        }
        std::string text = time_text(
            {times.begin(),
             times.begin() + static_cast<std::ptrdiff_t>(std::min(times.size(), times_per_label))});
        if (times.size() > times_per_label) {
            text.insert(text.size() - 2, ", ...");
        }
        labels.draw(body, view.sx(events[i].point[0]) + 6.0, view.sy(events[i].point[1]) + 14.0,
                    text);
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
    Labels labels;
    draw_key_frames(body, view, trajectory, tracks, keys, labels);
    draw_paths(body, view, trajectory, tracks);
    draw_events(body, view, trajectory.events, false, "");
    draw_event_times(body, view, trajectory.events, labels);
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
