#include "time_stepping.h"

#include "contact_candidates.h"
#include "contact_resting.h"
#include "energy_guard.h"
#include "integrator.h"
#include "island_lcp.h"
#include "overlap_guard.h"
#include "restitution.h"
#include "shape.h"
#include "swept_time_step.h"
#include "time_stepping_scratch.h"

#include <algorithm>
#include <cmath>

namespace impulse {

TimeSteppingScratch& TimeSteppingScratchSlot::get() {
    if (!scratch_) {
        scratch_ = {new TimeSteppingScratch, [](TimeSteppingScratch* p) { delete p; }};
    }
    return *scratch_;
}

namespace {

// The impulses of an earlier solve (last step's holding impulses, or a
// retried attempt's) for this step's points: both lists are in (a, b, k)
// order, so one merge walk finds them; a point not in `old` starts at 0.
void look_up(const std::vector<WarmImpulse>& old, const TimeSteppingScratch& s,
             std::vector<double>& warm) {
    warm.assign(s.points.size(), 0.0);
    std::size_t w = 0;
    for (std::size_t i = 0; i < s.points.size() && w < old.size(); ++i) {
        const ContactPoint& p = s.points[i];
        const WarmImpulse key{p.a, p.b, s.feature[i], 0.0};
        while (w < old.size() && warm_key_before(old[w], key)) {
            ++w;
        }
        if (w < old.size() && !warm_key_before(key, old[w])) {
            warm[i] = old[w].impulse;
        }
    }
}

// The points' positive impulses, keyed by (a, b, k), in the points' order.
void keep(const TimeSteppingScratch& s, const std::vector<double>& impulse,
          std::vector<WarmImpulse>& kept) {
    kept.clear();
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        if (impulse[i] > 0.0) {
            const ContactPoint& p = s.points[i];
            kept.push_back({p.a, p.b, s.feature[i], impulse[i]});
        }
    }
}

void apply_impulses(World& world, const IslandProblem& problem) {
    for (std::size_t i = 0; i < problem.points.size(); ++i) {
        if (problem.lambda[i] > 0.0) {
            const ContactPoint& p = problem.points[i];
            apply_impulse(world.bodies[static_cast<std::size_t>(p.a)],
                          world.bodies[static_cast<std::size_t>(p.b)], p.contact.point,
                          p.contact.normal, problem.lambda[i]);
        }
    }
}

bool any_positive(const std::vector<double>& values) {
    for (const double v : values) {
        if (v > 0.0) {
            return true;
        }
    }
    return false;
}

// The residual the holding solve of an island above tight_residual_points
// stops at, as a fraction of contact_tolerance d: r = d / 32h, so an accepted
// answer closes a held point by at most d / 32 per step beyond the exact one.
// With r = d / h a settled pile cycled: each step's holding solve, warm
// started and accepted at once, let a held point (pinned at its gap) close by
// up to d; the overlap guard lifted it back to just within d; the lift raised
// the island's energy; the energy guard returned the island to its pose at the
// step's start, where the next step began the same way (pile-discs-1000 at
// rest: one guard pass, 651 products and 32 returns per step; d / 8h: 260
// products, d / 32h: 79). Pushing a held point deeper than d / 4 back ended
// the guard passes with d / 8h, but its separating velocity kept three of the
// drawn sweep piles moving past their 60 s (docs/engine.md, "A settled pile
// and the guards"). Coarser residuals (d / 4h to 1000 d / h) were measured
// and not kept: 1000 d / h halved pile-boxes-100's products over seven seeds,
// but every one of them made the settled pile-discs-1000 6 to 25 times as
// costly, its guard pass lifting deeper points (docs/engine.md, "A coarser
// holding residual, measured and not adopted").
constexpr double contact_residual_fraction = 1.0 / 32.0;
// Islands of at most this many points keep the residual d / h: on the stack
// of ten boxes (20 points; test_dense_contact.cpp) a residual of d / 4h or
// d / 8h made the energy guard act (d / 8h: in 201 of 600 steps) and the
// boxes sink by up to 2.3e-9 m, where d / h and d / 2h leave the impulses
// exact to 1e-12; the cause is not found yet.
constexpr std::size_t tight_residual_points = 20;
// An island above diagonal_scaling_points stops at relative_residual times
// its fastest approach speed at the step's start, |u_i|, when that is coarser
// than d / 32h: the step is first order (its own error is |g| h per step), so
// digits of the holding answer far below the motion are not physics, and
// relative_residual |u| h is a thousandth of the distance the fastest point
// closes in the step; the overlap guard takes out whatever ends deeper than
// d, and the energy guard any gain. At rest u = 0 keeps d / 32h. Going to
// d / 32h first, for up to 300 products, was measured and dropped: in a
// creeping box pile every holding solve spent exactly those 300 and then
// stopped at the relaxed residual anyway. Counted in products the budget
// looked right for a falling disc pile (without it the guard took 421
// products per step instead of 292), but a guard product is one over a small
// group, a holding product one over the whole island: in CPU time no pile
// measured cost more without it, and 100 boxes cost 45% less
// (docs/engine.md, "The holding residual of large islands"). Islands of at most
// diagonal_scaling_points keep d / 32h to the cap: relaxed there too, one of
// the 37-body piles of dense.sweep (e = 0.3) was still moving at its 60 s
// rest budget (a frictionless pile's rest is chaotic in its solution). A
// fixed coarser residual (d / h to 1000 d / h) made the settled disc pile
// cost 6 to 25 times as much per step (docs/engine.md).
constexpr double relative_residual = 1e-3;
// The product cap of a holding solve taken again because its answer would
// carry a pair through itself: the overlap guard's (overlap_guard.h).
constexpr int crossing_cap_factor = guard_cap_factor;

// An island's failure, naming the pair `a`, `b` and the island's heaviest and
// lightest dynamic bodies (StepError).
StepError island_failure(const World& world, const IslandProblem& problem, StepFailure failure,
                         double t0, int a, int b) {
    StepError error{failure, t0, a, b};
    double least = 0.0; // the inverse masses of the heaviest and the lightest
    double most = 0.0;
    for (const ContactPoint& point : problem.points) {
        for (const int i : {point.a, point.b}) {
            const double inv_mass = world.bodies[static_cast<std::size_t>(i)].inv_mass;
            if (inv_mass == 0.0) {
                continue; // static
            }
            if (error.heaviest < 0 || inv_mass < least) {
                error.heaviest = i;
                least = inv_mass;
            }
            if (error.lightest < 0 || inv_mass > most) {
                error.lightest = i;
                most = inv_mass;
            }
        }
    }
    return error;
}

StepError unsolved(const World& world, const IslandProblem& problem, double t0) {
    const ContactPoint& named = problem.points.front();
    return island_failure(world, problem, StepFailure::contact_problem_unsolved, t0, named.a,
                          named.b);
}

// The first point of a holding problem whose applied answer carries it past
// its gap by more than its two bodies' inradii, or none. A point closes
// beyond its gap by at most h times the solve's residual: d / 32 to d for a
// tight solve, but an answer stopped by the product cap, or relaxed to a
// thousandth of a fast approach (|g| h of 16,700 m/s at g = 1e6 and dt =
// 1/60), can close a pair by more than it is thick. Past the inradii the
// pair's separating direction at the end poses need no longer be the side it
// came from, and a pair that crossed entirely shows no overlap at all: the
// overlap guard, which judges the end poses, cannot be trusted with it
// (docs/engine.md, "Dense contact", holding).
const ContactPoint* crossing(const World& world, const IslandProblem& problem, double h) {
    for (const ContactPoint& point : problem.points) {
        const Body& a = world.bodies[static_cast<std::size_t>(point.a)];
        const Body& b = world.bodies[static_cast<std::size_t>(point.b)];
        const double u = relative_normal_velocity(a, b, point.contact.point, point.contact.normal);
        const double end_gap = std::max(point.contact.separation, 0.0) + h * u;
        if (end_gap < -(inradius(a.shape) + inradius(b.shape))) {
            return &point;
        }
    }
    return nullptr;
}

class TimeStep {
  public:
    TimeStep(World& world, double t0, double h, std::vector<CollisionEvent>& events)
        : world_(world), s_(world.ts.get()), t0_(t0), h_(h), events_(events),
          d_(world.solver.contact_tolerance),
          v_rest_(std::max(rest_speed(world), world.solver.contact_tolerance / h)) {}

    std::optional<StepError> run();

  private:
    // Retries of a step whose impacts carried a body beyond its reach.
    static constexpr int max_reach_retries = 2;

    void start();
    std::optional<StepError> solve_islands();
    bool outran_reach();
    std::optional<StepError> island(int i);
    bool impacts(int first, int last, bool& pushed);
    bool hold(int first, int last, bool& pushed);
    void restore();
    bool is_impact(int r) const;
    void keep_velocities(const IslandProblem& problem);
    void restore_velocities();

    World& world_;
    TimeSteppingScratch& s_;
    double t0_;
    double h_;
    std::vector<CollisionEvent>& events_;
    double d_;
    // The rest speed, never below d / h: an approach slower than that closes
    // less than the contact tolerance within the step, so it is touching, not
    // an impact, whatever gravity gives. Found by an outside review: with no
    // gravity sqrt(2 |g| d) is 0, and two discs moving on together after an
    // impact at e = 0 had their approach of rounding size, 1e-16 m/s,
    // recorded as a collision in every step.
    double v_rest_;
    bool retrying_ = false; // solving again after an attempt outran a reach
    // hold()'s point whose answer, even solved again tightly, carries it
    // through its partner (crossing()); the step then stops.
    const ContactPoint* crossed_ = nullptr;
};

void TimeStep::keep_velocities(const IslandProblem& problem) {
    s_.before_loose.clear();
    for (const ContactPoint& point : problem.points) {
        for (const int b : {point.a, point.b}) {
            s_.before_loose.emplace_back(b, world_.bodies[static_cast<std::size_t>(b)].state);
        }
    }
}

// Only the velocities: the positions are set from them after the solve.
void TimeStep::restore_velocities() {
    for (const auto& [b, state] : s_.before_loose) {
        BodyState& now = world_.bodies[static_cast<std::size_t>(b)].state;
        now.velocity = state.velocity;
        now.angular_velocity = state.angular_velocity;
    }
}

// x_k and v_k of every body, and free flight by the scene's integrator.
void TimeStep::start() {
    const std::size_t n = world_.bodies.size();
    s_.start.resize(n);
    s_.free_end.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Body& body = world_.bodies[i];
        s_.start[i] = body.state;
        if (body.is_static()) {
            s_.free_end[i] = body.state;
        } else {
            ++world_.work.body_advances;
            s_.free_end[i] =
                advance(world_.solver.integrator, body.state, world_.gravity, body.rotates(), h_);
        }
    }
}

void TimeStep::restore() {
    for (std::size_t i = 0; i < world_.bodies.size(); ++i) {
        world_.bodies[i].state = s_.start[i];
    }
}

std::optional<StepError> TimeStep::run() {
    ++world_.work.steps;
    ++world_.work.time_stepping_steps;
    const std::size_t events_at_start = events_.size();
    start();
    s_.reach_floor.assign(world_.bodies.size(), 0.0);
    bool pairs_stale = false;
    for (int attempt = 0;; ++attempt) {
        if (std::optional<StepError> error = solve_islands()) {
            restore();
            events_.resize(events_at_start);
            return error;
        }
        if (!outran_reach()) {
            break;
        }
        if (attempt == max_reach_retries) {
            // The retries ran out with a body that may still have met one
            // it held no point with: the guard finds its pairs again around
            // the end poses, so no overlap escapes it (pile-discs-10000 at
            // 2.4 s: two discs 5.1e-4 m deep, a pair the guard never saw).
            pairs_stale = true;
            break;
        }
        ++world_.work.reach_retries;
        // The abandoned attempt's impulses are the retry's warm start: most
        // of its points are the retry's too, so the retry's solves start
        // close to their answers (pile-boxes-100: 1.66 million products with
        // cold retries, 0.70 million warm; docs/engine.md).
        keep(s_, s_.held, s_.retry_held);
        keep(s_, s_.impact, s_.retry_impact);
        retrying_ = true;
        restore();
        events_.resize(events_at_start);
    }
    if (world_.solver.ccd) {
        if (std::optional<StepError> error = swept_crossing(world_, s_, t0_, h_)) {
            restore();
            events_.resize(events_at_start);
            return error;
        }
    }
    guard_overlaps(world_, h_, s_, pairs_stale);
    guard_energy(world_, s_);
    keep(s_, s_.held, world_.warm_impulses);
    return std::nullopt;
}

// A body an impact sent further than its reach may have met a body it had no
// candidate point with, or a point of a candidate pair farther apart at the
// start than the pair's reach: if so (meets_unheld), the step is taken again
// with its reach doubled past that distance, so every point that can touch
// within the step is held. A body that outran its reach without meeting
// anything unheld leaves the step as it is: in pile-boxes-100 a quarter of the
// outrunning steps were of that kind.
bool TimeStep::outran_reach() {
    s_.outran.clear();
    s_.is_outran.assign(world_.bodies.size(), 0);
    s_.swept.resize(world_.bodies.size());
    for (const int i : s_.islands.bodies) {
        const std::size_t b = static_cast<std::size_t>(i);
        const BodyState& now = world_.bodies[b].state;
        const double turn = turning_reach(world_.bodies[b].shape, now.angle - s_.start[b].angle);
        const double moved = length(now.position - s_.start[b].position);
        if (moved + turn > s_.reach[b] || moved > s_.centre_reach[b]) {
            s_.outran.push_back(i);
            s_.is_outran[b] = 1;
            s_.swept[b] = swept_box(world_, b, s_.start[b], turn);
        }
    }
    if (s_.outran.empty()) {
        return false; // the common step: no grid to build
    }
    file_outran(s_);
    bool retry = false;
    for (const int i : s_.outran) {
        if (meets_unheld(world_, i, s_.outran, s_.swept, s_.is_outran, s_)) {
            const std::size_t b = static_cast<std::size_t>(i);
            const BodyState& now = world_.bodies[b].state;
            s_.reach_floor[b] =
                2.0 * (length(now.position - s_.start[b].position) +
                       turning_reach(world_.bodies[b].shape, now.angle - s_.start[b].angle));
            retry = true;
        }
    }
    return retry;
}

std::optional<StepError> TimeStep::solve_islands() {
    find_contact_candidates(world_, h_, s_);
    look_up(retrying_ ? s_.retry_held : world_.warm_impulses, s_, s_.warm);
    if (retrying_) {
        look_up(s_.retry_impact, s_, s_.impact_warm);
    } else {
        s_.impact_warm.assign(s_.points.size(), 0.0); // impacts start cold
    }
    s_.held.assign(s_.points.size(), 0.0);
    s_.impact.assign(s_.points.size(), 0.0);
    find_islands(world_.bodies, s_.links, s_.islands, s_.island_scratch);

    const std::size_t n = world_.bodies.size();
    s_.in_island.assign(n, 0);
    for (const int b : s_.islands.bodies) {
        s_.in_island[static_cast<std::size_t>(b)] = 1;
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (s_.in_island[i] == 0) {
            world_.bodies[i].state = s_.free_end[i]; // exact free flight
        }
    }
    s_.island_pushed.assign(static_cast<std::size_t>(s_.islands.count()), 0);
    for (int i = 0; i < s_.islands.count(); ++i) {
        if (std::optional<StepError> error = island(i)) {
            return error;
        }
    }
    return std::nullopt;
}

std::optional<StepError> TimeStep::island(int i) {
    const int first = s_.islands.link_offsets[static_cast<std::size_t>(i)];
    const int last = s_.islands.link_offsets[static_cast<std::size_t>(i) + 1];
    ++world_.work.islands;
    world_.work.island_points += last - first;
    const int b0 = s_.islands.body_offsets[static_cast<std::size_t>(i)];
    const int b1 = s_.islands.body_offsets[static_cast<std::size_t>(i) + 1];
    bool pushed = false;
    if (!impacts(first, last, pushed)) {
        return unsolved(world_, s_.problem, t0_);
    }
    for (int k = b0; k < b1; ++k) { // gravity's kick, v' + h M^-1 f
        BodyState& state =
            world_.bodies[static_cast<std::size_t>(s_.islands.bodies[static_cast<std::size_t>(k)])]
                .state;
        state.velocity += h_ * world_.gravity;
    }
    if (!hold(first, last, pushed)) {
        return unsolved(world_, s_.problem, t0_);
    }
    if (crossed_ != nullptr) {
        return island_failure(world_, s_.problem, StepFailure::contact_pass_through, t0_,
                              crossed_->a, crossed_->b);
    }
    s_.island_pushed[static_cast<std::size_t>(i)] = pushed ? 1 : 0;
    for (int k = b0; k < b1; ++k) {
        const std::size_t b =
            static_cast<std::size_t>(s_.islands.bodies[static_cast<std::size_t>(k)]);
        BodyState& state = world_.bodies[b].state;
        if (!pushed) {
            state = s_.free_end[b]; // no contact acted: the integrator's own flight
            continue;
        }
        // Semi-implicit: the new velocity carries the body over the step.
        state.position = s_.start[b].position + h_ * state.velocity;
        if (world_.bodies[b].rotates()) {
            state.angle = s_.start[b].angle + h_ * state.angular_velocity;
        }
    }
    return std::nullopt;
}

// A point that starts phase 1: it approaches faster than v_rest and will
// touch within the step.
bool TimeStep::is_impact(int r) const {
    const ContactPoint& point = s_.points[static_cast<std::size_t>(r)];
    return point.vn < -v_rest_ &&
           point.contact.separation +
                   h_ * (point.vn + h_ * gravity_normal_acceleration(world_, point)) <=
               d_;
}

// Phase 1, Newton's law at the step's start: only when some point is an
// impact (is_impact). Rows: the impacts, and every touching point that does
// not separate. A row approaching faster than v_rest bounces (e); slower, it
// is held (e = 0): below v_rest a bounce would rise less than d
// (docs/engine.md, "Resting contact"). Only a bouncing row that took an
// impulse is a collision event; a held row that passed the impact on is a
// contact held, like every holding impulse of phase 2.
bool TimeStep::impacts(int first, int last, bool& pushed) {
    IslandProblem& p = s_.problem;
    p.rows.clear();
    bool any_impact = false;
    for (int l = first; l < last; ++l) {
        const int r = s_.islands.links_of[static_cast<std::size_t>(l)];
        const ContactPoint& point = s_.points[static_cast<std::size_t>(r)];
        const bool impact = is_impact(r);
        any_impact = any_impact || impact;
        if (impact || (point.contact.separation <= d_ && point.vn <= 0.0)) {
            p.rows.push_back(r);
        }
    }
    if (!any_impact) {
        return true;
    }
    p.points.clear();
    p.q.clear();
    for (const int r : p.rows) {
        const ContactPoint& point = s_.points[static_cast<std::size_t>(r)];
        p.points.push_back(point);
        const double e = point.vn < -v_rest_ ? world_.restitution : 0.0;
        p.q.push_back((1.0 + e) * point.vn);
    }
    p.lambda.clear();
    for (const int r : p.rows) {
        p.lambda.push_back(s_.impact_warm[static_cast<std::size_t>(r)]);
    }
    if (!solve_island(world_, p, d_ / h_).solved || !impulses_finite(p)) {
        return false;
    }
    apply_impulses(world_, p);
    for (std::size_t i = 0; i < p.points.size(); ++i) {
        s_.impact[static_cast<std::size_t>(p.rows[i])] = p.lambda[i];
        if (p.lambda[i] > 0.0) {
            pushed = true;
        }
        const ContactPoint& point = p.points[i];
        if (p.lambda[i] > 0.0 && point.vn < -v_rest_) {
            const double vn_after =
                relative_normal_velocity(world_.bodies[static_cast<std::size_t>(point.a)],
                                         world_.bodies[static_cast<std::size_t>(point.b)],
                                         point.contact.point, point.contact.normal);
            events_.push_back({t0_, point.a, point.b, point.contact.point, point.contact.normal,
                               p.lambda[i], point.vn, vn_after});
        }
    }
    return true;
}

// Phase 2, holding: after gravity's kick no point may close more than its gap
// within the step, w = A lambda + u~ + max(g, 0) / h >= 0 (the velocities
// already carry the kick), solved to a residual of contact_residual_fraction
// d / h for an island above tight_residual_points (above
// diagonal_scaling_points, relative to its motion), d / h below.
bool TimeStep::hold(int first, int last, bool& pushed) {
    IslandProblem& p = s_.problem;
    p.rows.clear();
    p.points.clear();
    p.q.clear();
    p.lambda.clear();
    const std::size_t points = static_cast<std::size_t>(last - first);
    const bool relaxes = points > diagonal_scaling_points;
    const double tight =
        (points > tight_residual_points ? contact_residual_fraction : 1.0) * d_ / h_;
    double tolerance = tight;
    for (int l = first; l < last; ++l) {
        const int r = s_.islands.links_of[static_cast<std::size_t>(l)];
        p.rows.push_back(r);
        const ContactPoint& point = s_.points[static_cast<std::size_t>(r)];
        p.points.push_back(point);
        const double u = relative_normal_velocity(world_.bodies[static_cast<std::size_t>(point.a)],
                                                  world_.bodies[static_cast<std::size_t>(point.b)],
                                                  point.contact.point, point.contact.normal);
        const double gap = point.contact.separation;
        p.q.push_back(u + (gap > 0.0 ? gap : 0.0) / h_);
        p.lambda.push_back(s_.warm[static_cast<std::size_t>(r)]);
        if (relaxes) {
            tolerance = std::max(tolerance, relative_residual * std::fabs(point.vn));
        }
    }
    const IslandSolve solved = solve_island(world_, p, tolerance);
    if (!solved.solved || !impulses_finite(p)) {
        return false;
    }
    // Only a loose answer (closing a point by more than d) can cross a pair:
    // a tight one is applied with no copy kept (the step's hot path).
    const bool loose = h_ * solved.residual > d_;
    if (loose) {
        keep_velocities(p);
    }
    apply_impulses(world_, p);
    crossed_ = nullptr;
    if (loose && crossing(world_, p, h_) != nullptr) {
        // A loose answer that would carry a pair through itself: solved again
        // from it, to the tight residual with the overlap guard's larger cap
        // (pile-on-pegs, 80 boxes at dt 1/30: one island at 1.93 s stopped by
        // the cap closing two boxes by more than their inradii; solved on, it
        // held them). Only if that too fails does the step stop.
        restore_velocities();
        ++world_.work.holding_solved_again;
        const IslandSolve again = solve_island(world_, p, tight, crossing_cap_factor);
        if (!again.solved || !impulses_finite(p)) {
            return false;
        }
        apply_impulses(world_, p);
        crossed_ = crossing(world_, p, h_);
    }
    for (std::size_t i = 0; i < p.rows.size(); ++i) {
        s_.held[static_cast<std::size_t>(p.rows[i])] = p.lambda[i];
    }
    pushed = pushed || any_positive(p.lambda);
    return true;
}

} // namespace

std::optional<StepError> step_time_stepping(World& world, double t0, double dt,
                                            std::vector<CollisionEvent>& events) {
    return TimeStep(world, t0, dt, events).run();
}

} // namespace impulse
