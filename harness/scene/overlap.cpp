// The deepest interpenetration of a set of posed bodies (overlap.h).
#include "overlap.h"

#include "body.h"
#include "manifold.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace impulse::harness {

namespace {

struct Box {
    double lo_x = 0.0, hi_x = 0.0, lo_y = 0.0, hi_y = 0.0;
};

// The body's bounding box in its pose, from the same world vertices the
// narrow phase computes, widened by 1e-9 of its size and position so a pair
// whose separation is 0 or negative only by rounding is still tested.
Box box_of(const Shape& shape, const Transform& xf) {
    Box e;
    if (shape.type == ShapeType::circle) {
        const double r = shape.radius;
        e = {xf.p.x - r, xf.p.x + r, xf.p.y - r, xf.p.y + r};
    } else {
        const Vec2 first = apply(xf, shape.polygon.vertices[0]);
        e = {first.x, first.x, first.y, first.y};
        for (int i = 1; i < shape.polygon.count; ++i) {
            const Vec2 v = apply(xf, shape.polygon.vertices[static_cast<std::size_t>(i)]);
            e = {std::min(e.lo_x, v.x), std::max(e.hi_x, v.x), std::min(e.lo_y, v.y),
                 std::max(e.hi_y, v.y)};
        }
    }
    const double slack =
        1e-9 * (std::max(e.hi_x - e.lo_x, e.hi_y - e.lo_y) + std::abs(xf.p.x) + std::abs(xf.p.y));
    return {e.lo_x - slack, e.hi_x + slack, e.lo_y - slack, e.hi_y + slack};
}

bool boxes_meet(const Box& p, const Box& q) {
    return !(p.hi_x < q.lo_x || q.hi_x < p.lo_x || p.hi_y < q.lo_y || q.hi_y < p.lo_y);
}

// Keeps the deepest candidate, ties to the least (a, b): the result is the
// same whatever order the pairs are met in.
void consider(std::optional<Overlap>& best, const std::vector<SceneBody>& bodies,
              const std::vector<Transform>& poses, std::size_t i, std::size_t j) {
    const std::size_t a = std::min(i, j);
    const std::size_t b = std::max(i, j);
    const double gap = separation(bodies[a].shape, poses[a], bodies[b].shape, poses[b]);
    if (!(gap <= 0.0)) {
        return;
    }
    const Overlap found{-gap, a, b};
    if (!best || found.depth > best->depth ||
        (found.depth == best->depth && (a < best->a || (a == best->a && b < best->b)))) {
        best = found;
    }
}

// A cell's key: its two whole-number coordinates packed into 64 bits. Cells
// further than 2^31 apart would alias, which only costs extra box tests.
std::uint64_t cell_key(long long cx, long long cy) {
    return (static_cast<std::uint64_t>(cx) << 32) ^ (static_cast<std::uint64_t>(cy) & 0xffffffffu);
}

long long cell_of(double coordinate, double cell) {
    return static_cast<long long>(std::floor(coordinate / cell));
}

} // namespace

std::vector<Transform> initial_poses(const std::vector<SceneBody>& bodies) {
    std::vector<Transform> poses;
    poses.reserve(bodies.size());
    for (const SceneBody& body : bodies) {
        BodyState state;
        state.position = body.position;
        state.angle = body.angle;
        poses.push_back(transform_of(state));
    }
    return poses;
}

// Dynamic pairs: each dynamic body sits in the one cell holding its box's
// centre, the cell as wide as the largest dynamic box, so two boxes that meet
// lie in the same or neighbouring cells. Static bodies (walls, a floor: few,
// but as wide as the whole pile) are not put in the grid, which they would
// fill; each is tested against every dynamic box instead, O(N) per static body.
std::optional<Overlap> deepest_overlap(const std::vector<SceneBody>& bodies,
                                       const std::vector<Transform>& poses) {
    std::vector<Box> boxes;
    boxes.reserve(bodies.size());
    std::vector<std::size_t> dynamic;
    std::vector<std::size_t> fixed;
    double cell = 0.0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        boxes.push_back(box_of(bodies[i].shape, poses[i]));
        if (bodies[i].is_static) {
            fixed.push_back(i);
            continue;
        }
        dynamic.push_back(i);
        cell = std::max({cell, boxes[i].hi_x - boxes[i].lo_x, boxes[i].hi_y - boxes[i].lo_y});
    }
    std::optional<Overlap> best;
    for (const std::size_t s : fixed) {
        for (const std::size_t d : dynamic) {
            if (boxes_meet(boxes[s], boxes[d])) {
                consider(best, bodies, poses, s, d);
            }
        }
    }
    if (dynamic.size() < 2) {
        return best;
    }
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
    grid.reserve(dynamic.size());
    std::vector<std::pair<long long, long long>> cells(bodies.size());
    for (const std::size_t d : dynamic) {
        const Box& e = boxes[d];
        cells[d] = {cell_of((e.lo_x + e.hi_x) / 2.0, cell), cell_of((e.lo_y + e.hi_y) / 2.0, cell)};
        grid[cell_key(cells[d].first, cells[d].second)].push_back(d);
    }
    for (const std::size_t d : dynamic) {
        for (long long dx = -1; dx <= 1; ++dx) {
            for (long long dy = -1; dy <= 1; ++dy) {
                const auto found = grid.find(cell_key(cells[d].first + dx, cells[d].second + dy));
                if (found == grid.end()) {
                    continue;
                }
                for (const std::size_t other : found->second) {
                    // Each pair once: from its lower index.
                    if (other > d && boxes_meet(boxes[d], boxes[other])) {
                        consider(best, bodies, poses, d, other);
                    }
                }
            }
        }
    }
    return best;
}

} // namespace impulse::harness
