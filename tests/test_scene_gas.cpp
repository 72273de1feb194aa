// Scene loading, the gas generator (docs/formats.md, the gas block): the
// lattice, the draws, reproducibility, the scale scenes, and one case per
// rejected input, each checked for the file name, the exact JSON path and the
// reason (support/scene_text.h).
#include "gas.h"
#include "input_error.h"
#include "scene.h"
#include "sha256.h"
#include "shape.h"
#include "support/scene_text.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

using impulse::Integrator;
using impulse::ShapeType;
using impulse::Vec2;
using impulse::harness::InputError;
using impulse::harness::load_scene;
using impulse::harness::parse_scene;
using impulse::harness::Scene;
using namespace impulse::test;

// ---------------------------------------------------------------- the gas block

namespace {

// A scene of no gravity with the given gas block (its inside, without braces)
// and further top-level keys (end them with a comma).
std::string gas_scene(const std::string& gas, const std::string& extra = "") {
    return R"({"schema": "impulse/scene@1", "name": "gas", "gravity": [0, 0], "dt": 0.01,
               "duration": 1, )" +
           extra + R"( "gas": {)" + gas + "}}";
}

// Five discs of radius 0.1 on a 0.5 m lattice: k = 3 (3 * 3 >= 5 > 2 * 2).
const std::string five = R"("count": 5, "shape": {"circle": 0.1}, "mass": 1, "spacing": 0.5,
                             "max_speed": 5)";

// The rule of docs/formats.md written out again, independently of gas.cpp:
// splitmix64 from `seed`, u = (z >> 11) 2^-53, s = 2 u - 1.
struct Draws {
    std::uint64_t state;
    double next() {
        state += 0x9e3779b97f4a7c15u;
        std::uint64_t z = state;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
        z ^= z >> 31;
        return 2.0 * (static_cast<double>(z >> 11) * 0x1.0p-53) - 1.0;
    }
};

std::uint64_t bits(double value) {
    std::uint64_t out = 0;
    std::memcpy(&out, &value, sizeof out);
    return out;
}

} // namespace

TEST_CASE("splitmix64 gives the reference outputs, and unit() its 53 high bits", "[scene]") {
    // Vigna's splitmix64.c from state 0: the first outputs of the published generator.
    impulse::harness::SplitMix64 random(0);
    CHECK(random.next() == 0xe220a8397b1dcdafu);
    CHECK(random.next() == 0x6e789e6aa1b965f4u);
    CHECK(random.next() == 0x06c45d188009454fu);
    // The 53 high bits: 0xf7a2... >> 11, times 2^-53.
    impulse::harness::SplitMix64 again(0);
    CHECK(again.unit() == static_cast<double>(0xe220a8397b1dcdafu >> 11) * 0x1.0p-53);
    CHECK(again.unit() < 1.0);
}

TEST_CASE("the lattice side and the circumradius", "[scene]") {
    using impulse::circumradius;
    using impulse::harness::gas_lattice_side;
    CHECK(gas_lattice_side(1) == 1);
    CHECK(gas_lattice_side(4) == 2);
    CHECK(gas_lattice_side(5) == 3);
    CHECK(gas_lattice_side(9) == 3);
    CHECK(gas_lattice_side(10) == 4);
    CHECK(gas_lattice_side(10000) == 100);
    CHECK(gas_lattice_side(10001) == 101);
    CHECK(gas_lattice_side(100000) == 317); // 316^2 = 99856 < 100000 <= 317^2 = 100489
    CHECK(circumradius(impulse::make_circle(0.1)) == 0.1);
    // Box [0.3, 0.4]: corners 0.5 from the centre.
    CHECK(circumradius(impulse::make_box(0.3, 0.4)) == Approx(0.5).epsilon(1e-15));
}

TEST_CASE("a gas block makes four walls and its bodies on the lattice", "[scene]") {
    const Scene scene = parse_scene(gas_scene(five), test_file);
    REQUIRE(scene.bodies.size() == 9);
    CHECK(scene.listed_bodies == 0);
    REQUIRE(scene.gas.has_value());
    CHECK(scene.gas->count == 5);
    CHECK(scene.gas->seed == 1);
    CHECK(scene.gas->wall_thickness == 1.0);
    CHECK(scene.warnings.empty());

    // k = 3, L = 1.5, h = 0.75; walls 1 m thick, so t = 0.5 and their centres
    // are c = 1.25 from the origin; the side walls are h + 1 = 1.75 tall each way.
    struct Wall {
        const char* name;
        Vec2 position;
        double hx, hy;
    };
    const Wall walls[4] = {{"wall-bottom", {0.0, -1.25}, 0.75, 0.5},
                           {"wall-top", {0.0, 1.25}, 0.75, 0.5},
                           {"wall-left", {-1.25, 0.0}, 0.5, 1.75},
                           {"wall-right", {1.25, 0.0}, 0.5, 1.75}};
    for (std::size_t w = 0; w < 4; ++w) {
        const impulse::harness::SceneBody& body = scene.bodies[w];
        INFO(body.name);
        CHECK(body.name == walls[w].name);
        CHECK(body.is_static);
        CHECK(body.position == walls[w].position);
        CHECK(body.angle == 0.0);
        CHECK(body.mass == 0.0);
        REQUIRE(body.shape.type == ShapeType::polygon);
        // make_box's first vertex is the lower left corner, the third the upper right.
        CHECK(body.shape.polygon.vertices[0] == Vec2{-walls[w].hx, -walls[w].hy});
        CHECK(body.shape.polygon.vertices[2] == Vec2{walls[w].hx, walls[w].hy});
    }
    // Sites at -0.75 + 0.5 (i + 0.5): -0.5, 0, 0.5; row by row from the bottom left.
    const Vec2 sites[5] = {{-0.5, -0.5}, {0.0, -0.5}, {0.5, -0.5}, {-0.5, 0.0}, {0.0, 0.0}};
    for (std::size_t n = 0; n < 5; ++n) {
        const impulse::harness::SceneBody& body = scene.bodies[4 + n];
        INFO(body.name);
        CHECK(body.name == "gas-" + std::to_string(n));
        CHECK_FALSE(body.is_static);
        CHECK(body.rotation);
        CHECK(body.position == sites[n]);
        CHECK(body.shape.type == ShapeType::circle);
        CHECK(body.shape.radius == 0.1);
        CHECK(body.mass == 1.0);
        CHECK(body.inertia == Approx(0.005).epsilon(1e-15)); // m r^2 / 2
        CHECK(body.angle == 0.0);                            // random_angles false
        CHECK(body.angular_velocity == 0.0);                 // max_angular_speed 0
        CHECK(impulse::length_squared(body.velocity) <= 25.0);
    }
    // The velocities by the documented rule: per body, (a, b) until a^2 + b^2 <= 1.
    Draws draws{1};
    for (std::size_t n = 0; n < 5; ++n) {
        double a = 0.0;
        double b = 0.0;
        do {
            a = draws.next();
            b = draws.next();
        } while (!(a * a + b * b <= 1.0));
        CHECK(bits(scene.bodies[4 + n].velocity.x) == bits(5.0 * a));
        CHECK(bits(scene.bodies[4 + n].velocity.y) == bits(5.0 * b));
    }
}

TEST_CASE("a gas's angles and spins follow the velocity draws, body by body", "[scene]") {
    const Scene scene = parse_scene(
        gas_scene(R"("count": 3, "shape": {"box": [0.1, 0.2]}, "density": 2, "spacing": 1,
                     "max_speed": 2, "max_angular_speed": 3, "random_angles": true, "seed": 7,
                     "wall_thickness": 0.25)"),
        test_file);
    REQUIRE(scene.bodies.size() == 7);
    // k = 2, L = 2, h = 1, t = 0.125: bottom wall at y = -1.125.
    CHECK(scene.bodies[0].position == Vec2{0.0, -1.125});
    CHECK(scene.bodies[2].shape.polygon.vertices[2] == Vec2{0.125, 1.25});
    Draws draws{7};
    for (std::size_t n = 0; n < 3; ++n) {
        const impulse::harness::SceneBody& body = scene.bodies[4 + n];
        INFO(body.name);
        double a = 0.0;
        double b = 0.0;
        do {
            a = draws.next();
            b = draws.next();
        } while (!(a * a + b * b <= 1.0));
        CHECK(bits(body.velocity.x) == bits(2.0 * a));
        CHECK(bits(body.velocity.y) == bits(2.0 * b));
        CHECK(bits(body.angle) == bits(3.141592653589793 * draws.next()));
        CHECK(bits(body.angular_velocity) == bits(3.0 * draws.next()));
        CHECK(body.angle >= -3.141592653589793);
        CHECK(body.angle < 3.141592653589793);
        CHECK(std::abs(body.angular_velocity) <= 3.0);
        // Density 2 over 0.2 x 0.4 m: 0.16 kg; I = M (0.2^2 + 0.4^2) / 12.
        CHECK(body.mass == Approx(0.16).epsilon(1e-15));
        CHECK(body.inertia == Approx(0.16 * 0.2 / 12.0).epsilon(1e-14));
    }
    // Sites: (-0.5, -0.5), (0.5, -0.5), (-0.5, 0.5).
    CHECK(scene.bodies[6].position == Vec2{-0.5, 0.5});
}

TEST_CASE("a gas is reproducible: the same seed gives the same bits, another seed others",
          "[scene]") {
    const std::string block = R"("count": 50, "shape": {"box": [0.1, 0.1]}, "spacing": 0.5,
                                  "max_speed": 5, "max_angular_speed": 5, "random_angles": true)";
    const Scene a = parse_scene(gas_scene(block + R"(, "seed": 3)"), test_file);
    const Scene b = parse_scene(gas_scene(block + R"(, "seed": 3)"), "other.json");
    const Scene c = parse_scene(gas_scene(block + R"(, "seed": 4)"), test_file);
    REQUIRE(a.bodies.size() == 54);
    REQUIRE(c.bodies.size() == 54);
    int differ = 0;
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
        for (const auto& [x, y] :
             {std::pair{a.bodies[i].velocity.x, b.bodies[i].velocity.x},
              std::pair{a.bodies[i].velocity.y, b.bodies[i].velocity.y},
              std::pair{a.bodies[i].angle, b.bodies[i].angle},
              std::pair{a.bodies[i].angular_velocity, b.bodies[i].angular_velocity}}) {
            CHECK(bits(x) == bits(y));
        }
        CHECK(a.bodies[i].position == c.bodies[i].position);
        differ += a.bodies[i].velocity != c.bodies[i].velocity ? 1 : 0;
        CHECK(impulse::length_squared(a.bodies[i].velocity) <= 25.0);
    }
    CHECK(differ == 50); // every gas body, none of the walls
    CHECK(a.sha256 == b.sha256);
    CHECK(a.sha256 != c.sha256);
}

TEST_CASE("a gas block goes after the listed bodies, which may be left out or all static",
          "[scene]") {
    SECTION("listed bodies first, then the walls, then the gas") {
        const Scene scene =
            parse_scene(gas_scene(five, R"("bodies": [{"name": "post", "static": true,
                                          "shape": {"circle": 0.05}, "position": [0.25, 0.25]},
                                         {"name": "ball", "shape": {"circle": 0.1},
                                          "position": [10, 10]}],)"),
                        test_file);
        REQUIRE(scene.bodies.size() == 11);
        CHECK(scene.listed_bodies == 2);
        CHECK(scene.bodies[0].name == "post");
        CHECK(scene.bodies[1].name == "ball");
        CHECK(scene.bodies[2].name == "wall-bottom");
        CHECK(scene.bodies[5].name == "wall-right");
        CHECK(scene.bodies[6].name == "gas-0");
        CHECK(scene.bodies[10].name == "gas-4");
    }
    SECTION("an empty bodies array") {
        CHECK(rejection(gas_scene(five, R"("bodies": [],)")).empty());
    }
    SECTION("names that only look like the gas's") {
        CHECK(rejection(gas_scene(five, R"("bodies": [
            {"name": "gas-5", "shape": {"circle": 0.1}, "position": [10, 0]},
            {"name": "gas-01", "shape": {"circle": 0.1}, "position": [20, 0]},
            {"name": "wall", "shape": {"circle": 0.1}, "position": [30, 0]}],)"))
                  .empty());
    }
    SECTION("a polygon off its centroid is recentred, with a warning") {
        const Scene scene = parse_scene(
            gas_scene(R"("count": 1, "shape": {"polygon": [[0, 0], [0.2, 0], [0.2, 0.2], [0, 0.2]]},
                         "spacing": 1, "max_speed": 0)"),
            test_file);
        REQUIRE(scene.warnings.size() == 1);
        CHECK(scene.warnings[0].rfind(test_file + ": gas.shape.polygon: centroid is at (0.1, 0.1)",
                                      0) == 0);
        CHECK(scene.bodies[4].shape.polygon.vertices[0] == Vec2{-0.1, -0.1});
        CHECK(scene.bodies[4].position == Vec2{0.0, 0.0}); // one site, at the centre
    }
}

TEST_CASE("rejected gas blocks", "[scene]") {
    SECTION("not an object") {
        require_rejected(R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01,
                             "duration": 1, "gas": 5})",
                         "gas", "must be an object, got 5");
    }
    SECTION("an unknown key") {
        require_rejected(gas_scene(five + R"(, "colour": "red")"), "gas.colour", "unknown key");
    }
    SECTION("a typo of a key") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacng": 0.5,
                                      "max_speed": 5)"),
                         "gas.spacng", "unknown key (did you mean spacing?)");
    }
    SECTION("count missing") {
        require_rejected(gas_scene(R"("shape": {"circle": 0.1}, "spacing": 0.5, "max_speed": 5)"),
                         "gas.count", "is required but missing");
    }
    SECTION("count 0") {
        require_rejected(gas_scene(R"("count": 0, "shape": {"circle": 0.1}, "spacing": 0.5,
                                      "max_speed": 5)"),
                         "gas.count", "must be a whole number from 1 to 100000, got 0");
    }
    SECTION("count 1.5") {
        require_rejected(gas_scene(R"("count": 1.5, "shape": {"circle": 0.1}, "spacing": 0.5,
                                      "max_speed": 5)"),
                         "gas.count", "must be a whole number from 1 to 100000, got 1.5");
    }
    SECTION("count above 100000") {
        require_rejected(gas_scene(R"("count": 100001, "shape": {"circle": 0.1}, "spacing": 0.5,
                                      "max_speed": 5)"),
                         "gas.count", "got 100001");
    }
    SECTION("count a string") {
        require_rejected(gas_scene(R"("count": "5", "shape": {"circle": 0.1}, "spacing": 0.5,
                                      "max_speed": 5)"),
                         "gas.count", "must be a number");
    }
    SECTION("shape missing") {
        require_rejected(gas_scene(R"("count": 5, "spacing": 0.5, "max_speed": 5)"), "gas.shape",
                         "is required but missing");
    }
    SECTION("a bad shape") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": -0.1}, "spacing": 0.5,
                                      "max_speed": 5)"),
                         "gas.shape.circle", "must be > 0");
    }
    SECTION("mass and density together") {
        require_rejected(gas_scene(five + R"(, "density": 2)"), "gas.density",
                         "give mass or density, not both");
    }
    SECTION("mass negative") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "mass": -1,
                                      "spacing": 0.5, "max_speed": 5)"),
                         "gas.mass", "must be > 0, got -1");
    }
    SECTION("spacing missing") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "max_speed": 5)"),
                         "gas.spacing", "is required but missing");
    }
    SECTION("spacing zero") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacing": 0,
                                      "max_speed": 5)"),
                         "gas.spacing", "must be > 0, got 0");
    }
    SECTION("spacing equal to a disc's diameter") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacing": 0.2,
                                      "max_speed": 5)"),
                         "gas.spacing",
                         "must be more than the shape's bounding diameter 0.2 m (twice its "
                         "furthest point from the centroid), so that no two bodies overlap at any "
                         "angle, got 0.2");
    }
    SECTION("spacing enough for a box side by side but not turned") {
        // Box [0.1, 0.1]: corners sqrt(0.02) from the centre, diameter 0.2828...
        require_rejected(gas_scene(R"("count": 5, "shape": {"box": [0.1, 0.1]}, "spacing": 0.25,
                                      "max_speed": 5)"),
                         "gas.spacing", "bounding diameter 0.28284271247461906 m");
    }
    SECTION("spacing so large the room is not finite") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacing": 1e308,
                                      "max_speed": 5)"),
                         "gas.spacing", "gives a room inf m wide; it must be finite");
    }
    SECTION("walls so thick the room is not finite") {
        require_rejected(gas_scene(five + R"(, "wall_thickness": 1e308)"), "gas.wall_thickness",
                         "it must be finite");
    }
    SECTION("max_speed missing") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacing": 0.5)"),
                         "gas.max_speed", "is required but missing");
    }
    SECTION("max_speed negative") {
        require_rejected(gas_scene(R"("count": 5, "shape": {"circle": 0.1}, "spacing": 0.5,
                                      "max_speed": -1)"),
                         "gas.max_speed", "must be >= 0, got -1");
    }
    SECTION("max_angular_speed negative") {
        require_rejected(gas_scene(five + R"(, "max_angular_speed": -0.5)"),
                         "gas.max_angular_speed", "must be >= 0, got -0.5");
    }
    SECTION("random_angles not a bool") {
        require_rejected(gas_scene(five + R"(, "random_angles": 1)"), "gas.random_angles",
                         "must be true or false, got 1");
    }
    SECTION("seed negative") {
        require_rejected(gas_scene(five + R"(, "seed": -1)"), "gas.seed",
                         "must be a whole number from 0 to 9007199254740992, got -1");
    }
    SECTION("seed fractional") {
        require_rejected(gas_scene(five + R"(, "seed": 0.5)"), "gas.seed", "got 0.5");
    }
    SECTION("seed above 2^53") {
        require_rejected(gas_scene(five + R"(, "seed": 18014398509481984)"), "gas.seed",
                         "must be a whole number from 0 to 9007199254740992");
    }
    SECTION("wall_thickness zero") {
        require_rejected(gas_scene(five + R"(, "wall_thickness": 0)"), "gas.wall_thickness",
                         "must be > 0, got 0");
    }
    SECTION("a listed body takes a wall's name") {
        require_rejected(gas_scene(five, R"("bodies": [{"name": "wall-left",
                                                      "shape": {"circle": 0.1},
                                                      "position": [10, 0]}],)"),
                         "gas",
                         "makes a body named \"wall-left\", which is already the name of "
                         "bodies[0]; body names must be unique");
    }
    SECTION("a listed body takes a gas body's name") {
        require_rejected(gas_scene(five, R"("bodies": [{"name": "ball", "shape": {"circle": 0.1},
                                                      "position": [10, 0]},
                                                     {"name": "gas-4", "shape": {"circle": 0.1},
                                                      "position": [20, 0]}],)"),
                         "gas", "\"gas-4\", which is already the name of bodies[1]");
    }
    SECTION("a listed body inside the room, overlapping a gas body") {
        // gas-4 (scene body 1 + 4 + 4 = 9) at the origin, the ball 0.1 above it:
        // gap 0.1 - 0.1 - 0.1.
        require_rejected(gas_scene(five, R"("bodies": [{"name": "ball", "shape": {"circle": 0.1},
                                                      "position": [0, 0.1]}],)"),
                         "gas", "'gas-4' overlaps bodies[0] 'ball' at t = 0 by 0.1 m");
    }
    SECTION("a listed body in a wall") {
        require_rejected(gas_scene(five, R"("bodies": [{"name": "ball", "shape": {"circle": 0.1},
                                                      "position": [0, 1.25]}],)"),
                         "gas", "'wall-top' overlaps bodies[0] 'ball' at t = 0 by");
    }
    SECTION("neither bodies nor gas") {
        require_rejected(R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.01, "duration": 1})",
                         "bodies",
                         "is required but missing; a scene lists its bodies, has a gas "
                         "block, or both");
    }
}

// Whatever a value of the gas block is replaced with, only InputError escapes.
TEST_CASE("only InputError escapes from the gas block", "[scene]") {
    const std::string base =
        gas_scene(R"("count": 7, "shape": {"polygon": [[-0.1, -0.1], [0.1, -0.1], [0, 0.1]]},
                     "density": 2, "spacing": 0.5, "max_speed": 5, "max_angular_speed": 1,
                     "random_angles": true, "seed": 12, "wall_thickness": 0.5)");
    REQUIRE(rejection(base).empty());
    const std::vector<nlohmann::json> replacements = {nullptr,
                                                      true,
                                                      false,
                                                      0,
                                                      -1,
                                                      2.5,
                                                      1e308,
                                                      "text",
                                                      nlohmann::json::array(),
                                                      nlohmann::json::array({1, 2}),
                                                      nlohmann::json::object()};
    const nlohmann::json document = nlohmann::json::parse(base);
    require_only_input_errors(document, {"/gas"}, replacements);
}

// ---------------------------------------------------------------- the scale scenes

TEST_CASE("the gas scenes load with local stepping and their expectations", "[scene]") {
    const std::string dir = std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes/";
    using Kind = impulse::harness::Expectation::Kind;
    for (const std::string kind : {"circles", "boxes"}) {
        for (const int count : {10, 100, 1000, 10000}) {
            const std::string name = "gas-" + kind + "-" + std::to_string(count);
            INFO(name);
            const Scene scene = load_scene(dir + "scale/" + name + ".json");
            CHECK(scene.name == name);
            CHECK(scene.bodies.size() == static_cast<std::size_t>(count) + 4);
            CHECK(scene.bodies.back().name == "gas-" + std::to_string(count - 1));
            CHECK(scene.solver.stepping == impulse::Stepping::local);
            CHECK(scene.solver.integrator == Integrator::symplectic_euler);
            CHECK(scene.solver.toi == impulse::TimeOfImpactMethod::secant);
            CHECK(scene.gravity == Vec2{0.0, 0.0});
            CHECK(scene.restitution == 1.0);
            CHECK(scene.duration == 2.0);
            CHECK(scene.dt == 1.0 / 60.0);
            CHECK(scene.gas->random_angles == (kind == "boxes"));
            REQUIRE(scene.expectations.size() == 2);
            CHECK(scene.expectations[0].kind == Kind::conserved);
            CHECK(scene.expectations[0].rtol == 1e-9);
            CHECK(scene.expectations[1].kind == Kind::momentum_balance);
            CHECK(scene.expectations[1].rtol == 1e-9);
        }
        const Scene canonical = load_scene(dir + "gas-" + kind + ".json");
        CHECK(canonical.bodies.size() == 14);
        CHECK(canonical.duration == 3.0);
        CHECK(canonical.solver.stepping == impulse::Stepping::local);
        CHECK(canonical.expectations.size() == 2);
    }
}

TEST_CASE("momentum-balance is read, and refused under gravity", "[scene]") {
    const Scene scene =
        parse_scene(gas_scene(five, R"("expectations": [{"kind": "momentum-balance", "rtol": 1e-9,
                                             "description": "walls"}],)"),
                    test_file);
    REQUIRE(scene.expectations.size() == 1);
    CHECK(scene.expectations[0].kind == impulse::harness::Expectation::Kind::momentum_balance);
    CHECK(scene.expectations[0].description == "walls");
    require_rejected(expecting(R"([{"kind": "momentum-balance", "rtol": 1e-9}])"),
                     "expectations[0]",
                     "momentum-balance needs zero gravity, but the scene's gravity is (0, -9.81); "
                     "gravity would add m g t to the momentum");
    require_rejected(gas_scene(five, R"("expectations": [{"kind": "momentum-balance",
                                                          "rtol": 1e-9, "body": "gas-0"}],)"),
                     "expectations[0].body", "unknown key");
}
