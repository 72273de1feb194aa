// The "pile" block (harness/scene/pile.h, scene_pile_block.cpp): its bodies
// counted, never overlapping, enclosed by its walls, the same bits for the same
// seed by the rule docs/formats.md states, and its reading strict.
#include "gas.h"
#include "overlap.h"
#include "pile.h"
#include "scene.h"
#include "scene_pile_block.h"
#include "scene_reading.h"
#include "shape.h"
#include "support/files.h"
#include "support/outcome.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

using impulse::harness::generate_pile;
using impulse::harness::PileSpec;
using impulse::harness::Scene;
using impulse::harness::SceneBody;

namespace {

// Sizes 1:5, densities 1:25 (masses up to 1:625), spacing just over the
// largest box's diagonal 2 sqrt(2) 0.25 = 0.7071.
PileSpec mixed_pile(int count, std::uint64_t seed) {
    PileSpec spec;
    spec.count = count;
    spec.kinds = PileSpec::Kinds::mixed;
    spec.size_min = 0.05;
    spec.size_max = 0.25;
    spec.density_min = 1.0;
    spec.density_max = 25.0;
    spec.spacing = 0.71;
    spec.random_angles = true;
    spec.seed = seed;
    return spec;
}

Scene scene_of(const std::vector<SceneBody>& bodies) {
    Scene scene;
    scene.file = "pile.json";
    scene.bodies = bodies;
    return scene;
}

// Every number a body carries, as bits.
bool same_bits(const SceneBody& a, const SceneBody& b) {
    const double left[] = {a.position.x, a.position.y, a.angle, a.mass, a.inertia, a.shape.radius};
    const double right[] = {b.position.x, b.position.y, b.angle, b.mass, b.inertia, b.shape.radius};
    return std::memcmp(left, right, sizeof left) == 0 && a.shape.type == b.shape.type &&
           a.name == b.name &&
           std::memcmp(&a.shape.polygon, &b.shape.polygon, sizeof a.shape.polygon) == 0;
}

// read_pile after the listed `bodies` of a scene; the FieldError's path and
// message when it refuses.
std::string pile_refusal_with(const std::vector<SceneBody>& listed, const std::string& block) {
    const nlohmann::json json = nlohmann::json::parse(block);
    Scene scene = scene_of(listed);
    scene.listed_bodies = listed.size();
    try {
        impulse::harness::scene_reading::read_pile(
            impulse::harness::scene_reading::Node(json, "pile"), scene);
    } catch (const impulse::harness::json_fields::FieldError& e) {
        return e.path + ": " + e.message;
    }
    return "";
}

// read_pile on the block's JSON alone; the FieldError's path and message when
// it refuses.
std::string pile_refusal(const std::string& block) {
    return pile_refusal_with({}, block);
}

} // namespace

TEST_CASE("a pile is three walls then count bodies, named in order", "[pile]") {
    const std::vector<SceneBody> bodies = generate_pile(mixed_pile(10, 1));
    REQUIRE(bodies.size() == 13);
    CHECK(bodies[0].name == "floor");
    CHECK(bodies[1].name == "wall-left");
    CHECK(bodies[2].name == "wall-right");
    for (int i = 0; i < 3; ++i) {
        CHECK(bodies[static_cast<std::size_t>(i)].is_static);
    }
    CHECK(bodies[3].name == "pile-0");
    CHECK(bodies[12].name == "pile-9");
    for (std::size_t i = 3; i < bodies.size(); ++i) {
        CHECK_FALSE(bodies[i].is_static);
        CHECK(bodies[i].velocity.x == 0.0);
        CHECK(bodies[i].velocity.y == 0.0);
        CHECK(bodies[i].angular_velocity == 0.0);
    }
}

TEST_CASE("a pile at the tightest spacing has no overlap and its walls enclose it", "[pile]") {
    PileSpec spec = mixed_pile(400, 7);
    spec.columns = 13; // not square: 31 rows
    const std::vector<SceneBody> bodies = generate_pile(spec);
    // The loader's own check, then the overlap measure: nothing even touches.
    CHECK_NOTHROW(impulse::harness::scene_reading::reject_initial_overlaps(scene_of(bodies)));
    CHECK_FALSE(impulse::harness::deepest_overlap(bodies, impulse::harness::initial_poses(bodies)));

    // Inner faces: the floor's top, the walls' inner sides and their top.
    const SceneBody& floor = bodies[0];
    const SceneBody& left = bodies[1];
    const SceneBody& right = bodies[2];
    const double floor_top = floor.position.y + floor.shape.polygon.vertices[2].y;
    const double left_face = left.position.x + left.shape.polygon.vertices[2].x;
    const double right_face = right.position.x + right.shape.polygon.vertices[0].x;
    const double wall_top = left.position.y + left.shape.polygon.vertices[2].y;
    CHECK(floor_top == 0.0);
    CHECK(left_face == Approx(-13 * 0.71 / 2).margin(1e-12));
    CHECK(right_face == Approx(13 * 0.71 / 2).margin(1e-12));
    CHECK(wall_top == Approx(2 * 31 * 0.71).margin(1e-12));
    // The floor runs under both walls.
    CHECK(floor.position.x - floor.shape.polygon.vertices[2].x <= left.position.x);
    CHECK(floor.position.x + floor.shape.polygon.vertices[2].x >= right.position.x);
    for (std::size_t i = 3; i < bodies.size(); ++i) {
        const double r = impulse::circumradius(bodies[i].shape);
        INFO(bodies[i].name);
        CHECK(bodies[i].position.x - r > left_face);
        CHECK(bodies[i].position.x + r < right_face);
        CHECK(bodies[i].position.y - r > floor_top);
        CHECK(bodies[i].position.y + r < wall_top / 2.0); // the lattice fills the lower half
        CHECK(bodies[i].mass > 0.0);
    }
}

TEST_CASE("a pile's bodies follow the documented draws: same seed same bits", "[pile]") {
    const std::vector<SceneBody> first = generate_pile(mixed_pile(100, 42));
    const std::vector<SceneBody> again = generate_pile(mixed_pile(100, 42));
    REQUIRE(first.size() == again.size());
    for (std::size_t i = 0; i < first.size(); ++i) {
        CHECK(same_bits(first[i], again[i]));
    }
    // docs/formats.md: per body, kind (u < 0.5: circle), size, density, angle.
    impulse::harness::SplitMix64 random(42);
    for (std::size_t n = 0; n < 2; ++n) {
        const bool circle = random.unit() < 0.5;
        const double size = 0.05 + (0.25 - 0.05) * random.unit();
        const double density = 1.0 + (25.0 - 1.0) * random.unit();
        const double angle = 3.141592653589793 * (2.0 * random.unit() - 1.0);
        const SceneBody& body = first[3 + n];
        CHECK((body.shape.type == impulse::ShapeType::circle) == circle);
        const double area = circle ? 3.141592653589793 * size * size : 4.0 * size * size;
        CHECK(body.mass == Approx(density * area).epsilon(1e-12));
        CHECK(body.angle == angle);
        if (circle) {
            CHECK(body.shape.radius == size);
        } else {
            CHECK(body.shape.polygon.vertices[2].x == size);
        }
    }
    // Body 1 sits in column 1 of row 0: x = -W/2 + 1.5 spacing, y = spacing / 2.
    CHECK(first[4].position.x == -10 * 0.71 / 2 + 0.71 * 1.5);
    CHECK(first[4].position.y == 0.71 * 0.5);

    const std::vector<SceneBody> other = generate_pile(mixed_pile(100, 43));
    int differ = 0;
    for (std::size_t i = 3; i < first.size(); ++i) {
        differ += same_bits(first[i], other[i]) ? 0 : 1;
    }
    CHECK(differ == 100);
}

TEST_CASE("a pile's shape picks every body's kind", "[pile]") {
    for (const auto& [kinds, type] :
         {std::pair{PileSpec::Kinds::circle, impulse::ShapeType::circle},
          std::pair{PileSpec::Kinds::box, impulse::ShapeType::polygon}}) {
        PileSpec spec = mixed_pile(30, 3);
        spec.kinds = kinds;
        for (const SceneBody& body : generate_pile(spec)) {
            if (!body.is_static) {
                CHECK(body.shape.type == type);
            }
        }
    }
}

TEST_CASE("the pile block is read strictly, naming the JSON path", "[pile]") {
    const std::string good =
        R"("count": 20, "shape": "mixed", "size": [0.05, 0.25], "density": [1, 4])";
    CHECK(pile_refusal("{" + good + R"(, "spacing": 0.71, "seed": 3, "random_angles": true})") ==
          "");
    CHECK(pile_refusal(R"({"count": 20, "shape": "circle", "size": [0.05, 0.25], "spacing": 0.5})")
              .rfind("pile.spacing: must be more than the largest body's bounding diameter 0.5 m",
                     0) == 0);
    // Boxes: the diagonal 2 sqrt(2) 0.25 = 0.7071 is the bound.
    CHECK(
        pile_refusal("{" + good + R"(, "spacing": 0.7})").rfind("pile.spacing: must be more", 0) ==
        0);
    CHECK(
        pile_refusal("{" + good + R"(, "spacing": 0.71, "colour": 1})").rfind("pile.colour: ", 0) ==
        0);
    CHECK(pile_refusal(R"({"count": 20, "shape": "disc", "size": [1, 2], "spacing": 9})")
              .rfind("pile.shape: must be one of", 0) == 0);
    CHECK(pile_refusal(R"({"count": 20, "shape": "box", "size": [2, 1], "spacing": 9})")
              .rfind("pile.size: must be [min, max] with min <= max", 0) == 0);
    CHECK(pile_refusal(R"({"count": 0, "shape": "box", "size": [1, 2], "spacing": 9})")
              .rfind("pile.count: ", 0) == 0);
    CHECK(
        pile_refusal(R"({"count": 2, "shape": "box", "size": [1, 2], "spacing": 9, "columns": 0})")
            .rfind("pile.columns: ", 0) == 0);
    CHECK(pile_refusal(
              R"({"count": 2, "shape": "box", "size": [1, 2], "density": [0, 1], "spacing": 9})")
              .rfind("pile.density[0]: ", 0) == 0);
}

TEST_CASE("a listed body in the pile's box is refused at the pile, naming both", "[pile]") {
    // Two discs of radius 0.5 at spacing 2: pile-0 sits at (-1, 1); a listed
    // disc of radius 0.25 at (-1, 1.5) overlaps it by 0.25.
    SceneBody listed;
    listed.name = "stray";
    listed.shape = impulse::make_circle(0.25);
    listed.position = {-1.0, 1.5};
    listed.mass = 1.0;
    const std::string block =
        R"({"count": 2, "shape": "circle", "size": [0.5, 0.5], "spacing": 2})";
    const std::string refusal = pile_refusal_with({listed}, block);
    CHECK(refusal.rfind("pile: makes 'pile-0', which overlaps bodies[0] 'stray' at t = 0 by 0.25 m",
                        0) == 0);
    listed.position = {-1.0, 1.75}; // touching is allowed
    CHECK(pile_refusal_with({listed}, block) == "");
}

TEST_CASE("a scene file with a pile block runs through the real tool", "[pile]") {
    // 12 discs of radius 0.1 on a 4-column lattice, spacing 0.3: one step of
    // free fall, so the trajectory has a column block per generated body.
    impulse::test::TempDir dir;
    impulse::test::spit(dir.dir / "heap.json",
                        R"({"schema": "impulse/scene@1", "name": "heap", "dt": 0.01,
  "duration": 0.01, "pile": {"count": 12, "shape": "circle", "size": [0.1, 0.1],
  "spacing": 0.3, "columns": 4}})");
    const impulse::test::Outcome ran =
        impulse::test::run_tool({"run", (dir.dir / "heap.json").string()});
    impulse::test::require_exit(ran, 0);
    const nlohmann::json trajectory = nlohmann::json::parse(ran.out);
    CHECK(trajectory.at("columns").size() == 1 + 6 * 12);
    CHECK(trajectory.at("columns")[1] == "pile-0.x");
    CHECK(trajectory.at("frames").size() == 2);
}
