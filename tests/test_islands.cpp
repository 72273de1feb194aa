// Contact islands (engine/islands.h): bodies joined through contact links,
// static bodies never joining, in the documented deterministic order.
#include "islands.h"
#include "support.h"

#include <catch2/catch.hpp>
#include <cstddef>
#include <random>
#include <vector>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::static_body;

namespace {

std::vector<int> bodies_of(const Islands& islands, int k) {
    const auto i = static_cast<std::size_t>(k);
    return {islands.bodies.begin() + islands.body_offsets[i],
            islands.bodies.begin() + islands.body_offsets[i + 1]};
}

std::vector<int> links_of(const Islands& islands, int k) {
    const auto i = static_cast<std::size_t>(k);
    return {islands.links_of.begin() + islands.link_offsets[i],
            islands.links_of.begin() + islands.link_offsets[i + 1]};
}

// Body 0 is a static floor; bodies 1.. are unit boxes (only the masses matter).
std::vector<Body> floor_and_boxes(int boxes) {
    std::vector<Body> bodies{static_body(make_box(10.0, 0.5), {0.0, -0.5})};
    for (int i = 0; i < boxes; ++i) {
        bodies.push_back(dynamic_body(make_box(0.5, 0.5), 1.0, {0.0, 0.5 + i}));
    }
    return bodies;
}

bool scratch_is_clean(const IslandScratch& s) {
    for (std::size_t i = 0; i < s.parent.size(); ++i) {
        if (s.parent[i] != -1 || s.island_of[i] != -1) {
            return false;
        }
    }
    return s.touched.empty();
}

bool same(const Islands& x, const Islands& y) {
    return x.body_offsets == y.body_offsets && x.bodies == y.bodies &&
           x.link_offsets == y.link_offsets && x.links_of == y.links_of;
}

} // namespace

TEST_CASE("three stacks on one floor are three islands, the floor in none", "[islands]") {
    // Stacks {1,2,3}, {4,5,6}, {7,8,9}, each bottom box on floor 0; the links
    // are given interleaved and top-down so order must come from the bodies.
    const std::vector<Body> bodies = floor_and_boxes(9);
    const std::vector<IslandLink> links{{9, 8}, {3, 2}, {6, 5}, {8, 7}, {2, 1},
                                        {5, 4}, {7, 0}, {1, 0}, {4, 0}};
    Islands islands;
    IslandScratch scratch;
    find_islands(bodies, links, islands, scratch);
    REQUIRE(islands.count() == 3);
    CHECK(bodies_of(islands, 0) == std::vector<int>{1, 2, 3});
    CHECK(bodies_of(islands, 1) == std::vector<int>{4, 5, 6});
    CHECK(bodies_of(islands, 2) == std::vector<int>{7, 8, 9});
    CHECK(links_of(islands, 0) == std::vector<int>{1, 4, 7});
    CHECK(links_of(islands, 1) == std::vector<int>{2, 5, 8});
    CHECK(links_of(islands, 2) == std::vector<int>{0, 3, 6});
    CHECK(scratch_is_clean(scratch));
}

TEST_CASE("a chain of 50 is one island with its bodies ascending", "[islands]") {
    // Links from the top of the chain down, so the root changes at every union.
    const std::vector<Body> bodies = floor_and_boxes(50);
    std::vector<IslandLink> links;
    for (int i = 50; i > 1; --i) {
        links.push_back({i, i - 1});
    }
    links.push_back({1, 0});
    Islands islands;
    IslandScratch scratch;
    find_islands(bodies, links, islands, scratch);
    REQUIRE(islands.count() == 1);
    std::vector<int> expected;
    for (int i = 1; i <= 50; ++i) {
        expected.push_back(i);
    }
    CHECK(bodies_of(islands, 0) == expected);
    CHECK(islands.links_of.size() == links.size());
    CHECK(scratch_is_clean(scratch));
}

TEST_CASE("bodies touching only through the floor are separate islands", "[islands]") {
    // Two boxes each on the floor, a third on nothing and a link between two
    // static bodies: that one is in no island, box 3 flies free.
    std::vector<Body> bodies = floor_and_boxes(3);
    bodies.push_back(static_body(make_box(1.0, 1.0), {20.0, 0.0}));
    const std::vector<IslandLink> links{{0, 2}, {1, 0}, {4, 0}};
    Islands islands;
    IslandScratch scratch;
    find_islands(bodies, links, islands, scratch);
    REQUIRE(islands.count() == 2);
    CHECK(bodies_of(islands, 0) == std::vector<int>{1});
    CHECK(bodies_of(islands, 1) == std::vector<int>{2});
    CHECK(links_of(islands, 0) == std::vector<int>{1});
    CHECK(links_of(islands, 1) == std::vector<int>{0});
    CHECK(islands.bodies.size() == 2); // neither 3 (no link) nor the static ones
    CHECK(islands.links_of.size() == 2);
    CHECK(scratch_is_clean(scratch));

    find_islands(bodies, {}, islands, scratch);
    CHECK(islands.count() == 0);
    CHECK(islands.bodies.empty());
}

TEST_CASE("islands are the same bits for reused scratch and for shuffled links", "[islands]") {
    // A random contact graph over 200 bodies, every fifth one static.
    std::mt19937_64 rng(20261124);
    std::vector<Body> bodies;
    for (int i = 0; i < 200; ++i) {
        bodies.push_back(i % 5 == 0 ? static_body(make_circle(1.0), {})
                                    : dynamic_body(make_circle(1.0), 1.0, {}));
    }
    std::vector<IslandLink> links;
    for (int l = 0; l < 150; ++l) {
        const int a = static_cast<int>(rng() % 200);
        const int b = static_cast<int>(rng() % 200);
        if (a != b) {
            links.push_back({a, b});
        }
    }
    Islands first;
    IslandScratch scratch;
    find_islands(bodies, links, first, scratch);
    REQUIRE(first.count() > 10); // a graph this sparse splits into many islands
    // Every link's dynamic bodies are in the island that lists the link, every
    // listed body is dynamic, and the islands' smallest bodies ascend.
    std::vector<int> island_of(bodies.size(), -1);
    for (int k = 0; k < first.count(); ++k) {
        for (const int b : bodies_of(first, k)) {
            CHECK(!bodies[static_cast<std::size_t>(b)].is_static());
            island_of[static_cast<std::size_t>(b)] = k;
        }
        if (k > 0) {
            CHECK(bodies_of(first, k - 1).front() < bodies_of(first, k).front());
        }
        for (const int l : links_of(first, k)) {
            for (const int b :
                 {links[static_cast<std::size_t>(l)].a, links[static_cast<std::size_t>(l)].b}) {
                if (!bodies[static_cast<std::size_t>(b)].is_static()) {
                    CHECK(island_of[static_cast<std::size_t>(b)] == k);
                }
            }
        }
    }
    Islands again;
    find_islands(bodies, links, again, scratch);
    CHECK(same(first, again));
    CHECK(scratch_is_clean(scratch));

    // Shuffle the links (Fisher-Yates on the generator's raw bits): the same
    // bodies per island, and each island's links in the shuffled order.
    std::vector<std::size_t> order(links.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        order[i] = i;
    }
    for (std::size_t i = order.size() - 1; i > 0; --i) {
        std::swap(order[i], order[static_cast<std::size_t>(rng() % (i + 1))]);
    }
    std::vector<IslandLink> shuffled;
    for (const std::size_t i : order) {
        shuffled.push_back(links[i]);
    }
    Islands mixed;
    find_islands(bodies, shuffled, mixed, scratch);
    CHECK(mixed.body_offsets == first.body_offsets);
    CHECK(mixed.bodies == first.bodies);
    CHECK(mixed.link_offsets == first.link_offsets);
    for (int k = 0; k < first.count(); ++k) {
        std::vector<int> in_given_order; // island k's original links, in shuffled order
        for (std::size_t s = 0; s < order.size(); ++s) {
            for (const int l : links_of(first, k)) {
                if (static_cast<std::size_t>(l) == order[s]) {
                    in_given_order.push_back(static_cast<int>(s));
                }
            }
        }
        CHECK(links_of(mixed, k) == in_given_order);
    }
}
