#include "contact_candidates.h"

#include "manifold.h"
#include "restitution.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace impulse {

double rotation_radius(const Shape& shape) {
    return shape.type == ShapeType::circle ? 0.0 : circumradius(shape);
}

double turning_reach(const Shape& shape, double angle_change) {
    return rotation_radius(shape) * std::min(std::abs(angle_change), 2.0);
}

namespace {

// The rounding of rotated vertices (as local stepping's boxes allow for).
double rounding_margin(const Transform& pose, const Shape& shape, double rotation_reach) {
    const double reach = std::max(std::abs(pose.p.x), std::abs(pose.p.y)) + shape.radius;
    return 1e-12 * (reach + rotation_reach) + 1e-300;
}

// How far any point of a dynamic body can move within h: its speed, what
// gravity adds (at most |g| h^2 for every integrator), and its turning.
double body_reach(const World& world, const Body& body, double h) {
    if (body.is_static()) {
        return 0.0;
    }
    const BodyState& s = body.state;
    return length(s.velocity) * h + length(world.gravity) * h * h +
           turning_reach(body.shape, s.angular_velocity * h);
}

bool pair_less(const CandidatePair& x, const CandidatePair& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
}

void find_pairs(World& world, TimeSteppingScratch& s) {
    const int n = static_cast<int>(world.bodies.size());
    s.grid.build(s.boxes);
    s.pairs.clear();
    const double d = world.solver.contact_tolerance;
    for (int i = 0; i < n; ++i) {
        if (world.bodies[static_cast<std::size_t>(i)].is_static()) {
            continue;
        }
        const Aabb box = s.boxes[static_cast<std::size_t>(i)];
        s.grid.query(box, [&](int k) {
            const Body& other = world.bodies[static_cast<std::size_t>(k)];
            // Two dynamic bodies once, from the lower index.
            if (k == i || (!other.is_static() && k < i) ||
                !overlaps(box, s.boxes[static_cast<std::size_t>(k)])) {
                return;
            }
            const Pair p = pair_of(world, i, k);
            s.pairs.push_back({p.a, p.b,
                               s.reach[static_cast<std::size_t>(p.a)] +
                                   s.reach[static_cast<std::size_t>(p.b)] + d});
        });
    }
    // Discovery order depends on the grid's cells: the sort makes it (a, b).
    std::sort(s.pairs.begin(), s.pairs.end(), pair_less);
}

} // namespace

double gravity_normal_acceleration(const World& world, const ContactPoint& point) {
    const Vec2 ga =
        world.bodies[static_cast<std::size_t>(point.a)].is_static() ? Vec2{} : world.gravity;
    const Vec2 gb =
        world.bodies[static_cast<std::size_t>(point.b)].is_static() ? Vec2{} : world.gravity;
    return dot(ga - gb, point.contact.normal);
}

ContactPoint candidate_point(const World& world, int pair, int a, int b, const Contact& contact) {
    const Body& ba = world.bodies[static_cast<std::size_t>(a)];
    const Body& bb = world.bodies[static_cast<std::size_t>(b)];
    return {pair,
            a,
            b,
            contact,
            dot(perp(contact.point - ba.state.position), contact.normal),
            dot(perp(contact.point - bb.state.position), contact.normal),
            relative_normal_velocity(ba, bb, contact.point, contact.normal)};
}

namespace {

// Body i's pose and its box grown by `grow` (its reach), the contact
// tolerance and the rounding of its corners; its reach and state recorded as
// what the pairs cover.
void box_body(const World& world, std::size_t i, double grow, TimeSteppingScratch& s) {
    const Body& body = world.bodies[i];
    s.reach[i] = grow;
    s.paired_at[i] = body.state;
    s.poses[i] = transform_of(body.state);
    const double margin = grow + world.solver.contact_tolerance +
                          rounding_margin(s.poses[i], body.shape, rotation_radius(body.shape));
    s.boxes[i] = aabb_of(body.shape, s.poses[i], margin);
}

// True when body i's turning cannot carry it to `other` within the step,
// though its reach (which counts the turning of its farthest point toward
// every direction at once) says it might: the body lies within the disc of
// radius R about its centre at every instant, and that centre moves at most
// s.centre_reach[i] (its reach less the turning part); a disc that far from
// the other body, grown by the other's reach, cannot touch it. A rod spinning
// in place at 100 rad/s took an impact from a wall it could never reach, its
// linear rows predicting its tip would close up to 0.83 m within the step.
bool beyond_turning_disc(const World& world, const TimeSteppingScratch& s, int i, int other) {
    const std::size_t bi = static_cast<std::size_t>(i);
    if (s.centre_reach[bi] == std::numeric_limits<double>::infinity()) {
        return false; // not tested: see drop_pairs_beyond_turning
    }
    const Shape& shape = world.bodies[bi].shape;
    const double r = rotation_radius(shape);
    const std::size_t bo = static_cast<std::size_t>(other);
    const Transform centre = s.poses[bi];
    const double grow = rounding_margin(centre, shape, r);
    const double gap =
        separation(make_circle(r + grow), centre, world.bodies[bo].shape, s.poses[bo]);
    return gap > s.centre_reach[bi] + s.reach[bo] + world.solver.contact_tolerance;
}

// Drops the pairs that beyond_turning_disc shows cannot touch within the step.
// Only bodies turning more than half a radian are tested (the disc is then
// much tighter than the reach; elsewhere it costs a query for little); each
// records how far its centre may move, which outran_reach (time_stepping.cpp)
// holds it to: an impact within the step can turn spin into speed.
void drop_pairs_beyond_turning(World& world, double h, TimeSteppingScratch& s) {
    const std::size_t n = world.bodies.size();
    s.centre_reach.assign(n, std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < n; ++i) {
        const Body& body = world.bodies[i];
        const double turn = turning_reach(body.shape, body.state.angular_velocity * h);
        if (!body.is_static() && turn > 0.5 * rotation_radius(body.shape)) {
            s.centre_reach[i] = s.reach[i] - turn;
        }
    }
    const auto beyond = [&](const CandidatePair& p) {
        return beyond_turning_disc(world, s, p.a, p.b) || beyond_turning_disc(world, s, p.b, p.a);
    };
    s.pairs.erase(std::remove_if(s.pairs.begin(), s.pairs.end(), beyond), s.pairs.end());
}

} // namespace

void find_pairs_around(World& world, double grow, TimeSteppingScratch& s) {
    const std::size_t n = world.bodies.size();
    s.poses.resize(n);
    s.boxes.resize(n);
    s.reach.resize(n);
    s.paired_at.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        box_body(world, i, world.bodies[i].is_static() ? 0.0 : grow, s);
    }
    find_pairs(world, s);
}

void find_contact_candidates(World& world, double h, TimeSteppingScratch& s) {
    const std::size_t n = world.bodies.size();
    s.poses.resize(n);
    s.reach.resize(n);
    s.paired_at.resize(n);
    s.boxes.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        box_body(world, i, std::max(body_reach(world, world.bodies[i], h), s.reach_floor[i]), s);
    }
    find_pairs(world, s);
    drop_pairs_beyond_turning(world, h, s);

    s.points.clear();
    s.feature.clear();
    s.links.clear();
    for (std::size_t p = 0; p < s.pairs.size(); ++p) {
        const CandidatePair& pair = s.pairs[p];
        const Body& a = world.bodies[static_cast<std::size_t>(pair.a)];
        const Body& b = world.bodies[static_cast<std::size_t>(pair.b)];
        ++world.work.narrow_phase_queries;
        const Manifold m = collide(a.shape, s.poses[static_cast<std::size_t>(pair.a)], b.shape,
                                   s.poses[static_cast<std::size_t>(pair.b)], pair.reach,
                                   world.solver.vertex_normal);
        for (int k = 0; k < m.point_count; ++k) {
            s.points.push_back(candidate_point(world, static_cast<int>(p), pair.a, pair.b,
                                               m.points[static_cast<std::size_t>(k)]));
            s.feature.push_back(k);
            s.links.push_back({pair.a, pair.b});
        }
    }
}

Aabb swept_box(const World& world, std::size_t b, const BodyState& start, double turn) {
    const Body& body = world.bodies[b];
    const double rr = rotation_radius(body.shape);
    const double grow = turn + world.solver.contact_tolerance;
    const Transform from_pose = transform_of(start);
    const Transform to_pose = transform_of(body.state);
    const Aabb from =
        aabb_of(body.shape, from_pose, grow + rounding_margin(from_pose, body.shape, rr));
    const Aabb to = aabb_of(body.shape, to_pose, grow + rounding_margin(to_pose, body.shape, rr));
    return {{std::min(from.lower.x, to.lower.x), std::min(from.lower.y, to.lower.y)},
            {std::max(from.upper.x, to.upper.x), std::max(from.upper.y, to.upper.y)}};
}

namespace {

bool is_candidate_pair(const TimeSteppingScratch& s, const Pair& p) {
    const CandidatePair key{p.a, p.b, 0.0};
    const auto it = std::lower_bound(s.pairs.begin(), s.pairs.end(), key, pair_less);
    return it != s.pairs.end() && it->a == p.a && it->b == p.b;
}

bool deeper_than_tolerance(const World& world, const Pair& p) {
    const Body& a = world.bodies[static_cast<std::size_t>(p.a)];
    const Body& b = world.bodies[static_cast<std::size_t>(p.b)];
    const double d = world.solver.contact_tolerance;
    const Manifold m = collide(a.shape, transform_of(a.state), b.shape, transform_of(b.state), d,
                               world.solver.vertex_normal);
    for (int k = 0; k < m.point_count; ++k) {
        if (m.points[static_cast<std::size_t>(k)].separation < -d) {
            return true;
        }
    }
    return false;
}

} // namespace

void file_outran(TimeSteppingScratch& s) {
    s.outran_boxes.clear();
    for (const int k : s.outran) {
        s.outran_boxes.push_back(s.swept[static_cast<std::size_t>(k)]);
    }
    s.outran_grid.build(s.outran_boxes);
}

bool meets_unheld(World& world, int b, const std::vector<int>& outran,
                  const std::vector<Aabb>& swept, const std::vector<char>& is_outran,
                  TimeSteppingScratch& s) {
    const Aabb& box = swept[static_cast<std::size_t>(b)];
    bool meets = false;
    const auto test = [&](int k) {
        const std::size_t kk = static_cast<std::size_t>(k);
        if (meets || k == b || !overlaps(box, is_outran[kk] != 0 ? swept[kk] : s.boxes[kk])) {
            return;
        }
        ++world.work.narrow_phase_queries;
        const Pair p = pair_of(world, b, k);
        meets = !is_candidate_pair(s, p) || deeper_than_tolerance(world, p);
    };
    // The grid holds every body's box at the step's start; a body that also
    // outran its reach is met wherever its swept box lies (a pass over the
    // list for each body made this quadratic: 467 bodies outran one step of
    // pile-discs-1000, and the test took 7% of its first 3 s).
    s.grid.query(box, test);
    s.outran_grid.query(box, [&](int j) { test(outran[static_cast<std::size_t>(j)]); });
    return meets;
}

} // namespace impulse
