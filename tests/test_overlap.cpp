// The deepest interpenetration of posed bodies (harness/scene/overlap.h): hand-made
// overlaps whose depth is known from the geometry, and a lattice of 2,000 bodies
// whose answer is constructed, checked against every pair tested one by one.
#include "manifold.h"
#include "overlap.h"
#include "scene.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

using impulse::make_box;
using impulse::make_circle;
using impulse::harness::deepest_overlap;
using impulse::harness::initial_poses;
using impulse::harness::Overlap;
using impulse::harness::SceneBody;

namespace {

SceneBody disc(double x, double y, double r) {
    SceneBody body;
    body.name = "d";
    body.shape = make_circle(r);
    body.position = {x, y};
    body.mass = 1.0;
    return body;
}

SceneBody floor_box() {
    SceneBody body;
    body.name = "floor";
    body.is_static = true;
    body.shape = make_box(5.0, 0.5);
    body.position = {0.0, -0.5}; // top at y = 0
    return body;
}

std::optional<Overlap> deepest(const std::vector<SceneBody>& bodies) {
    return deepest_overlap(bodies, initial_poses(bodies));
}

} // namespace

TEST_CASE("two discs whose centres are 0.1 closer than their radii overlap by 0.1", "[overlap]") {
    const std::optional<Overlap> found = deepest({disc(0.0, 0.0, 0.5), disc(0.9, 0.0, 0.5)});
    REQUIRE(found);
    CHECK(found->depth == Approx(0.1).margin(1e-12));
    CHECK(found->a == 0);
    CHECK(found->b == 1);
}

TEST_CASE("a box's corner 0.02 below the floor's top overlaps it by 0.02", "[overlap]") {
    // A unit square turned 45 degrees: its lowest corner is half its diagonal,
    // sqrt(2) / 2, below its centre.
    SceneBody box = disc(0.0, std::sqrt(2.0) / 2.0 - 0.02, 0.5);
    box.shape = make_box(0.5, 0.5);
    box.angle = std::atan(1.0);
    const std::optional<Overlap> found = deepest({floor_box(), box});
    REQUIRE(found);
    CHECK(found->depth == Approx(0.02).margin(1e-12));
    CHECK(found->a == 0);
    CHECK(found->b == 1);
}

TEST_CASE("touching bodies are a pair at depth 0; separated ones are no pair", "[overlap]") {
    const std::optional<Overlap> touching = deepest({disc(0.0, 0.0, 0.5), disc(1.0, 0.0, 0.5)});
    REQUIRE(touching);
    CHECK(touching->depth == 0.0);
    CHECK_FALSE(deepest({disc(0.0, 0.0, 0.5), disc(1.5, 0.0, 0.5)}));
    // A disc resting exactly on the floor touches it.
    const std::optional<Overlap> resting = deepest({floor_box(), disc(2.0, 0.5, 0.5)});
    REQUIRE(resting);
    CHECK(resting->depth == 0.0);
}

TEST_CASE("static bodies overlapping each other are not a pair", "[overlap]") {
    SceneBody wall = floor_box();
    wall.position = {1.0, -0.5};
    CHECK_FALSE(deepest({floor_box(), wall, disc(0.0, 5.0, 0.5)}));
}

TEST_CASE("a 2,000-body lattice: the one pair pushed deeper is found, as by every pair tested",
          "[overlap]") {
    // 50 x 40 discs of radius 0.5 at spacing 0.99: each overlaps its four
    // neighbours by 0.01 (the diagonals, 0.99 sqrt(2) apart, do not meet).
    // Disc 1234 is moved 0.02 towards disc 1235, so that pair overlaps by 0.03.
    const int columns = 50;
    std::vector<SceneBody> bodies;
    for (int n = 0; n < 2000; ++n) {
        bodies.push_back(disc(0.99 * (n % columns), 0.99 * (n / columns), 0.5));
    }
    bodies[1234].position.x += 0.02;
    const std::optional<Overlap> found = deepest(bodies);
    REQUIRE(found);
    CHECK(found->a == 1234);
    CHECK(found->b == 1235);
    CHECK(found->depth == Approx(0.03).margin(1e-12));

    // The same lattice with boxes turned by various angles: the grid's answer
    // is the double loop's, bit for bit.
    for (int n = 0; n < 2000; n += 3) {
        bodies[static_cast<std::size_t>(n)].shape = make_box(0.35, 0.3);
        bodies[static_cast<std::size_t>(n)].angle = 0.001 * n;
    }
    const std::vector<impulse::Transform> poses = initial_poses(bodies);
    std::optional<Overlap> brute;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        for (std::size_t a = 0; a < b; ++a) {
            const double gap =
                impulse::separation(bodies[a].shape, poses[a], bodies[b].shape, poses[b]);
            if (gap <= 0.0 &&
                (!brute || -gap > brute->depth ||
                 (-gap == brute->depth && (a < brute->a || (a == brute->a && b < brute->b))))) {
                brute = Overlap{-gap, a, b};
            }
        }
    }
    const std::optional<Overlap> grid = deepest_overlap(bodies, poses);
    REQUIRE(brute);
    REQUIRE(grid);
    CHECK(grid->a == brute->a);
    CHECK(grid->b == brute->b);
    CHECK(grid->depth == brute->depth);
}
