// The broad phase may only prune: every pair whose boxes overlap must come back
// from a query, whatever the boxes' sizes, places and later re-insertions.
#include "broad_phase.h"
#include "support.h"

#include <catch2/catch.hpp>
#include <random>
#include <set>
#include <utility>

using namespace impulse;
using impulse::test::uniform;

namespace {

Aabb box_at(Vec2 centre, double hx, double hy) {
    return {{centre.x - hx, centre.y - hy}, {centre.x + hx, centre.y + hy}};
}

std::set<int> overlapping(const std::vector<Aabb>& boxes, const Aabb& query) {
    std::set<int> ids;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (overlaps(boxes[i], query)) {
            ids.insert(static_cast<int>(i));
        }
    }
    return ids;
}

std::set<int> candidates(UniformGrid& grid, const Aabb& query) {
    std::set<int> ids;
    std::vector<int> order;
    grid.query(query, [&](int id) {
        order.push_back(id);
        ids.insert(id);
    });
    CHECK(order.size() == ids.size()); // each id visited once per query
    return ids;
}

bool contains_all(const std::set<int>& superset, const std::set<int>& subset) {
    for (const int id : subset) {
        if (superset.count(id) == 0) {
            return false;
        }
    }
    return true;
}

} // namespace

TEST_CASE("aabb_of a box turned 45 degrees reaches half a diagonal from its centre", "[unit]") {
    const Shape box = make_box(1.0, 1.0);
    const Aabb b = aabb_of(box, {{2.0, -1.0}, rotation_of(0.7853981633974483)}, 0.0);
    const double half_diagonal = std::sqrt(2.0);
    CHECK(b.lower.x == Approx(2.0 - half_diagonal).epsilon(1e-15));
    CHECK(b.upper.x == Approx(2.0 + half_diagonal).epsilon(1e-15));
    CHECK(b.lower.y == Approx(-1.0 - half_diagonal).epsilon(1e-15));
    CHECK(b.upper.y == Approx(-1.0 + half_diagonal).epsilon(1e-15));
    const Aabb c = aabb_of(make_circle(0.5), {{1.0, 1.0}, {}}, 0.25);
    CHECK(c.lower.x == 0.25);
    CHECK(c.upper.y == 1.75);
}

TEST_CASE("overlaps counts touching boxes as overlapping", "[unit]") {
    CHECK(overlaps(box_at({0, 0}, 1, 1), box_at({2, 0}, 1, 1)));
    CHECK_FALSE(overlaps(box_at({0, 0}, 1, 1), box_at({2.000001, 0}, 1, 1)));
    CHECK_FALSE(overlaps(box_at({0, 0}, 1, 1), box_at({0, -2.5}, 1, 1)));
}

TEST_CASE("grid queries return every overlapping box", "[unit]") {
    std::mt19937_64 rng(20261122);
    for (int trial = 0; trial < 40; ++trial) {
        const int n = 1 + static_cast<int>(rng() % 300);
        std::vector<Aabb> boxes;
        for (int i = 0; i < n; ++i) {
            // Mostly small boxes in a room, some huge (walls), some far away.
            const double size = trial % 3 == 0 ? uniform(rng, 0.0, 0.3) : 0.1;
            const double spread = i % 17 == 0 ? 1e4 : 20.0;
            Vec2 centre{uniform(rng, -spread, spread), uniform(rng, -spread, spread)};
            const bool wall = i % 29 == 0;
            boxes.push_back(box_at(centre, wall ? 50.0 : size, wall ? 0.5 : size));
        }
        UniformGrid grid;
        grid.build(boxes);
        for (int q = 0; q < 50; ++q) {
            const Aabb query = box_at({uniform(rng, -25.0, 25.0), uniform(rng, -25.0, 25.0)},
                                      uniform(rng, 0, 2), uniform(rng, 0, 2));
            REQUIRE(contains_all(candidates(grid, query), overlapping(boxes, query)));
        }
        // Bodies move after the build: new boxes filed under the same ids,
        // including far outside the grid's original bounds.
        for (int m = 0; m < n / 2; ++m) {
            const int id = static_cast<int>(rng() % static_cast<unsigned>(n));
            const double spread = m % 5 == 0 ? 1e6 : 30.0;
            boxes[static_cast<std::size_t>(id)] =
                box_at({uniform(rng, -spread, spread), uniform(rng, -spread, spread)}, 0.2, 0.2);
            grid.insert(id, boxes[static_cast<std::size_t>(id)]);
        }
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            REQUIRE(contains_all(candidates(grid, boxes[i]), overlapping(boxes, boxes[i])));
        }
    }
}

TEST_CASE("a grid of equal bodies hands each query a handful of candidates", "[unit]") {
    // The point of the grid: a dense lattice of 10^4 small boxes, each query
    // sees its neighbourhood, not the world.
    std::vector<Aabb> boxes;
    for (int j = 0; j < 100; ++j) {
        for (int i = 0; i < 100; ++i) {
            boxes.push_back(box_at({0.5 * i, 0.5 * j}, 0.1, 0.1));
        }
    }
    UniformGrid grid;
    grid.build(boxes);
    std::size_t most = 0;
    for (const Aabb& box : boxes) {
        most = std::max(most, candidates(grid, box).size());
    }
    CHECK(most <= 9);
}
