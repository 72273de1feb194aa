// Memory the time-stepping step reuses from one step to the next, so that a
// step allocates nothing once the world has been stepped a few times: every
// vector is cleared, never shrunk.
#pragma once

#include "broad_phase.h"
#include "contact_problem.h"
#include "islands.h"
#include "mprgp.h"
#include "pgs.h"

#include <cmath>
#include <utility>
#include <vector>

namespace impulse {

// A pair of bodies whose boxes, grown by what the step's motion can cover,
// overlap: its contact points within that reach are the step's candidates.
struct CandidatePair {
    int a = 0;
    int b = 0;
    double reach = 0.0; // how far the pair can close within the step (metres)
};

// The scratch of one island's contact problem.
struct IslandProblem {
    std::vector<int> rows;            // indices into TimeSteppingScratch::points
    std::vector<ContactPoint> points; // the rows' points, in rows' order
    std::vector<double> q;
    std::vector<double> lambda;
    std::vector<double> A; // row-major Delassus matrix of a direct solve
    // An iterative solve's sweep order (by height against gravity) and the
    // problem in that order.
    std::vector<int> order;
    std::vector<double> height;
    std::vector<ContactPoint> sorted_points;
    std::vector<double> sorted_q;
    std::vector<double> sorted_lambda;
    std::vector<double> scaled_lambda; // a retry with diagonal scaling (island_lcp.cpp)
    PgsScratch pgs;
    MprgpScratch mprgp;
};

// false when some impulse of a solved problem is not finite. A problem with
// no solution (the overlap guard's, translation only, for a body wedged
// between two static bodies closer than its thickness: w_1 + w_2 = (g_1 +
// g_2) / h < 0 for every impulse) sends the iterative solver's impulses to
// infinity, and infinity times a static body's zero inverse mass is NaN: such
// an answer is no solution and is never applied.
inline bool impulses_finite(const IslandProblem& problem) {
    for (const double l : problem.lambda) {
        if (!std::isfinite(l)) {
            return false;
        }
    }
    return true;
}

// The root of body b in a union-find over bodies (path halving), and the
// union of two bodies' sets, rooted at the smaller index so the result does not
// depend on the order of the unions.
inline int joined_root(std::vector<int>& parent, int b) {
    while (parent[static_cast<std::size_t>(b)] != b) {
        const std::size_t i = static_cast<std::size_t>(b);
        parent[i] = parent[static_cast<std::size_t>(parent[i])];
        b = parent[i];
    }
    return b;
}

inline void join_bodies(std::vector<int>& parent, int a, int b) {
    const int ra = joined_root(parent, a);
    const int rb = joined_root(parent, b);
    if (ra != rb) {
        parent[static_cast<std::size_t>(ra < rb ? rb : ra)] = ra < rb ? ra : rb;
    }
}

struct TimeSteppingScratch {
    std::vector<BodyState> start;    // x_k, v_k of every body
    std::vector<BodyState> free_end; // free flight by the scene's integrator
    // hold(): each body of a loose holding answer's points and its state
    // before that answer was applied, for a second solve (time_stepping.cpp).
    std::vector<std::pair<int, BodyState>> before_loose;
    std::vector<Transform> poses; // per body, at the configuration being looked at
    std::vector<double> reach;    // per body: how far any of its points moves in the step
    // Per body: how far its centre may move for the pairs its turning disc
    // dropped to stay out of reach (contact_candidates.cpp); infinite when
    // no such test was made. A step that moves it further is retaken.
    std::vector<double> centre_reach;
    // Per body: its state when s.pairs were found; with s.reach, what the
    // pairs cover (a body within its reach of it meets no body it has no
    // pair with).
    std::vector<BodyState> paired_at;
    std::vector<double> reach_floor; // per body: at least this (a retried step's lesson)
    std::vector<Aabb> boxes;
    // The bodies that ended an attempt further from their start than their
    // reach: the list, a flag and their swept boxes per body.
    std::vector<int> outran;
    std::vector<char> is_outran;
    std::vector<Aabb> swept;
    // The outran bodies' swept boxes, filed under their index in outran
    // (file_outran), so that meeting one another costs a grid query, not a
    // pass over the list for each of them.
    std::vector<Aabb> outran_boxes;
    UniformGrid outran_grid;
    UniformGrid grid;
    std::vector<CandidatePair> pairs; // sorted by (a, b)
    // Every candidate point of the step, in (a, b, k) order; a point's `pair`
    // is its index in `pairs`, feature its index k in the pair's manifold.
    std::vector<ContactPoint> points;
    std::vector<int> feature;
    std::vector<double> warm;        // per point: last step's holding impulse, or 0
    std::vector<double> held;        // per point: this step's holding impulse
    std::vector<double> impact;      // per point: this attempt's impact impulse
    std::vector<double> impact_warm; // per point: the impact warm start (a retry's)
    // A retried step's warm starts: the abandoned attempt's holding and impact
    // impulses in (a, b, k) order.
    std::vector<WarmImpulse> retry_held;
    std::vector<WarmImpulse> retry_impact;
    std::vector<IslandLink> links;
    Islands islands;
    IslandScratch island_scratch;
    std::vector<char> in_island;       // per body
    std::vector<double> island_energy; // per island: energy at the step's start
    std::vector<char> island_pushed;   // per island: some impulse acted
    std::vector<char> guard_moved;     // per body: the overlap guard moved it
    std::vector<int> energy_check;     // per body: the energy guard checks its unit
    // Per body, a union-find parent: the bodies one overlap-guard group moved
    // together, which the energy guard checks with each other's islands.
    std::vector<int> guard_joined;
    std::vector<int> energy_units; // the energy guard's bodies, grouped by unit
    std::vector<char> returned;    // per body: the energy guard sent it back to x_k
    // The overlap guard found its pairs again this step: some body went
    // beyond what the step's candidate pairs cover.
    bool pairs_refound = false;
    IslandProblem problem;
    std::vector<double> pair_gap; // the overlap guard's separation of each candidate pair
    // The overlap guard's groups: candidate pairs within contact_tolerance
    // (indices into pairs), their links, and the bodies they join.
    std::vector<int> guard_pairs;
    std::vector<IslandLink> guard_links;
    Islands guard_groups;
    std::vector<BodyState> guard_saved; // per body: its state before a group's move
    // A group solved again with equal masses (overlap_guard.cpp): the mass
    // metric's answer and the group's inverse masses, kept to be put back.
    std::vector<double> guard_lambda;
    std::vector<double> guard_inv_mass;
    // Per body: in a pair the overlap guard left deeper than d; the energy
    // guard sends its unit back to the step's start, at rest.
    std::vector<char> guard_stuck;
    // The overlap guard's warm starts: this step's first-pass answers
    // (unsorted until the step's end) and the keys of a problem's points.
    std::vector<WarmImpulse> guard_warm_next;
    std::vector<WarmImpulse> guard_keys;
};

} // namespace impulse
