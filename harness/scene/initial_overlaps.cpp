// A physical precondition of every scene: no two bodies interpenetrate at
// t = 0 (touching is fine).
#include "body.h"
#include "generated_bodies.h"
#include "manifold.h"
#include "scene_reading.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness::scene_reading {

namespace {

BodyState initial_state(const SceneBody& body) {
    BodyState state;
    state.position = body.position;
    state.angle = body.angle;
    return state;
}

// A body's bounding box at t = 0, from the same world vertices the narrow
// phase computes, widened by a hair (see reject_initial_overlaps).
struct Extent {
    double lo_x = 0.0, hi_x = 0.0, lo_y = 0.0, hi_y = 0.0;
};

Extent extent_of(const SceneBody& body, const Transform& xf) {
    Extent e;
    if (body.shape.type == ShapeType::circle) {
        const double r = body.shape.radius;
        e = {xf.p.x - r, xf.p.x + r, xf.p.y - r, xf.p.y + r};
    } else {
        const Polygon& polygon = body.shape.polygon;
        const Vec2 first = apply(xf, polygon.vertices[0]);
        e = {first.x, first.x, first.y, first.y};
        for (int i = 1; i < polygon.count; ++i) {
            const Vec2 v = apply(xf, polygon.vertices[static_cast<std::size_t>(i)]);
            e = {std::min(e.lo_x, v.x), std::max(e.hi_x, v.x), std::min(e.lo_y, v.y),
                 std::max(e.hi_y, v.y)};
        }
    }
    const double slack =
        1e-9 * (std::max(e.hi_x - e.lo_x, e.hi_y - e.lo_y) + std::abs(xf.p.x) + std::abs(xf.p.y));
    return {e.lo_x - slack, e.hi_x + slack, e.lo_y - slack, e.hi_y + slack};
}

// How far a pair may seem to overlap at t = 0 by the rounding of its
// positions alone, when resting contact holds it: bodies stacked at decimal
// heights (a box of half height 0.15 at y = 0.45 on one at y = 0.15) compute a
// gap of -5.6e-17 m, though the scene says they touch. Eight ULPs of the
// largest coordinate or extent of the pair, and never more than the contact
// band d, inside which resting contact counts a pair as touching. Only with
// resting: the seed's model has no use for a pair already inside.
double rounding_allowance(const Scene& scene, const Extent& a, const Extent& b) {
    double scale = 0.0;
    for (const Extent& e : {a, b}) {
        for (const double x : {e.lo_x, e.hi_x, e.lo_y, e.hi_y}) {
            scale = std::max(scale, std::abs(x));
        }
    }
    return std::min(scene.solver.contact_tolerance,
                    8.0 * std::numeric_limits<double>::epsilon() * scale);
}

constexpr const char* rounding_hint =
    ", no more than the rounding of the positions: with \"resting\": true such a pair counts "
    "as touching";

// What to change for a real overlap: the seed's model has no time of impact
// for bodies already inside each other.
constexpr const char* separate_hint =
    "; move them apart by at least that, so that they start separate or touching";

} // namespace

// The engine resolves collisions as they happen; bodies already interpenetrating
// at t = 0 have no collision time, so the run would be meaningless. Touching is
// fine, and with resting contact so is an overlap of the positions' rounding
// (rounding_allowance). Static bodies may overlap one another (walls meeting in a corner).
//
// The pair reported is the one the plain double loop over (j, i < j) meets
// first: the smallest j, then the smallest i, at bodies[j]. Testing every pair
// is O(N^2), too slow for a gas of 10,000; instead the bodies are swept in
// order of their bounding boxes' left edges and only pairs whose boxes meet
// are tested, each with the same call (same argument order, same bits) as the
// double loop would make. Every overlap found is a candidate and the least
// (j, i) wins, so the sweep's order never decides which pair is named. The
// boxes are widened by 1e-9 of their size and position so that a pair whose
// computed gap is negative only by rounding is still tested, as before.
void reject_initial_overlaps(const Scene& scene) {
    const std::vector<SceneBody>& bodies = scene.bodies;
    std::vector<Transform> transforms;
    std::vector<Extent> extents;
    transforms.reserve(bodies.size());
    extents.reserve(bodies.size());
    for (const SceneBody& body : bodies) {
        transforms.push_back(transform_of(initial_state(body)));
        extents.push_back(extent_of(body, transforms.back()));
    }
    std::vector<std::size_t> order(bodies.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return extents[a].lo_x < extents[b].lo_x || (extents[a].lo_x == extents[b].lo_x && a < b);
    });
    struct Overlap {
        std::size_t j = 0, i = 0;
        double gap = 0.0;
        bool rounding = false; // within what resting contact would count as touching
    };
    std::optional<Overlap> first;
    std::vector<std::size_t> active; // boxes that may still reach the next one's left edge
    for (const std::size_t p : order) {
        const Extent& e = extents[p];
        active.erase(std::remove_if(active.begin(), active.end(),
                                    [&](std::size_t q) { return extents[q].hi_x < e.lo_x; }),
                     active.end());
        for (const std::size_t q : active) {
            const Extent& f = extents[q];
            if (f.hi_y < e.lo_y || e.hi_y < f.lo_y) {
                continue;
            }
            const std::size_t j = std::max(p, q);
            const std::size_t i = std::min(p, q);
            if ((bodies[i].is_static && bodies[j].is_static) ||
                (first && (j > first->j || (j == first->j && i > first->i)))) {
                continue;
            }
            const double gap =
                separation(bodies[i].shape, transforms[i], bodies[j].shape, transforms[j]);
            const double allowance = rounding_allowance(scene, extents[i], extents[j]);
            if (gap < (scene.solver.resting ? -allowance : 0.0)) {
                first = Overlap{j, i, gap, -gap <= allowance};
            }
        }
        active.push_back(p);
    }
    if (first) {
        json_fields::fail(body_path(scene, first->j),
                          "'" + bodies[first->j].name + "' overlaps " +
                              body_reference(scene, first->i) + " at t = 0 by " +
                              number_text(-first->gap) + " m" +
                              (first->rounding ? rounding_hint : separate_hint));
    }
}

} // namespace impulse::harness::scene_reading
