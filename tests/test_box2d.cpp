// The Box2D adapter (harness/simulate/box2d_simulator.cpp): the fairness settings of
// docs/physics.md ("Box2D, the second reference") checked by their physical
// consequences, the exact answers Box2D should reach within its own errors,
// refused shapes, clamp warnings, collision events and determinism.
#ifdef IMPULSE_WITH_BOX2D

#include "box2d_simulator.h"
#include "input_error.h"
#include "record.h"
#include "scene.h"
#include "simulator.h"
#include "trajectory.h"

#include <box2d/box2d.h>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

using impulse::harness::box2d_version;
using impulse::harness::InputError;
using impulse::harness::make_box2d_simulator;
using impulse::harness::parse_scene;
using impulse::harness::record;
using impulse::harness::Scene;
using impulse::harness::Trajectory;
using impulse::harness::TrajectoryEvent;

namespace {

constexpr double g = 9.81;
constexpr double dt60 = 1.0 / 60.0;
const double pi = std::acos(-1.0);
// How far Box2D lets resting contacts sink into the skin before its position
// solver pushes back: b2_linearSlop.
const double slop = static_cast<double>(b2_linearSlop);

std::string number(double value) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

// A scene from its variable parts; `bodies` is the JSON array's content.
std::string scene_text(double restitution, double dt, double duration, const std::string& gravity,
                       const std::string& bodies) {
    return R"({"schema": "impulse/scene@1", "name": "t", "restitution": )" + number(restitution) +
           R"(, "dt": )" + number(dt) + R"(, "duration": )" + number(duration) +
           R"(, "gravity": )" + gravity + R"(, "bodies": [)" + bodies + "]}";
}

const std::string ground =
    R"({"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]})";

// A body of mass 1 named `name` with the given shape and centre height, plus
// any `extra` fields (each preceded by a comma).
std::string body(const std::string& name, const std::string& shape, double x, double y,
                 const std::string& extra = "") {
    return R"({"name": ")" + name + R"(", "shape": )" + shape + R"(, "mass": 1, "position": [)" +
           number(x) + ", " + number(y) + "]" + extra + "}";
}

Scene on_ground(double restitution, double duration, const std::string& falling) {
    return parse_scene(
        scene_text(restitution, dt60, duration, "[0, -9.81]", ground + ", " + falling),
        "test.json");
}

Trajectory run(const Scene& scene) {
    std::vector<std::string> warnings;
    const auto simulator = make_box2d_simulator(scene, warnings);
    return record(*simulator, scene);
}

// Columns of the first dynamic body: t, x, y, angle, vx, vy, omega.
enum Column { t_col, x_col, y_col, angle_col, vx_col, vy_col, omega_col };

double at(const std::vector<double>& frame, Column column, int body = 0) {
    return column == t_col ? frame[0] : frame[static_cast<std::size_t>(6 * body + column)];
}

// The frame at the end of the step an event was resolved in.
const std::vector<double>& frame_after(const Trajectory& trajectory, const TrajectoryEvent& event,
                                       double dt) {
    return trajectory.frames[static_cast<std::size_t>(std::llround(event.t / dt))];
}

std::string rejection(const Scene& scene) {
    std::vector<std::string> warnings;
    try {
        make_box2d_simulator(scene, warnings);
    } catch (const InputError& error) {
        return error.what();
    }
    return "";
}

std::string regular_polygon(int count, double radius) {
    std::string points;
    for (int k = 0; k < count; ++k) {
        // Start half an edge below the x axis so that one edge lies flat at the bottom.
        const double angle = -pi / 2.0 + (2.0 * k + 1.0) * pi / count;
        points += (k ? ", [" : "[") + number(radius * std::cos(angle)) + ", " +
                  number(radius * std::sin(angle)) + "]";
    }
    return R"({"polygon": [)" + points + "]}";
}

} // namespace

TEST_CASE("Box2D reports its version and every fairness setting", "[box2d]") {
    const Scene scene = on_ground(0.8, 1.0, body("ball", R"({"circle": 0.5})", 0, 2));
    std::vector<std::string> warnings;
    const auto simulator = make_box2d_simulator(scene, warnings);
    CHECK(simulator->engine() == box2d_version());
    CHECK(box2d_version() == "box2d 2.4.1");

    std::vector<std::string> keys;
    for (const auto& [key, value] : simulator->settings()) {
        keys.push_back(key);
    }
    CHECK(keys == std::vector<std::string>{"dt", "substeps", "velocity_iterations",
                                           "position_iterations", "friction", "restitution",
                                           "restitution_threshold", "sleeping", "damping", "skin",
                                           "continuous", "precision"});
    const auto settings = simulator->settings();
    CHECK(settings[4].second == "0");
    CHECK(settings[5].second == "0.8");
    CHECK(settings[6].second == "0");
    CHECK(settings[7].second == "false");
    CHECK(std::stod(settings[9].second) == static_cast<double>(b2_polygonRadius));
    CHECK(settings[11].second == "\"single\"");
}

// Where a body comes to rest on the ground with e = 0, its centre `height`
// above the surface when the true surfaces touch. Box2D finds a contact only
// after the step that crossed into it and pushes back only the overlap beyond
// b2_linearSlop, so a corrected body rests in [height - slop, height]; with the
// skin uncorrected it would rest in [height + 0.005, height + 0.01].
void check_rests_on_true_surface(const std::string& shape, double height, double gap) {
    const Trajectory t = run(on_ground(0.0, 2.0, body("body", shape, 0, height + gap)));
    const auto& last = t.frames.back();
    INFO(shape << " from " << gap << " m above: rests at " << at(last, y_col));
    CHECK(at(last, y_col) <= height + 1e-6);
    CHECK(at(last, y_col) >= height - slop - 1e-6);
    CHECK(std::fabs(at(last, vy_col)) < 1e-3);
    CHECK(std::fabs(at(last, angle_col)) < 1e-4); // single precision: no tipping over
}

TEST_CASE("Box2D: the skin is corrected, bodies rest on the true surface", "[box2d]") {
    const double hex_radius = 0.5;
    const double apothem = hex_radius * std::cos(pi / 6.0);
    for (const double gap : {0.0, 0.002, 0.05}) {
        check_rests_on_true_surface(R"({"box": [0.5, 0.5]})", 0.5, gap);
        // Not an axis-aligned box: shrunk edge by edge and built with Set.
        check_rests_on_true_surface(regular_polygon(6, hex_radius), apothem, gap);
        // No skin on circles: the radius is the surface.
        check_rests_on_true_surface(R"({"circle": 0.5})", 0.5, gap);
    }
    // A unit box placed touching stays exactly there: the skin neither lifts it
    // nor lets it sink.
    const Trajectory t = run(on_ground(0.0, 1.0, body("box", R"({"box": [0.5, 0.5]})", 0, 0.5)));
    CHECK(std::fabs(at(t.frames.back(), y_col) - 0.5) < 1e-6);
}

TEST_CASE("Box2D: friction 0, a sliding box keeps its speed", "[box2d]") {
    const Trajectory t = run(on_ground(
        0.0, 1.0, body("box", R"({"box": [0.5, 0.5]})", 0, 0.5, R"(, "velocity": [2, 0])")));
    CHECK(std::fabs(at(t.frames.back(), vx_col) - 2.0) < 1e-5);
    CHECK(std::fabs(at(t.frames.back(), x_col) - 2.0) < 1e-4);
}

TEST_CASE("Box2D: no sleeping", "[box2d]") {
    SECTION("a body drifting below Box2D's sleep tolerance keeps drifting") {
        // 5 mm/s is under b2_linearSleepTolerance (1 cm/s): with sleeping on,
        // Box2D would stop it after b2_timeToSleep (0.5 s) at x = 0.0025.
        const Scene scene = parse_scene(
            scene_text(1.0, dt60, 5.0, "[0, 0]",
                       body("drifter", R"({"circle": 0.5})", 0, 0, R"(, "velocity": [0.005, 0])")),
            "test.json");
        const Trajectory t = run(scene);
        CHECK(std::fabs(at(t.frames.back(), x_col) - 0.025) < 1e-6);
        CHECK(at(t.frames.back(), vx_col) == Approx(0.005).epsilon(1e-6));
    }
    SECTION("a body resting on the ground is stepped and reported every frame") {
        const Scene scene = on_ground(0.0, 5.0, body("box", R"({"box": [0.5, 0.5]})", 0, 0.5));
        const Trajectory t = run(scene);
        REQUIRE(t.frames.size() == 301);
        for (const auto& frame : t.frames) {
            CHECK(std::fabs(at(frame, vy_col)) < 1e-3);
        }
        CHECK(at(t.frames.back(), t_col) == Approx(5.0));
    }
}

TEST_CASE("Box2D: restitution threshold 0, slow impacts still bounce", "[box2d]") {
    // Dropped 2 cm: impact speed sqrt(2 g h) = 0.63 m/s, under Box2D's default
    // threshold of 1 m/s, below which it would stop the ball dead (vy = 0).
    const double h0 = 0.02;
    const double e = 0.8;
    const double impact = std::sqrt(2.0 * g * h0);
    Scene scene = on_ground(e, 0.2, body("ball", R"({"circle": 0.5})", 0, 0.5 + h0));

    SECTION("at 60 Hz it bounces") {
        const Trajectory t = run(scene);
        REQUIRE_FALSE(t.events.empty());
        CHECK(at(frame_after(t, t.events[0], dt60), vy_col) > 0.0);
    }
    SECTION("at 600 Hz it bounces at e times the impact speed") {
        // At 60 Hz the gravity kick Box2D adds before it applies restitution,
        // g dt = 0.16 m/s, is a quarter of this impact speed; 10 sub-steps
        // make it small, so the bounce shows e itself.
        scene.box2d.substeps = 10;
        const Trajectory t = run(scene);
        REQUIRE_FALSE(t.events.empty());
        CHECK(at(frame_after(t, t.events[0], dt60), vy_col) == Approx(e * impact).epsilon(0.10));
    }
}

TEST_CASE("Box2D: a drop hits at sqrt(2 h0 / g) and rebounds at e times the impact speed",
          "[box2d]") {
    const double h0 = 1.0;
    const double e = 0.8;
    const Trajectory t = run(on_ground(
        e, 1.0, body("box", R"({"box": [0.5, 0.5]})", 0, 0.5 + h0, R"(, "rotation": false)")));
    REQUIRE_FALSE(t.events.empty());
    const TrajectoryEvent& hit = t.events[0];
    const double t_exact = std::sqrt(2.0 * h0 / g);
    // The event is stamped at the end of the step that resolves it. Box2D
    // finds the overlap at the start of that step, within half a step of the
    // exact time (its symplectic Euler falls about half a step ahead), so the
    // stamp is h/2 to 3h/2 late in general: 0.91 h for this drop.
    CHECK(std::fabs(hit.t - t_exact) <= dt60);
    CHECK(std::fabs(hit.t - dt60 - t_exact) <= 0.5 * dt60);

    // Box2D applies restitution after the step's gravity kick, so it rebounds
    // faster than e v by e g dt: g dt / v = 3.7% here at 60 Hz.
    const double impact = std::sqrt(2.0 * g * h0);
    CHECK(at(frame_after(t, hit, dt60), vy_col) == Approx(e * impact).epsilon(0.05));
}

TEST_CASE("Box2D: head-on hit of two discs in zero gravity", "[box2d]") {
    const double ma = 1000.0;
    const double mb = 1.0;
    const double va = 1.0;
    const double vb = -5.0;
    const double e = 0.9;
    const Scene scene = parse_scene(
        scene_text(
            e, dt60, 1.5, "[0, 0]",
            R"({"name": "heavy", "shape": {"circle": 0.5}, "mass": 1000, "position": [-2, 0], "velocity": [1, 0]},
                      {"name": "light", "shape": {"circle": 0.5}, "mass": 1, "position": [2, 0], "velocity": [-5, 0]})"),
        "test.json");
    const Trajectory t = run(scene);
    REQUIRE(t.events.size() == 1);

    // Single precision: momentum holds to float rounding, not to 1e-12.
    const double p0 = ma * va + mb * vb;
    for (const auto& frame : t.frames) {
        const double p = ma * at(frame, vx_col, 0) + mb * at(frame, vx_col, 1);
        CHECK(std::fabs(p - p0) <= 1e-5 * std::fabs(p0));
    }
    const double va_after = (ma * va + mb * vb - mb * e * (va - vb)) / (ma + mb);
    const double vb_after = (ma * va + mb * vb + ma * e * (va - vb)) / (ma + mb);
    CHECK(std::fabs(at(t.frames.back(), vx_col, 0) - va_after) < 1e-3);
    CHECK(std::fabs(at(t.frames.back(), vx_col, 1) - vb_after) < 1e-3);

    // The pair convention: both dynamic, so a is the lower index, and the
    // normal points toward it (to the left).
    const TrajectoryEvent& hit = t.events[0];
    CHECK(hit.a == "heavy");
    CHECK(hit.b == "light");
    CHECK(hit.normal[0] == Approx(-1.0));
    CHECK(hit.vn_before == Approx(vb - va).epsilon(1e-5));
    CHECK(hit.vn_after == Approx(-e * (vb - va)).epsilon(1e-5));
}

TEST_CASE("Box2D refuses a polygon of more than 8 vertices", "[box2d]") {
    const Scene scene = on_ground(0.5, 1.0, body("nonagon", regular_polygon(9, 0.5), 0, 2));
    const std::string message = rejection(scene);
    CHECK(message.find("test.json: bodies[1].shape: ") == 0);
    CHECK(message.find("at most 8") != std::string::npos);
    CHECK(message.find("has 9") != std::string::npos);
    CHECK(rejection(on_ground(0.5, 1.0, body("octagon", regular_polygon(8, 0.5), 0, 2))).empty());
}

TEST_CASE("Box2D refuses a polygon too small to shrink by the skin", "[box2d]") {
    const Scene scene = on_ground(0.5, 1.0, body("crumb", regular_polygon(3, 0.012), 0, 2));
    const std::string message = rejection(scene);
    CHECK(message.find("test.json: bodies[1].shape: too small for Box2D") == 0);
}

TEST_CASE("Box2D warns about speeds its per-step clamp would cut", "[box2d]") {
    const Scene scene = parse_scene(
        scene_text(1.0, dt60, 1.0, "[0, -9.81]",
                   body("bullet", R"({"circle": 0.1})", 0, 0, R"(, "velocity": [300, 0])") + ", " +
                       body("snail", R"({"circle": 0.1})", 0, 5, R"(, "velocity": [1, 0])") + ", " +
                       body("top", R"({"circle": 0.1})", 0, 10, R"(, "angular_velocity": 200)")),
        "test.json");
    std::vector<std::string> warnings;
    make_box2d_simulator(scene, warnings);
    REQUIRE(warnings.size() == 2);
    // 300 m/s at 1/60 s is 5 m per step, over b2_maxTranslation = 2 m.
    CHECK(warnings[0].find("bodies[0] 'bullet'") == 0);
    CHECK(warnings[0].find("b2_maxTranslation") != std::string::npos);
    // 200 rad/s at 1/60 s is 3.3 rad per step, over b2_maxRotation = pi/2.
    CHECK(warnings[1].find("bodies[2] 'top'") == 0);
    CHECK(warnings[1].find("b2_maxRotation") != std::string::npos);
}

TEST_CASE("Box2D events: a body hitting the ground", "[box2d]") {
    const Trajectory t = run(on_ground(0.5, 1.0, body("box", R"({"box": [0.5, 0.5]})", 0.25, 1.5)));
    REQUIRE_FALSE(t.events.empty());
    const TrajectoryEvent& hit = t.events[0];
    // The dynamic body is a; the normal points toward it, up out of the ground.
    CHECK(hit.a == "box");
    CHECK(hit.b == "ground");
    CHECK(hit.normal[0] == Approx(0.0).margin(1e-6));
    CHECK(hit.normal[1] == Approx(1.0));
    // The mean of the two manifold points: under the centre, on the surface
    // (within the step's overlap).
    CHECK(hit.point[0] == Approx(0.25).margin(1e-5));
    CHECK(std::fabs(hit.point[1]) < 0.1);
    CHECK(hit.vn_before < 0.0);
    CHECK(hit.impulse > 0.0);
    CHECK(hit.vn_after > 0.0);
    // The impulse is what changed the box's momentum (mass 1) in that step,
    // less the step's gravity.
    const auto& after = frame_after(t, hit, dt60);
    const auto& before = t.frames[static_cast<std::size_t>(std::llround(hit.t / dt60)) - 1];
    CHECK(hit.impulse == Approx(at(after, vy_col) - at(before, vy_col) + g * dt60).epsilon(1e-4));
    // Events are stamped at step ends.
    CHECK(hit.t / dt60 == Approx(std::round(hit.t / dt60)).margin(1e-9));
}

TEST_CASE("Box2D events are stamped at the end of the sub-step", "[box2d]") {
    Scene scene = on_ground(0.5, 1.0, body("ball", R"({"circle": 0.5})", 0, 1.5));
    scene.box2d.substeps = 4;
    const Trajectory t = run(scene);
    REQUIRE_FALSE(t.events.empty());
    const double sub = dt60 / 4.0;
    const double k = t.events[0].t / sub;
    CHECK(k == Approx(std::round(k)).margin(1e-6));
    CHECK(std::fabs(t.events[0].t - std::sqrt(2.0 / g)) <= 1.5 * sub);
}

TEST_CASE("Box2D runs the same scene identically twice", "[box2d]") {
    const std::string bodies =
        ground + ", " +
        body("box", R"({"box": [0.5, 0.3]})", 0, 2, R"(, "angle": 0.4, "angular_velocity": 1)") +
        ", " + body("ball", R"({"circle": 0.3})", 0.4, 3.5, R"(, "velocity": [-0.5, 0])");
    const Scene scene = parse_scene(scene_text(0.6, dt60, 3.0, "[0, -9.81]", bodies), "test.json");
    const Trajectory first = run(scene);
    const Trajectory second = run(scene);
    CHECK(first.frames == second.frames);
    REQUIRE(first.events.size() == second.events.size());
    CHECK_FALSE(first.events.empty());
    CHECK(impulse::harness::digest_of(first) == impulse::harness::digest_of(second));
}

#endif // IMPULSE_WITH_BOX2D
