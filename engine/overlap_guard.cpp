#include "overlap_guard.h"

#include "contact_candidates.h"
#include "island_lcp.h"
#include "manifold.h"
#include "restitution.h"

namespace impulse {

namespace {

// The separation of every candidate pair at the bodies' current poses; true
// when some pair is deeper than d.
bool measure_gaps(World& world, TimeSteppingScratch& s) {
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
        s.poses[i] = transform_of(world.bodies[i].state);
    }
    s.pair_gap.resize(s.pairs.size());
    bool deep = false;
    for (std::size_t p = 0; p < s.pairs.size(); ++p) {
        const std::size_t a = static_cast<std::size_t>(s.pairs[p].a);
        const std::size_t b = static_cast<std::size_t>(s.pairs[p].b);
        ++world.work.narrow_phase_queries;
        s.pair_gap[p] =
            separation(world.bodies[a].shape, s.poses[a], world.bodies[b].shape, s.poses[b]);
        deep = deep || s.pair_gap[p] < -world.solver.contact_tolerance;
    }
    return deep;
}

void gather_touching_points(World& world, TimeSteppingScratch& s) {
    const double d = world.solver.contact_tolerance;
    s.guard_points.clear();
    s.guard_links.clear();
    for (std::size_t p = 0; p < s.pairs.size(); ++p) {
        if (s.pair_gap[p] > d) {
            continue;
        }
        const CandidatePair& pair = s.pairs[p];
        const std::size_t a = static_cast<std::size_t>(pair.a);
        const std::size_t b = static_cast<std::size_t>(pair.b);
        ++world.work.narrow_phase_queries;
        const Manifold m = collide(world.bodies[a].shape, s.poses[a], world.bodies[b].shape,
                                   s.poses[b], d, world.solver.vertex_normal);
        for (int k = 0; k < m.point_count; ++k) {
            s.guard_points.push_back(candidate_point(world, static_cast<int>(p), pair.a, pair.b,
                                                     m.points[static_cast<std::size_t>(k)]));
            s.guard_links.push_back({pair.a, pair.b});
        }
    }
}

// Moves island i's bodies by h M^-1 J^T m, where m solves its position problem.
void separate_island(World& world, double h, TimeSteppingScratch& s, int i) {
    const double d = world.solver.contact_tolerance;
    IslandProblem& p = s.problem;
    p.points.clear();
    p.q.clear();
    bool deep = false;
    for (int l = s.guard_islands.link_offsets[static_cast<std::size_t>(i)];
         l < s.guard_islands.link_offsets[static_cast<std::size_t>(i) + 1]; ++l) {
        const ContactPoint& point = s.guard_points[static_cast<std::size_t>(
            s.guard_islands.links_of[static_cast<std::size_t>(l)])];
        p.points.push_back(point);
        p.q.push_back(point.contact.separation / h);
        deep = deep || point.contact.separation < -d;
    }
    if (!deep) {
        return;
    }
    p.lambda.assign(p.points.size(), 0.0);
    if (!solve_island(world, p, d / h).solved) {
        return; // the overlap stays, and max-overlap judges it
    }
    const int b0 = s.guard_islands.body_offsets[static_cast<std::size_t>(i)];
    const int b1 = s.guard_islands.body_offsets[static_cast<std::size_t>(i) + 1];
    s.saved.clear();
    for (int k = b0; k < b1; ++k) {
        BodyState& state = world
                               .bodies[static_cast<std::size_t>(
                                   s.guard_islands.bodies[static_cast<std::size_t>(k)])]
                               .state;
        s.saved.push_back(state);
        state.velocity = {};
        state.angular_velocity = 0.0;
    }
    for (std::size_t j = 0; j < p.points.size(); ++j) {
        if (p.lambda[j] > 0.0) {
            const ContactPoint& point = p.points[j];
            apply_impulse(world.bodies[static_cast<std::size_t>(point.a)],
                          world.bodies[static_cast<std::size_t>(point.b)], point.contact.point,
                          point.contact.normal, p.lambda[j]);
        }
    }
    for (int k = b0; k < b1; ++k) {
        Body& body = world.bodies[static_cast<std::size_t>(
            s.guard_islands.bodies[static_cast<std::size_t>(k)])];
        const BodyState& before = s.saved[static_cast<std::size_t>(k - b0)];
        BodyState& state = body.state;
        state.position = before.position + h * state.velocity;
        state.angle = before.angle + h * state.angular_velocity;
        state.velocity = before.velocity;
        state.angular_velocity = before.angular_velocity;
    }
}

} // namespace

void guard_overlaps(World& world, double h, TimeSteppingScratch& s) {
    for (int pass = 0; pass < max_overlap_guard_passes; ++pass) {
        if (!measure_gaps(world, s)) {
            return;
        }
        ++world.work.overlap_guard_passes;
        gather_touching_points(world, s);
        group_islands(world.bodies, s.guard_links, s.guard_islands, s.island_scratch);
        for (int i = 0; i < s.guard_islands.count(); ++i) {
            separate_island(world, h, s, i);
        }
    }
}

} // namespace impulse
