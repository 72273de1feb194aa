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

// Moves the bodies of pair p apart by h M^-1 J^T m, where m solves the pair's
// own position problem, w = A m + g / h >= 0 over its points within d, at the
// poses as they are now (earlier pairs of this pass may have moved them).
void separate_pair(World& world, double h, TimeSteppingScratch& s, std::size_t p) {
    const double d = world.solver.contact_tolerance;
    const CandidatePair& pair = s.pairs[p];
    const std::size_t a = static_cast<std::size_t>(pair.a);
    const std::size_t b = static_cast<std::size_t>(pair.b);
    Body& body_a = world.bodies[a];
    Body& body_b = world.bodies[b];
    ++world.work.narrow_phase_queries;
    const Manifold m = collide(body_a.shape, transform_of(body_a.state), body_b.shape,
                               transform_of(body_b.state), d, world.solver.vertex_normal);
    IslandProblem& problem = s.problem;
    problem.points.clear();
    problem.q.clear();
    bool deep = false;
    for (int k = 0; k < m.point_count; ++k) {
        const Contact& c = m.points[static_cast<std::size_t>(k)];
        problem.points.push_back(candidate_point(world, static_cast<int>(p), pair.a, pair.b, c));
        problem.q.push_back(c.separation / h);
        deep = deep || c.separation < -d;
    }
    if (!deep) {
        return;
    }
    problem.lambda.assign(problem.points.size(), 0.0);
    if (!solve_island(world, problem, d / h).solved) {
        return; // the overlap stays, and max-overlap judges it
    }
    // The correction as a velocity change, applied to positions only.
    const BodyState before_a = body_a.state;
    const BodyState before_b = body_b.state;
    for (Body* body : {&body_a, &body_b}) {
        body->state.velocity = {};
        body->state.angular_velocity = 0.0;
    }
    for (std::size_t j = 0; j < problem.points.size(); ++j) {
        if (problem.lambda[j] > 0.0) {
            const ContactPoint& point = problem.points[j];
            apply_impulse(body_a, body_b, point.contact.point, point.contact.normal,
                          problem.lambda[j]);
        }
    }
    for (auto [body, before] : {std::pair<Body*, const BodyState*>{&body_a, &before_a},
                                std::pair<Body*, const BodyState*>{&body_b, &before_b}}) {
        BodyState& state = body->state;
        state.position = before->position + h * state.velocity;
        state.angle = before->angle + h * state.angular_velocity;
        state.velocity = before->velocity;
        state.angular_velocity = before->angular_velocity;
    }
}

} // namespace

void guard_overlaps(World& world, double h, TimeSteppingScratch& s) {
    for (int pass = 0; pass < max_overlap_guard_passes; ++pass) {
        if (!measure_gaps(world, s)) {
            return;
        }
        ++world.work.overlap_guard_passes;
        for (std::size_t p = 0; p < s.pairs.size(); ++p) {
            if (s.pair_gap[p] < -world.solver.contact_tolerance) {
                separate_pair(world, h, s, p);
            }
        }
    }
}

} // namespace impulse
