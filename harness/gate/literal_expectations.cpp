// The expectations whose values the scene writes itself: an event's fields
// and a body's state at a time.
#include "expectation_checks.h"

#include <algorithm>

namespace impulse::harness {

void check_event(const Trajectory& trajectory, Checks& checks) {
    const Expectation& x = checks.expectation();
    const std::size_t count = trajectory.events.size();
    if (x.index >= count) {
        checks.failure("",
                       "the run has " + std::to_string(count) + " collision event" +
                           (count == 1 ? "" : "s") + ", so there is no event " +
                           std::to_string(x.index),
                       static_cast<double>(x.index + 1), static_cast<double>(count));
        return;
    }
    const TrajectoryEvent& e = trajectory.events[x.index];
    if (!x.body.empty()) {
        checks.name("a", x.body, e.a);
    }
    if (!x.other.empty()) {
        checks.name("b", x.other, e.b);
    }
    for (const auto& [field, value] : x.values) {
        checks.value(field, plain(value), field_of(e, field));
    }
}

namespace {

// Frames are k dt apart; the spacing of the first two is the run's dt even
// when a command-line override changed the scene's.
double frame_spacing(const Scene& scene, const Trajectory& trajectory) {
    if (trajectory.frames.size() >= 2) {
        return frame_time(trajectory.frames[1]) - frame_time(trajectory.frames[0]);
    }
    return scene.dt;
}

} // namespace

void check_state(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const Expectation& x = checks.expectation();
    const double dt = frame_spacing(scene, trajectory);
    const auto frame = std::find_if(
        trajectory.frames.begin(), trajectory.frames.end(),
        [&](const std::vector<double>& f) { return std::abs(frame_time(f) - x.t) <= 1e-9 * dt; });
    const std::optional<BodyColumns> columns = body_columns(trajectory, x.body);
    if (!columns) {
        checks.failure("", "the trajectory has no columns for " + single_quoted(x.body));
        return;
    }
    if (frame == trajectory.frames.end()) {
        const double end = trajectory.frames.empty() ? 0.0 : frame_time(trajectory.frames.back());
        checks.failure("", "the run has no frame at t = " + sentence_number(x.t) +
                               " s (its frames are " + sentence_number(dt) +
                               " s apart and end at " + sentence_number(end) + " s)");
        return;
    }
    const Motion m = motion_in(*frame, *columns);
    for (const auto& [field, value] : x.values) {
        checks.value(field, plain(value), field_of(m, field));
    }
}

} // namespace impulse::harness
