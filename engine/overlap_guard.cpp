#include "overlap_guard.h"

#include "contact_candidates.h"
#include "island_lcp.h"
#include "manifold.h"
#include "mprgp.h"
#include "restitution.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace impulse {

namespace {

// The separation of every candidate pair at the bodies' current poses; returns
// the deepest overlap (0 when none).
double measure_gaps(World& world, TimeSteppingScratch& s) {
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
        s.poses[i] = transform_of(world.bodies[i].state);
    }
    s.pair_gap.resize(s.pairs.size());
    double deepest = 0.0;
    for (std::size_t p = 0; p < s.pairs.size(); ++p) {
        const std::size_t a = static_cast<std::size_t>(s.pairs[p].a);
        const std::size_t b = static_cast<std::size_t>(s.pairs[p].b);
        ++world.work.narrow_phase_queries;
        s.pair_gap[p] =
            separation(world.bodies[a].shape, s.poses[a], world.bodies[b].shape, s.poses[b]);
        deepest = std::max(deepest, -s.pair_gap[p]);
    }
    return deepest;
}

// The groups the guard solves together: bodies joined through pairs closer
// than `margin`, so a body squeezed between the floor and a heavy neighbour is
// moved with both of them in one solve, not back and forth between them one
// pair at a time. The margin (d plus twice the deepest overlap) is as far as
// the guard's moves can carry a body: a pair that far apart is held in the
// same solve, so moving one overlap apart cannot make another.
void find_groups(const std::vector<Body>& bodies, TimeSteppingScratch& s, double margin) {
    s.guard_pairs.clear();
    s.guard_links.clear();
    for (std::size_t p = 0; p < s.pairs.size(); ++p) {
        if (s.pair_gap[p] <= margin) {
            s.guard_pairs.push_back(static_cast<int>(p));
            s.guard_links.push_back({s.pairs[p].a, s.pairs[p].b});
        }
    }
    find_islands(bodies, s.guard_links, s.guard_groups, s.island_scratch);
}

bool has_deep_pair(const World& world, const TimeSteppingScratch& s, int first, int last) {
    for (int l = first; l < last; ++l) {
        const int p = s.guard_pairs[static_cast<std::size_t>(
            s.guard_groups.links_of[static_cast<std::size_t>(l)])];
        if (s.pair_gap[static_cast<std::size_t>(p)] < -world.solver.contact_tolerance) {
            return true;
        }
    }
    return false;
}

// Under translation alone the points of one manifold along one normal (the
// two corners of a face contact) close alike: their rows of A are equal, so
// only their sum of impulses is decided and MPRGP's active set wandered
// between them. Each such run of points becomes one row holding the smaller
// gap, which keeps the same moves. Only problems above
// diagonal_scaling_points are merged, where the guard's cost is: measured
// pairwise on the same problems (pile-boxes-100 and two other seeds, 8 s),
// the guard's products fell by 37% there (790,000 -> 490,000), while the
// problems of at most 128 points took about 30 products each either way
// (pile-polygons, 208 solves: 6,110 against 5,677), and merging them would
// only move that canonical pile's chaotic settling (docs/engine.md).
void merge_face_rows(IslandProblem& problem) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < problem.points.size(); ++i) {
        if (kept > 0) {
            const ContactPoint& last = problem.points[kept - 1];
            const ContactPoint& point = problem.points[i];
            if (point.pair == last.pair && point.contact.normal.x == last.contact.normal.x &&
                point.contact.normal.y == last.contact.normal.y) {
                problem.q[kept - 1] = std::min(problem.q[kept - 1], problem.q[i]);
                continue;
            }
        }
        problem.points[kept] = problem.points[i];
        problem.q[kept] = problem.q[i];
        ++kept;
    }
    problem.points.resize(kept);
    problem.q.resize(kept);
}

// The overlap guard's first pass over a large problem starts from the last
// step's first-pass answer of the same points: in a pile that rocks or creeps
// the holding step leaves much the same overlaps step after step, and a cold
// start spends most of its products finding the active set again. Measured
// paired (every first-pass problem solved both ways, the run going on with
// the cold answer): over 8 s of pile-boxes-100 at seeds 1, 2 and 3 the
// first pass took 150,000 / 85,000 / 260,000 products cold and 90,000 /
// 58,000 / 119,000 warm (-40%, -32%, -54%); over the first 3 s of
// pile-boxes-1000, where the pile is still falling into itself, 461,000
// against 447,000 (-3%). Only problems above diagonal_scaling_points, where
// the guard's cost is, are warm started: a canonical pile's guard problems
// are smaller, so its answers, and its chaotic settling, are untouched.
//
// The key of each of problem's points, (a, b, k) with k its index among its
// pair's rows (a pair's rows are consecutive), into `keys`.
void point_keys(const IslandProblem& problem, std::vector<WarmImpulse>& keys) {
    keys.clear();
    for (std::size_t i = 0; i < problem.points.size(); ++i) {
        const ContactPoint& point = problem.points[i];
        const bool same_pair = i > 0 && problem.points[i - 1].pair == point.pair;
        keys.push_back({point.a, point.b, same_pair ? keys.back().k + 1 : 0, 0.0});
    }
}

void start_from_last_step(const World& world, TimeSteppingScratch& s, IslandProblem& problem) {
    const std::vector<WarmImpulse>& last = world.guard_warm_impulses;
    point_keys(problem, s.guard_keys);
    for (std::size_t i = 0; i < s.guard_keys.size(); ++i) {
        const auto it =
            std::lower_bound(last.begin(), last.end(), s.guard_keys[i], warm_key_before);
        if (it != last.end() && !warm_key_before(s.guard_keys[i], *it)) {
            problem.lambda[i] = it->impulse;
        }
    }
}

void keep_for_next_step(TimeSteppingScratch& s, const IslandProblem& problem) {
    point_keys(problem, s.guard_keys);
    for (std::size_t i = 0; i < s.guard_keys.size(); ++i) {
        if (problem.lambda[i] > 0.0) {
            s.guard_keys[i].impulse = problem.lambda[i];
            s.guard_warm_next.push_back(s.guard_keys[i]);
        }
    }
}

// The island solver on a guard problem, with the guard's larger product
// cap (guard_cap_factor), its products counted apart.
IslandSolve solve_guard_problem(World& world, IslandProblem& problem, double tolerance) {
    const long long products = world.work.solver_sweeps;
    const IslandSolve solve = solve_island(world, problem, tolerance, guard_cap_factor);
    world.work.overlap_guard_products += world.work.solver_sweeps - products;
    return solve;
}

// Group g's position problem: every point within `margin` of its pairs, at
// the poses as they are now, w = A m + g / h >= 0, m >= 0, m . w = 0.
// Translation only (`turn` false, see guard_overlaps) unless that has no
// solution: then with the bodies' turning as well.
IslandSolve solve_group(World& world, double h, TimeSteppingScratch& s, int g, double margin,
                        bool turn, bool first_pass) {
    const double d = world.solver.contact_tolerance;
    const std::size_t gi = static_cast<std::size_t>(g);
    IslandProblem& problem = s.problem;
    problem.points.clear();
    problem.q.clear();
    for (int l = s.guard_groups.link_offsets[gi]; l < s.guard_groups.link_offsets[gi + 1]; ++l) {
        const int p = s.guard_pairs[static_cast<std::size_t>(
            s.guard_groups.links_of[static_cast<std::size_t>(l)])];
        const CandidatePair& pair = s.pairs[static_cast<std::size_t>(p)];
        const std::size_t a = static_cast<std::size_t>(pair.a);
        const std::size_t b = static_cast<std::size_t>(pair.b);
        ++world.work.narrow_phase_queries;
        const Manifold m = collide(world.bodies[a].shape, s.poses[a], world.bodies[b].shape,
                                   s.poses[b], margin, world.solver.vertex_normal);
        for (int k = 0; k < m.point_count; ++k) {
            const Contact& c = m.points[static_cast<std::size_t>(k)];
            ContactPoint point = candidate_point(world, p, pair.a, pair.b, c);
            if (!turn) {
                point.rn_a = 0.0;
                point.rn_b = 0.0;
            }
            problem.points.push_back(point);
            problem.q.push_back(c.separation / h);
        }
    }
    // Merged rows and warm starts only where the guard's cost is (both above).
    const bool large = !turn && problem.points.size() > diagonal_scaling_points;
    if (large) {
        merge_face_rows(problem);
    }
    problem.lambda.assign(problem.points.size(), 0.0);
    if (large && first_pass) {
        start_from_last_step(world, s, problem);
    }
    IslandSolve solve;
    if (!problem.points.empty()) {
        solve = solve_guard_problem(world, problem, d / h);
    }
    solve.solved = !problem.points.empty() && solve.solved && impulses_finite(problem);
    if (large && first_pass && solve.solved) {
        keep_for_next_step(s, problem);
    }
    return solve;
}

// Group g's bodies move by h M^-1 J^T m (positions, and angles when `turn`;
// velocities kept): the correction as a velocity change from rest. The energy
// guard then checks these bodies' islands (a lift adds energy).
void move_group(World& world, double h, TimeSteppingScratch& s, int g, bool turn) {
    const std::size_t gi = static_cast<std::size_t>(g);
    const IslandProblem& problem = s.problem;
    const int b0 = s.guard_groups.body_offsets[gi];
    const int b1 = s.guard_groups.body_offsets[gi + 1];
    for (int k = b0; k < b1; ++k) {
        const std::size_t b =
            static_cast<std::size_t>(s.guard_groups.bodies[static_cast<std::size_t>(k)]);
        s.guard_saved[b] = world.bodies[b].state;
        world.bodies[b].state.velocity = {};
        world.bodies[b].state.angular_velocity = 0.0;
    }
    for (std::size_t j = 0; j < problem.points.size(); ++j) {
        if (problem.lambda[j] > 0.0) {
            const ContactPoint& point = problem.points[j];
            Body& a = world.bodies[static_cast<std::size_t>(point.a)];
            Body& b = world.bodies[static_cast<std::size_t>(point.b)];
            if (turn) {
                apply_impulse(a, b, point.contact.point, point.contact.normal, problem.lambda[j]);
                continue;
            }
            const Vec2 push = problem.lambda[j] * point.contact.normal;
            a.state.velocity += a.inv_mass * push;
            b.state.velocity -= b.inv_mass * push;
        }
    }
    for (int k = b0; k < b1; ++k) {
        const std::size_t b =
            static_cast<std::size_t>(s.guard_groups.bodies[static_cast<std::size_t>(k)]);
        const BodyState& before = s.guard_saved[b];
        BodyState& state = world.bodies[b].state;
        state.position = before.position + h * state.velocity;
        state.angle = turn ? before.angle + h * state.angular_velocity : before.angle;
        state.velocity = before.velocity;
        state.angular_velocity = before.angular_velocity;
        s.guard_moved[b] = 1;
        join_bodies(s.guard_joined, s.guard_groups.bodies[static_cast<std::size_t>(b0)],
                    static_cast<int>(b));
    }
}

// true when the turning solution moves no point of a body further than
// `margin`, the group's reach: the turn is linear in the angle, so a large one
// swings corners into bodies outside the group (measured: a 0.29 m overlap in
// a random pile of 80 boxes without this bound).
bool small_turn(const World& world, double h, const TimeSteppingScratch& s, double margin) {
    const IslandProblem& problem = s.problem;
    for (std::size_t j = 0; j < problem.points.size(); ++j) {
        const ContactPoint& point = problem.points[j];
        for (const int i : {point.a, point.b}) {
            const Body& body = world.bodies[static_cast<std::size_t>(i)];
            if (body.is_static()) {
                continue;
            }
            const double rn = i == point.a ? point.rn_a : point.rn_b;
            const double move = h * problem.lambda[j] *
                                (body.inv_mass + rotation_radius(body.shape) * std::abs(rn) *
                                                     (body.rotates() ? body.inv_inertia : 0.0));
            if (!(move <= margin)) {
                return false;
            }
        }
    }
    return true;
}

// A group whose translation problem the iterative solver left unconverged at
// its cap, far from done (unconverged_fraction below). s.problem holds the
// points and that answer, whose residual is `residual`. The same problem is
// solved again with every dynamic body of the group moved as if its mass were
// 1 kg, and the group moves by whichever of the two answers leaves the smaller
// residual. Why: the guard may move bodies along any metric (a move is a
// position correction, not an impulse), and the mass metric is what makes a
// jammed pile's problem ill-conditioned. Found in a random pile of 80 boxes (1
// to 940 kg) resting on a peg, dt 1/30: a 3.8 kg box turned 6.6 mm into the
// peg under a column of boxes up to 940 kg; the group (76 bodies, 277 points)
// needed about 50,000 products to converge in the mass metric and 300 to
// 8,000 with equal masses. Capped at 2,000, each pass left about half of the
// overlap before it, and eight passes ended at 2.3e-4 m. Equal masses move
// heavy bodies as far as light ones, so the lift costs more energy: the
// energy guard takes it out as for any guard move.
void separate_with_equal_masses(World& world, double h, TimeSteppingScratch& s, int g,
                                double residual) {
    IslandProblem& problem = s.problem;
    s.guard_lambda = problem.lambda; // the mass metric's answer
    const std::size_t gi = static_cast<std::size_t>(g);
    const int b0 = s.guard_groups.body_offsets[gi];
    const int b1 = s.guard_groups.body_offsets[gi + 1];
    s.guard_inv_mass.clear();
    for (int k = b0; k < b1; ++k) {
        Body& body = world.bodies[static_cast<std::size_t>(
            s.guard_groups.bodies[static_cast<std::size_t>(k)])];
        s.guard_inv_mass.push_back(body.inv_mass);
        body.inv_mass = 1.0; // every group body is dynamic: static ones never join a group
    }
    problem.lambda.assign(problem.points.size(), 0.0);
    const IslandSolve equal =
        solve_guard_problem(world, problem, world.solver.contact_tolerance / h);
    const bool better = equal.solved && impulses_finite(problem) && equal.residual < residual;
    if (better) {
        ++world.work.overlap_guard_equal_masses;
        move_group(world, h, s, g, false);
    }
    for (int k = b0; k < b1; ++k) {
        world.bodies[static_cast<std::size_t>(s.guard_groups.bodies[static_cast<std::size_t>(k)])]
            .inv_mass = s.guard_inv_mass[static_cast<std::size_t>(k - b0)];
    }
    if (!better) {
        problem.lambda = s.guard_lambda;
        move_group(world, h, s, g, false);
    }
}

// An unconverged translation answer is tried again with equal masses only
// when its residual as a distance (h times the velocity residual) is more
// than this fraction of the pass's deepest overlap: a pass is meant to leave
// about a tenth of it (max_overlap_guard_passes). Below that the mass metric's
// answer does a pass's work and the next pass finishes it (pile-boxes-100:
// about 55 such answers, 1e-7 to 5e-6 m/s at h = 1/60; solved again, the run
// took a third longer for the same result). In the pile on pegs the residuals
// were 0.002 to 0.05 m/s at h = 1/30 against overlaps of 0.1 to 7 mm.
constexpr double unconverged_fraction = 0.1;

// Translation first; a group with no translation that separates it (a box
// wedged between two pegs whose corners are closer than its thickness, found
// by a random pile) may still turn free. When neither solves, the overlap
// stays for this pass; if the passes end with it, mark_stuck sends the bodies
// back to the step's start. A translation the iterative solver did not
// converge is tried again with equal masses (separate_with_equal_masses).
void separate_group(World& world, double h, TimeSteppingScratch& s, int g, double margin,
                    double deepest, bool first_pass) {
    const IslandSolve translated = solve_group(world, h, s, g, margin, false, first_pass);
    if (translated.solved && !translated.converged &&
        h * translated.residual > unconverged_fraction * deepest) {
        separate_with_equal_masses(world, h, s, g, translated.residual);
    } else if (translated.solved) {
        move_group(world, h, s, g, false);
    } else if (solve_group(world, h, s, g, margin, true, false).solved &&
               small_turn(world, h, s, margin)) {
        ++world.work.overlap_guard_turns;
        move_group(world, h, s, g, true);
    } else {
        ++world.work.overlap_guard_unsolved;
    }
}

// Up to max_overlap_guard_passes passes over the pairs in s.pairs; true when
// they ended with no pair deeper than d (measured after the last move).
// `first` the step's first run: its first pass is warm started.
bool run_passes(World& world, double h, TimeSteppingScratch& s, bool first) {
    for (int pass = 0; pass < max_overlap_guard_passes; ++pass) {
        const double deepest = measure_gaps(world, s);
        const double d = world.solver.contact_tolerance;
        if (!(deepest > d)) {
            return true;
        }
        const double margin = d + 2.0 * deepest;
        ++world.work.overlap_guard_passes;
        find_groups(world.bodies, s, margin);
        for (int g = 0; g < s.guard_groups.count(); ++g) {
            const std::size_t gi = static_cast<std::size_t>(g);
            if (has_deep_pair(world, s, s.guard_groups.link_offsets[gi],
                              s.guard_groups.link_offsets[gi + 1])) {
                separate_group(world, h, s, g, margin, deepest, first && pass == 0);
            }
        }
    }
    return false;
}

// The passes ended with some pair deeper than d: a group neither translation
// nor a bounded turn separates (a box turned across the slot between two
// pegs narrower than itself), or one the passes did not finish. Both bodies of
// every such pair are marked in s.guard_stuck and joined in s.guard_joined:
// the energy guard sends their islands back to their poses at the step's
// start, at rest, where the previous step left them within d.
void mark_stuck(World& world, TimeSteppingScratch& s) {
    measure_gaps(world, s);
    const double d = world.solver.contact_tolerance;
    for (std::size_t p = 0; p < s.pairs.size(); ++p) {
        if (s.pair_gap[p] < -d) {
            const int a = s.pairs[p].a;
            const int b = s.pairs[p].b;
            for (const int i : {a, b}) {
                if (!world.bodies[static_cast<std::size_t>(i)].is_static()) {
                    s.guard_stuck[static_cast<std::size_t>(i)] = 1;
                    join_bodies(s.guard_joined, a, i);
                }
            }
        }
    }
}

// The farthest the guard carried a body beyond what the pairs cover: its
// reach from its pose when they were found (0 when none went beyond). Found
// again, they cover only `grow` around the poses of that moment, not the
// step's reach around its start: measured from the step's start, a body
// the guard moved back towards it after the pairs were found again (or after
// a stale step's pairs were) was not counted however far it went
// (pile-boxes-10000 at 2.6 s: an overlap of 0.36 m that no pass measured).
double moved_past_reach(const World& world, const TimeSteppingScratch& s) {
    double beyond = 0.0;
    for (std::size_t b = 0; b < world.bodies.size(); ++b) {
        if (s.guard_moved[b] == 0) {
            continue;
        }
        const BodyState& now = world.bodies[b].state;
        const BodyState& then = s.paired_at[b];
        const double moved = length(now.position - then.position) +
                             turning_reach(world.bodies[b].shape, now.angle - then.angle);
        beyond = std::max(beyond, moved - s.reach[b]);
    }
    return beyond;
}

// How many times a step's guard finds its pairs again because its moves
// outran them and runs its passes over them (guard_overlaps).
constexpr int max_pair_rebuilds = 3;

} // namespace

void guard_overlaps(World& world, double h, TimeSteppingScratch& s, bool pairs_stale) {
    s.guard_moved.assign(world.bodies.size(), 0);
    s.guard_joined.resize(world.bodies.size());
    std::iota(s.guard_joined.begin(), s.guard_joined.end(), 0);
    s.guard_saved.resize(world.bodies.size());
    s.guard_stuck.assign(world.bodies.size(), 0);
    s.pairs_refound = pairs_stale;
    if (pairs_stale) {
        ++world.work.overlap_guard_pair_rebuilds;
        find_pairs_around(world, world.solver.contact_tolerance, s);
    }
    s.guard_warm_next.clear();
    bool within = run_passes(world, h, s, true);
    // A deep overlap's correction can carry a body past what its pairs cover,
    // into a body it had no candidate pair with (a box pushed 7 cm into a wall
    // in pile-boxes-1000): the pairs are found again around the poses as they
    // are now, grown by how far the guard went beyond, and the passes run once
    // more over them. The pairs are grown by twice that, so that passes which
    // go on moving the same way outrun them rarely. Those passes can outrun the new pairs in turn:
    // after max_pair_rebuilds runs the pairs are found once more and only measured, so a body the
    // guard pushed into one it held no point with is stuck like any other, never unseen.
    for (int rebuild = 0; rebuild <= max_pair_rebuilds; ++rebuild) {
        const double beyond = moved_past_reach(world, s);
        if (!(beyond > 0.0)) {
            break;
        }
        ++world.work.overlap_guard_pair_rebuilds;
        s.pairs_refound = true;
        find_pairs_around(world, 2.0 * beyond + world.solver.contact_tolerance, s);
        within = rebuild < max_pair_rebuilds
                     ? run_passes(world, h, s, false)
                     : !(measure_gaps(world, s) > world.solver.contact_tolerance);
    }
    if (!within) {
        mark_stuck(world, s);
    }
    // A step with no first-pass solve leaves nothing to start from: a warm
    // start is only as good as the step before.
    std::sort(s.guard_warm_next.begin(), s.guard_warm_next.end(), warm_key_before);
    world.guard_warm_impulses.swap(s.guard_warm_next);
}

} // namespace impulse
