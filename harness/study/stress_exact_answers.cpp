// docs/physics.md's exact answers as stress rows (stress_exact_answers.h).
#include "stress_exact_answers.h"

#include "exact_answers.h"
#include "stress_rows.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>

namespace impulse::harness {

namespace {

// How far the engine's answers may stray from the ladder's.
struct LadderBounds {
    double time = 0.0;
    double speed = 0.0;
};

// Each impact is resolved at the search's lo, up to toi_tolerance (T) before
// the touch: from up to v T above the ground and g T slower. To first order
// that moves the next impact by T (1/e - 1 - 2e) and leaves the next landing
// speed g T (1/e - e) off, which later flights carry on (2 e / g of a speed
// error in time, e of it per bounce in speed). Summed over n impacts, e <= 1:
//   time  <= T (1 + (n - 1)(1/e + 1 + 4e) + e n (n - 1)(1/e + e))
//   speed <= g T ((n - 1)(1 + e^2) + e)
// Away from the origin a position off by the budget dy at an impact of speed
// v acts as an impact dy / v early or late, so T becomes T + dy / v at the
// slowest impact. Plus 8 epsilons of the values for their own rounding.
LadderBounds ladder_bounds(const DropLadder& ladder, int n, double toi_tolerance,
                           double position_budget) {
    const double e = ladder.e;
    const double g = ladder.g;
    const double slowest = ladder.v1() * ladder.e_to(n - 1);
    const double shift = toi_tolerance + position_budget / slowest;
    const double later =
        n > 1 ? (n - 1) * (1.0 / e + 1.0 + 4.0 * e) + e * n * (n - 1) * (1.0 / e + e) : 0.0;
    return {shift * (1.0 + later) + 8.0 * epsilon * ladder.impact_time(n),
            g * shift * ((n - 1) * (1.0 + e * e) + e) + 8.0 * epsilon * ladder.v1()};
}

// The largest error and the impact (1 to n) where it happened.
struct WorstImpact {
    double error = 0.0;
    int at = 1;

    void observe(double value, int k) {
        if (value > error) {
            error = value;
            at = k;
        }
    }
};

} // namespace

std::vector<StressRow> drop_rows(const Scene& scene, const DropCheck& check,
                                 const std::vector<TrajectoryEvent>& events,
                                 double position_budget) {
    const SceneBody& body = scene.bodies[static_cast<std::size_t>(check.body)];
    const int n = check.impacts;
    std::vector<const TrajectoryEvent*> impacts;
    for (const TrajectoryEvent& e : events) {
        if (involves(e, body.name)) {
            impacts.push_back(&e);
        }
    }
    const std::optional<DropLadder> ladder = drop_ladder(scene, body);
    const std::string title = "drop ladder of " + single_quoted(body.name);
    if (!ladder || static_cast<int>(impacts.size()) != n) {
        const std::string why =
            !ladder ? "no static ground below"
                    : std::to_string(impacts.size()) + " impacts, expected " + std::to_string(n);
        return {judged(title + ": impact times (s)", infinity, 0.0, Bound::at_most, why),
                judged(title + ": rebound speeds (m/s)", infinity, 0.0, Bound::at_most, why)};
    }
    const LadderBounds bounds =
        ladder_bounds(*ladder, n, scene.solver.toi_tolerance, position_budget);
    WorstImpact time, speed;
    for (int k = 1; k <= n; ++k) {
        const TrajectoryEvent& event = *impacts[static_cast<std::size_t>(k - 1)];
        time.observe(std::abs(event.t - ladder->impact_time(k)), k);
        speed.observe(std::abs(event.vn_after - ladder->rebound_speed(k)), k);
    }
    const std::string of_n = " of " + std::to_string(n);
    return {judged(title + ": impact times (s)", time.error, bounds.time, Bound::at_most,
                   "largest at impact " + std::to_string(time.at) + of_n),
            judged(title + ": rebound speeds (m/s)", speed.error, bounds.speed, Bound::at_most,
                   "largest at impact " + std::to_string(speed.at) + of_n)};
}

std::vector<StressRow> head_on_rows(const Scene& scene, const HeadOnCheck& check,
                                    const std::vector<TrajectoryEvent>& events,
                                    const std::vector<BodyState>& last) {
    const SceneBody& a = scene.bodies[static_cast<std::size_t>(check.a)];
    const SceneBody& b = scene.bodies[static_cast<std::size_t>(check.b)];
    const HeadOn exact = head_on(scene, a, b);
    const std::string title = "head-on velocities (relative)";
    if (events.empty() || last.empty()) {
        return {judged(title, infinity, 0.0, Bound::at_most, "they never collided")};
    }
    // The engine's j and v + j n / m round a few times each: a few epsilons
    // of the terms, far inside the slack.
    const double va = dot(last[static_cast<std::size_t>(check.a)].velocity, exact.u);
    const double vb = dot(last[static_cast<std::size_t>(check.b)].velocity, exact.u);
    const double error =
        std::max(relative(std::abs(va - exact.va_after.value), exact.va_after.scale),
                 relative(std::abs(vb - exact.vb_after.value), exact.vb_after.scale));
    return {judged(title, error, stress_relative_slack, Bound::at_most,
                   "final velocities along the line of centres, docs/physics.md")};
}

} // namespace impulse::harness
