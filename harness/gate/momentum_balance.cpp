// The momentum-balance expectation: a closed room's total momentum changes
// only by the impulses of its static walls.
#include "expectation_checks.h"

#include <algorithm>
#include <limits>
#include <map>

namespace impulse::harness {

namespace {

// An impulse a static body gave a dynamic one.
struct Kick {
    double t = 0.0;
    Vec2 impulse; // on the dynamic body
    double size = 0.0;
};

// The impulses from static bodies, in time order. In an event the impulse on
// a is j n (the normal points toward a) and on b is -j n; the dynamic body is
// a in the impulse engine's events, but either is read right. Events between
// two dynamic bodies give equal and opposite impulses and leave the total
// alone. Empty (after a failure) when an event names a body the scene lacks.
std::optional<std::vector<Kick>>
kicks_from_static_bodies(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    std::map<std::string, bool> is_static;
    for (const SceneBody& body : scene.bodies) {
        is_static.emplace(body.name, body.is_static);
    }
    std::vector<Kick> kicks;
    for (std::size_t k = 0; k < trajectory.events.size(); ++k) {
        const TrajectoryEvent& e = trajectory.events[k];
        const auto a = is_static.find(e.a);
        const auto b = is_static.find(e.b);
        if (a == is_static.end() || b == is_static.end()) {
            checks.failure("", "event " + std::to_string(k) + " names " +
                                   single_quoted(a == is_static.end() ? e.a : e.b) +
                                   ", which is not a body of the scene");
            return std::nullopt;
        }
        if (a->second == b->second) {
            continue;
        }
        const Vec2 on_a{e.impulse * e.normal[0], e.impulse * e.normal[1]};
        kicks.push_back({e.t, a->second ? -on_a : on_a, std::abs(e.impulse)});
    }
    // Events come in time order from a world-stepping run; a run whose bodies
    // keep their own clocks may record them otherwise. Stable: ties keep the
    // recorded order, so the sum is the same however the run is repeated.
    std::stable_sort(kicks.begin(), kicks.end(),
                     [](const Kick& x, const Kick& y) { return x.t < y.t; });
    return kicks;
}

// How far a value is off relative to what it is allowed: the scale of the
// momentum balance grows with every impulse, so the frame nearest to failing
// is not always the one furthest off. NaN (a blown-up run) is the worst.
double share_of_allowance(double off, double allowed) {
    if (std::isnan(off)) {
        return std::numeric_limits<double>::infinity();
    }
    if (allowed > 0.0) {
        return off / allowed;
    }
    return off > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

} // namespace

// A gas in a closed room: total momentum changes only by the walls' impulses.
// In every frame, P(t) - P(0) = sum of j n over the events with a static body
// up to t (event.t <= t), judged against the sum of |m v| at t = 0 plus the
// sum of those |j|; the frame and component nearest to failing (by share of
// its allowance) is reported. The loader has refused gravity (it would add
// m g t).
void check_momentum_balance(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const std::optional<std::vector<Mass>> masses = masses_of(scene, trajectory, checks);
    if (!masses) {
        return;
    }
    const std::optional<std::vector<Kick>> kicks =
        kicks_from_static_bodies(scene, trajectory, checks);
    if (!kicks) {
        return;
    }
    const Expectation& x = checks.expectation();
    const Totals initial = totals_in(trajectory.frames.front(), *masses, scene.gravity);
    Vec2 given;              // sum of j n up to the frame
    double given_size = 0.0; // sum of |j| up to the frame
    std::size_t next = 0;
    struct Worst {
        std::size_t frame = 0;
        std::size_t component = 0;
        double expected = 0.0;
        double actual = 0.0;
        double scale = 0.0;
        double share = -1.0;
    } worst;
    for (std::size_t k = 0; k < trajectory.frames.size(); ++k) {
        const double t = frame_time(trajectory.frames[k]);
        for (; next < kicks->size() && (*kicks)[next].t <= t; ++next) {
            given += (*kicks)[next].impulse;
            given_size += (*kicks)[next].size;
        }
        const Vec2 now = totals_in(trajectory.frames[k], *masses, scene.gravity).momentum;
        const double scale = initial.momentum_scale + given_size;
        const double expected[2] = {initial.momentum.x + given.x, initial.momentum.y + given.y};
        const double actual[2] = {now.x, now.y};
        for (std::size_t c = 0; c < 2; ++c) {
            const double share =
                share_of_allowance(std::abs(actual[c] - expected[c]), x.atol + x.rtol * scale);
            if (share > worst.share) {
                worst = {k, c, expected[c], actual[c], scale, share};
            }
        }
    }
    const double t = frame_time(trajectory.frames[worst.frame]);
    checks.value(std::string("momentum balance") + (worst.component == 0 ? " (x)" : " (y)") +
                     ", nearest to its tolerance at t = " + sentence_number(t) + " s",
                 {worst.expected, worst.scale}, worst.actual);
}

} // namespace impulse::harness
