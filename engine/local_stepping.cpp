#include "local_stepping.h"

#include "contact_single.h"
#include "integrator.h"
#include "narrow_phase_query.h"
#include "time_of_impact.h"

#include <algorithm>

namespace impulse {

namespace {

// Worlds this small test every pair: the grid would cost more than it saves
// ("two bodies need no broad phase").
constexpr std::size_t brute_force_bodies = 16;

// The box margin: rotated vertices carry a rounding error of a few ULPs of
// their coordinates, so boxes grow by that much and a little more.
double box_margin(const Transform& pose, const Shape& shape) {
    const double reach = std::max(std::abs(pose.p.x), std::abs(pose.p.y)) +
                         (shape.type == ShapeType::circle ? shape.radius : 0.0);
    double polygon_reach = 0.0;
    for (int i = 0; i < shape.polygon.count; ++i) {
        polygon_reach = std::max(polygon_reach, length(shape.polygon.vertices[i]));
    }
    return 1e-12 * (reach + polygon_reach) + 1e-300;
}

class LocalStep {
  public:
    LocalStep(World& world, double t0, double dt, std::vector<CollisionEvent>& events)
        : world_(world), s_(world.local), t0_(t0), dt_(dt), events_(events) {}

    std::optional<StepError> run() {
        ++world_.work.steps;
        const std::size_t n = world_.bodies.size();
        s_.clocks.resize(n);
        s_.boxes.resize(n);
        s_.queue.clear();
        for (std::size_t i = 0; i < n; ++i) {
            restart(static_cast<int>(i), world_.bodies[i].state, 0.0, /*first=*/true);
        }
        brute_force_ = n <= brute_force_bodies;
        if (!brute_force_) {
            s_.grid.build(s_.boxes);
        }
        for (std::size_t i = 0; i < n; ++i) {
            if (!world_.bodies[i].is_static()) {
                test_neighbours(static_cast<int>(i), [&](int k) {
                    // Each pair of moving bodies once, from its lower index.
                    return world_.bodies[static_cast<std::size_t>(k)].is_static() ||
                           k > static_cast<int>(i);
                });
            }
        }
        while (!s_.queue.empty()) {
            std::pop_heap(s_.queue.begin(), s_.queue.end(), later);
            const PendingCollision c = s_.queue.back();
            s_.queue.pop_back();
            if (c.version_a != clock(c.a).version || c.version_b != clock(c.b).version) {
                continue; // one of its bodies has collided since: its motion is gone
            }
            if (std::optional<StepError> error = resolve(c)) {
                return error;
            }
        }
        for (std::size_t i = 0; i < n; ++i) {
            world_.bodies[i].state = s_.clocks[i].end;
        }
        return std::nullopt;
    }

  private:
    BodyClock& clock(int i) { return s_.clocks[static_cast<std::size_t>(i)]; }
    const Body& body(int i) const { return world_.bodies[static_cast<std::size_t>(i)]; }

    // The body's motion starts afresh at `since` from `state`.
    void restart(int i, const BodyState& state, double since, bool first) {
        BodyClock& c = clock(i);
        const Body& b = body(i);
        c.start = state;
        c.since = since;
        if (b.is_static()) {
            c.end = state;
        } else {
            ++world_.work.body_advances;
            c.end =
                advance(world_.solver.integrator, state, world_.gravity, b.rotates(), dt_ - since);
        }
        c.end_pose = transform_of(c.end);
        c.end_box = aabb_of(b.shape, c.end_pose, box_margin(c.end_pose, b.shape));
        s_.boxes[static_cast<std::size_t>(i)] = c.end_box;
        if (first) {
            c.version = 0;
            c.collisions = 0;
        } else {
            ++c.version;
            if (!brute_force_) {
                s_.grid.insert(i, c.end_box);
            }
        }
    }

    // Tests body i against every body whose box overlaps its own and that
    // `wanted` accepts.
    template <class Wanted> void test_neighbours(int i, Wanted&& wanted) {
        const Aabb box = clock(i).end_box;
        const auto consider = [&](int k) {
            if (k != i && wanted(k) && overlaps(box, clock(k).end_box)) {
                test_pair(pair_of(world_, i, k));
            }
        };
        if (brute_force_) {
            for (int k = 0; k < static_cast<int>(world_.bodies.size()); ++k) {
                if (!(body(i).is_static() && body(k).is_static())) {
                    consider(k);
                }
            }
        } else {
            s_.grid.query(box, [&](int k) {
                if (!(body(i).is_static() && body(k).is_static())) {
                    consider(k);
                }
            });
        }
    }

    // The seed's test for one pair: do the bodies interpenetrate where their
    // motions end? If so, search back for when, and queue the collision.
    void test_pair(const Pair& pair) {
        const BodyClock& ca = clock(pair.a);
        const BodyClock& cb = clock(pair.b);
        const double s_end = pair_separation(world_, pair, ca.end_pose, cb.end_pose);
        if (!(s_end < 0.0)) {
            return;
        }
        const double from = std::max(ca.since, cb.since);
        PairMotion motion{pair, ca.start, cb.start, from - ca.since, from - cb.since};
        PendingCollision c;
        const TimeOfImpact toi =
            pair_time_of_impact(world_, motion, dt_ - from, s_end, c.state_a, c.state_b);
        c.time = from + toi.time;
        c.a = pair.a;
        c.b = pair.b;
        c.version_a = ca.version;
        c.version_b = cb.version;
        c.converged = toi.converged;
        // The bracket's low end never moved: was it free of interpenetration at all?
        c.late = toi.time == 0.0 && pair_separation(world_, pair, c.state_a, c.state_b) < 0.0;
        s_.queue.push_back(c);
        std::push_heap(s_.queue.begin(), s_.queue.end(), later);
    }

    std::optional<StepError> resolve(const PendingCollision& c) {
        if (!c.converged) {
            return StepError{StepFailure::toi_not_converged, t0_ + c.time, c.a, c.b};
        }
        Body& a = world_.bodies[static_cast<std::size_t>(c.a)];
        Body& b = world_.bodies[static_cast<std::size_t>(c.b)];
        a.state = c.state_a;
        b.state = c.state_b;
        const Pair pair{c.a, c.b};
        if (!resolve_single_contact(world_, pair, t0_ + c.time, events_)) {
            if (c.late) {
                // A graze the end-of-step test missed, already separating: the
                // seed would not have seen it at all. Let it separate.
                ++world_.work.missed_grazes;
                return std::nullopt;
            }
            return StepError{StepFailure::resting_contact, t0_ + c.time, c.a, c.b};
        }
        ++world_.work.collisions;
        for (const int i : {c.a, c.b}) {
            if (!body(i).is_static() &&
                ++clock(i).collisions > world_.solver.max_collisions_per_step) {
                return StepError{StepFailure::too_many_collisions, t0_ + c.time, c.a, c.b};
            }
        }
        // Only these two bodies move differently now: restart their clocks and
        // test them again against their neighbours (each other included, once).
        restart_after_collision(c.a, a.state, c.time);
        restart_after_collision(c.b, b.state, c.time);
        if (!a.is_static()) {
            test_neighbours(c.a, [](int) { return true; });
        }
        if (!b.is_static()) {
            test_neighbours(c.b, [&](int k) { return k != c.a; });
        }
        return std::nullopt;
    }

    void restart_after_collision(int i, const BodyState& state, double time) {
        if (!body(i).is_static()) {
            restart(i, state, time, /*first=*/false);
        }
    }

    World& world_;
    LocalScratch& s_;
    double t0_;
    double dt_;
    std::vector<CollisionEvent>& events_;
    bool brute_force_ = true;
};

} // namespace

std::optional<StepError> step_local(World& world, double t0, double dt,
                                    std::vector<CollisionEvent>& events) {
    return LocalStep(world, t0, dt, events).run();
}

} // namespace impulse
