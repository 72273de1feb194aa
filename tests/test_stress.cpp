// Extremes (issue 7; harness/study/stress.h): the stress matrix holds, every
// invariant checker catches a violation made by hand, the NaN guard names
// what overflowed, a scene that would tunnel is refused before it runs, and
// the per-collision energy bound the matrix uses is what rounding gives.
#include "cli.h"
#include "exact_answers.h"
#include "input_error.h"
#include "number_format.h"
#include "record.h"
#include "restitution.h"
#include "run.h"
#include "simulator.h"
#include "stress.h"
#include "support.h"
#include "support/stress_rows.h"

#include <catch2/catch.hpp>
#include <cfloat>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace impulse;
using namespace impulse::harness;
using impulse::test::passes;
using impulse::test::row_of;
using impulse::test::states_of;

namespace {

Scene scene_with(const std::string& top, const std::string& bodies, double dt = 0.1,
                 double duration = 1.0) {
    return parse_scene(R"({"schema": "impulse/scene@1", "name": "t", "dt": )" + format_double(dt) +
                           R"(, "duration": )" + format_double(duration) + ", " + top +
                           R"(, "bodies": [)" + bodies + "]}",
                       "test.json");
}

// Two 0.5 m discs 4 m apart closing at 2 m/s in free space, e = 1.
Scene free_pair() {
    return scene_with(
        R"("gravity": [0, 0])",
        R"({"name": "a", "shape": {"circle": 0.5}, "mass": 2, "position": [-2, 0], "velocity": [1, 0]},
                         {"name": "b", "shape": {"circle": 0.5}, "mass": 1, "position": [2, 0], "velocity": [-1, 0]})");
}

// A 0.5 m disc 1 m above static ground, e = 0.5, under gravity.
Scene drop() {
    return scene_with(
        R"("restitution": 0.5, "solver": {"integrator": "verlet"})",
        R"({"name": "ground", "static": true, "shape": {"box": [5, 0.5]}, "position": [0, -0.5]},
                         {"name": "ball", "shape": {"circle": 0.5}, "mass": 1, "position": [0, 1.5]})");
}

TrajectoryEvent event_between(const std::string& a, const std::string& b, double t,
                              double vn_after) {
    TrajectoryEvent e;
    e.t = t;
    e.a = a;
    e.b = b;
    e.vn_after = vn_after;
    return e;
}

std::string message_of(const Scene& scene) {
    try {
        run_scene(scene);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST_CASE("every case of the stress matrix holds or is refused as expected", "[unit][stress]") {
    const std::vector<StressCase> cases = stress_cases();
    REQUIRE(cases.size() >= 20);
    int refused = 0;
    for (const StressCase& c : cases) {
        if (c.slow) {
            continue; // impulse stress runs it, under the stress label
        }
        const StressResult r = run_stress_case(c);
        INFO(c.name << ": " << c.description);
        INFO("refusal: " << r.refusal << "; stopped: " << r.stopped);
        for (const StressRow& row : r.rows) {
            INFO(row.invariant << " worst " << row.worst << " bound " << row.bound << " ("
                               << row.detail << ")");
            CHECK(row.passed);
        }
        CHECK(r.passed());
        CHECK(r.stopped.empty());
        if (r.expected_refusal) {
            ++refused;
            CHECK(r.rows.empty());
        } else {
            CHECK(r.refusal.empty());
            CHECK(r.steps == step_count(c.scene));
        }
    }
    // The 1000 m/s disc without ccd, and only it.
    CHECK(refused == 1);
}

TEST_CASE("the stress checkers catch a violation made by hand", "[unit][stress]") {
    SECTION("a NaN or an infinity, named with its body, quantity and time") {
        const Scene scene = free_pair();
        StressMonitor monitor(scene, {});
        std::vector<BodyState> states = states_of(scene);
        monitor.observe(0.0, states);
        CHECK(passes(monitor, "finite"));
        states[1].velocity.y = std::numeric_limits<double>::quiet_NaN();
        monitor.observe(0.5, states);
        const StressRow row = row_of(monitor.rows(), "finite");
        CHECK_FALSE(row.passed);
        CHECK(row.detail == "'b'.vy is NaN at t = 0.5 s");
    }
    SECTION("an overlap deeper than the contact tolerance") {
        const Scene scene = free_pair();
        StressMonitor monitor(scene, {});
        std::vector<BodyState> states = states_of(scene);
        monitor.observe(0.0, states);
        // Touching is fine, and so is overlapping within the tolerance (1e-9 m).
        states[0].position = {-0.5, 0.0};
        states[1].position = {0.5, 0.0};
        monitor.observe(0.1, states);
        CHECK(passes(monitor, "interpenetration"));
        states[1].position = {0.5 - 0.5e-9, 0.0};
        monitor.observe(0.2, states);
        CHECK(passes(monitor, "interpenetration"));
        states[1].position = {0.5 - 3e-9, 0.0};
        monitor.observe(0.3, states);
        const StressRow row = row_of(monitor.rows(), "interpenetration");
        CHECK_FALSE(row.passed);
        CHECK(row.worst == Approx(3e-9).epsilon(1e-6));
        CHECK(row.detail == "'a' and 'b' at t = 0.3 s");
    }
    SECTION("a body that ends on the wrong side of another (tunnelled)") {
        const Scene scene = free_pair();
        StressChecks checks;
        checks.sides = {{1, 0, {1.0, 0.0}}};
        StressMonitor monitor(scene, checks);
        std::vector<BodyState> states = states_of(scene);
        monitor.observe(0.0, states);
        CHECK(passes(monitor, "side"));
        states[0].position = {3.0, 0.0}; // a passed b without touching
        monitor.observe(0.1, states);
        const StressRow row = row_of(monitor.rows(), "side");
        CHECK_FALSE(row.passed);
        CHECK(row.worst == -1.0);
    }
    SECTION("momentum and angular momentum that change in free space") {
        const Scene scene = free_pair();
        StressChecks checks;
        checks.momentum = true;
        checks.angular_momentum = true;
        StressMonitor monitor(scene, checks);
        std::vector<BodyState> states = states_of(scene);
        monitor.observe(0.0, states);
        // An exchange that conserves momentum: -2/3 and 4/3 m/s (e = 1).
        states[0].velocity = {-1.0 / 3.0, 0.0};
        states[1].velocity = {5.0 / 3.0, 0.0};
        monitor.observe(0.1, states);
        CHECK(passes(monitor, "momentum drift"));
        states[1].velocity.x *= 1.0 + 1e-9;
        states[1].angular_velocity = 1e-6; // spin from nowhere
        monitor.observe(0.2, states);
        CHECK_FALSE(passes(monitor, "momentum drift"));
        CHECK_FALSE(passes(monitor, "angular momentum drift"));
    }
    SECTION("energy gained, and energy lost at e = 1") {
        const Scene scene = free_pair();
        StressChecks checks;
        checks.energy_drift = true;
        StressMonitor monitor(scene, checks);
        std::vector<BodyState> states = states_of(scene);
        monitor.observe(0.0, states);
        states[0].velocity = {0.9, 0.0}; // lost 5% of a's energy: no gain, but a drift
        monitor.observe(0.1, states);
        CHECK(passes(monitor, "energy gain"));
        CHECK_FALSE(passes(monitor, "energy drift"));

        StressMonitor gaining(scene, checks);
        states = states_of(scene);
        gaining.observe(0.0, states);
        states[1].velocity = {-1.0 - 1e-10, 0.0};
        gaining.observe(0.1, states);
        const StressRow row = row_of(gaining.rows(), "energy gain");
        CHECK_FALSE(row.passed);
        // b's 0.5 J of the 1.5 J grows by 1e-10 J.
        CHECK(row.worst == Approx(1e-10 / 1.5).epsilon(1e-3));
    }
    SECTION("potential energy counts: a drop that rises higher than it fell") {
        const Scene scene = drop();
        StressMonitor monitor(scene, {});
        std::vector<BodyState> states = states_of(scene);
        monitor.observe(0.0, states);
        states[1].position.y = 1.0; // fell 0.5 m: m g h into speed
        states[1].velocity.y = -std::sqrt(2.0 * 9.81 * 0.5);
        monitor.observe(0.1, states);
        CHECK(passes(monitor, "energy gain"));
        states[1].position.y = 1.6; // above where it started, and still moving
        monitor.observe(0.2, states);
        CHECK_FALSE(passes(monitor, "energy gain"));
    }
    SECTION("a drop ladder off in time, in speed or in its count of impacts") {
        const Scene scene = drop();
        const DropLadder ladder{1.0, 9.81, 0.5};
        StressChecks checks;
        checks.drop = DropCheck{1, 2};
        const auto run = [&](double t_error, double v_error, int impacts) {
            StressMonitor monitor(scene, checks);
            monitor.observe(0.0, states_of(scene));
            for (int n = 1; n <= impacts; ++n) {
                monitor.observe(event_between("ball", "ground", ladder.impact_time(n) + t_error,
                                              ladder.rebound_speed(n) + v_error));
            }
            return monitor.rows();
        };
        CHECK(row_of(run(0.0, 0.0, 2), "drop ladder of 'ball': impact times").passed);
        CHECK(row_of(run(0.0, 0.0, 2), "drop ladder of 'ball': rebound speeds").passed);
        CHECK(row_of(run(-5e-13, 0.0, 2), "drop ladder of 'ball': impact times").passed);
        CHECK_FALSE(row_of(run(1e-9, 0.0, 2), "drop ladder of 'ball': impact times").passed);
        CHECK_FALSE(row_of(run(0.0, 1e-8, 2), "drop ladder of 'ball': rebound speeds").passed);
        const StressRow missing = row_of(run(0.0, 0.0, 1), "drop ladder of 'ball': impact times");
        CHECK_FALSE(missing.passed);
        CHECK(missing.detail == "1 impacts, expected 2");
    }
    SECTION("head-on velocities off the 1D formula") {
        const Scene scene = free_pair();
        StressChecks checks;
        checks.head_on = HeadOnCheck{0, 1};
        const auto run = [&](double error) {
            StressMonitor monitor(scene, checks);
            std::vector<BodyState> states = states_of(scene);
            monitor.observe(0.0, states);
            monitor.observe(event_between("a", "b", 1.5, 2.0));
            // docs/physics.md, e = 1, masses 2 and 1 at +1 and -1: -1/3 and 5/3.
            states[0].velocity = {-1.0 / 3.0 + error, 0.0};
            states[1].velocity = {5.0 / 3.0, 0.0};
            monitor.observe(3.0, states);
            return row_of(monitor.rows(), "head-on velocities").passed;
        };
        CHECK(run(0.0));
        CHECK_FALSE(run(1e-9));
        StressMonitor never(scene, checks);
        never.observe(0.0, states_of(scene));
        CHECK_FALSE(passes(never, "head-on velocities"));
    }
}

TEST_CASE("the NaN guard names the body, the quantity and the time", "[unit][stress]") {
    SECTION("a NaN: 1e308 m/s up against 1e308 m/s^2 down over a 2 s step") {
        // Verlet's h v + h^2 g / 2 is 2e308 - 2e308: inf - inf.
        const Scene scene = scene_with(
            R"("gravity": [0, -1e308], "solver": {"integrator": "verlet"})",
            R"({"name": "ball", "shape": {"circle": 0.5}, "mass": 1, "velocity": [0, 1e308]})", 2.0,
            4.0);
        CHECK(message_of(scene) ==
              "test.json: 'ball'.y became NaN at t = 2 s: the scene's numbers overflow double "
              "precision (its gravity, speeds, sizes, dt or duration are too large)");
    }
    SECTION("an infinity: a speed that passes the largest double") {
        const Scene scene =
            scene_with(R"("gravity": [0, -1e308], "solver": {"integrator": "euler"})",
                       R"({"name": "stone", "shape": {"circle": 0.5}, "mass": 1})", 1.0, 3.0);
        const std::string message = message_of(scene);
        CHECK(message.find("'stone'.vy became -inf at t = 2 s") != std::string::npos);
    }
    SECTION("a position past the largest double: 1e300 m/s for 1e10 s") {
        const Scene scene = scene_with(
            R"("gravity": [0, 0])",
            R"({"name": "ball", "shape": {"circle": 0.5}, "mass": 1, "velocity": [1e300, 0]})",
            1e10, 3e10);
        CHECK(message_of(scene).find("'ball'.x became +inf at t = 1e+10 s") != std::string::npos);
    }
}

TEST_CASE("a scene that would tunnel without ccd is refused before it runs", "[unit][stress]") {
    const auto bullet = [](double speed, double dt, bool ccd) {
        return scene_with(R"("gravity": [0, 0], "solver": {"ccd": )" +
                              std::string(ccd ? "true" : "false") + "}",
                          R"({"name": "wall", "static": true, "shape": {"box": [0.01, 1]}},
               {"name": "bullet", "shape": {"circle": 0.05}, "mass": 0.01, "position": [-10, 0], "velocity": [)" +
                              format_double(speed) + ", 0]}",
                          dt, 0.1);
    };
    const auto refusal = [](const Scene& scene) {
        const std::optional<TunnellingRefusal> r = tunnelling_refusal(scene);
        return r ? r->path + ": " + r->message : std::string();
    };
    // 1000 m/s at dt 1/30: 33 m per step against 0.02 + 0.1 m of thickness.
    const std::string message = refusal(bullet(1000.0, 1.0 / 30.0, false));
    CHECK(message ==
          "bodies[1]: 'bullet' and 'wall' close at up to 1000 m/s at t = 0: 33.33 m per step of "
          "dt = 0.03333 s, at least their combined thickness of 0.12 m, so one could pass "
          "through the other between two steps without either end of the step seeing them "
          "overlap (tunnelling); set \"ccd\": true in the solver block, or use dt below 0.00012 s");
    // Every verb refuses it (run_scene throws the sentence). Without the
    // refusal the seed's step does let it through: no collision, and the
    // disc ends on the far side of the wall.
    CHECK_THROWS_WITH(run_scene(bullet(1000.0, 1.0 / 30.0, false)), "test.json: " + message);
    const Scene fast = bullet(1000.0, 1.0 / 30.0, false);
    std::unique_ptr<Simulator> simulator = make_impulse_simulator(fast);
    const Trajectory tunnelled = record(*simulator, fast);
    CHECK(tunnelled.events.empty());
    CHECK(tunnelled.frames.back()[1] > 0.0);
    // With ccd it is not refused, and just inside the threshold it is not either.
    CHECK(refusal(bullet(1000.0, 1.0 / 30.0, true)).empty());
    CHECK(refusal(bullet(1000.0, 0.000119, false)).empty());
    CHECK_FALSE(refusal(bullet(1000.0, 0.000121, false)).empty());
    // A spin counts: a 2 x 0.02 m rod turning at 30 rad/s sweeps its tips at 30 m/s.
    const Scene rod = scene_with(R"("gravity": [0, 0])",
                                 R"({"name": "wall", "static": true, "shape": {"box": [0.01, 1]}},
           {"name": "rod", "shape": {"box": [1, 0.01]}, "mass": 1, "position": [-2, 0], "angular_velocity": 30})",
                                 0.01, 0.1);
    CHECK(refusal(rod).rfind("bodies[1]: 'rod' and 'wall' close at up to 30 m/s", 0) == 0);
    // Local stepping has no ccd: the cure it names is a smaller dt.
    CHECK(refusal(parse_scene(R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.1,
        "duration": 1, "gravity": [0, 0], "solver": {"stepping": "local"}, "bodies": [
        {"name": "wall", "static": true, "shape": {"box": [0.01, 1]}},
        {"name": "bullet", "shape": {"circle": 0.05}, "mass": 0.01, "position": [-10, 0], "velocity": [10, 0]}]})",
                              "test.json"))
              .find("use dt below 0.012 s (ccd needs \"stepping\": \"world\")") !=
          std::string::npos);
    // Every canonical scene passes at its own dt and at the sweep's coarsest, 1/30 s.
    int scenes = 0;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes")) {
        if (entry.path().extension() != ".json") {
            continue;
        }
        Scene scene = load_scene(entry.path().string());
        INFO(scene.name);
        CHECK(refusal(scene).empty());
        scene.dt = 1.0 / 30.0;
        CHECK(refusal(scene).empty());
        ++scenes;
    }
    CHECK(scenes >= 20);
    // The thickness of a shape is twice the inradius: a polygon's nearest edge.
    CHECK(inradius(make_box(1.0, 0.01)) == Approx(0.01));
    CHECK(inradius(make_circle(0.3)) == 0.3);
}

TEST_CASE("one collision at e = 1 changes energy by at most 32 epsilons", "[unit][stress]") {
    // The bound of the stress matrix's energy drift rows, measured: random
    // pairs (masses 1e-3 to 1e3 kg, sizes 0.05 to 50 m, lever arms within
    // the body, normals in every direction), both rotating, one rotating
    // against a static body, and neither rotating. 10 epsilons of the
    // kinetic energy is the largest here, 14 over 6 x 10^6 such collisions;
    // the bound doubles that.
    std::mt19937_64 rng(7);
    double worst = 0.0;
    for (int kind = 0; kind < 3; ++kind) {
        for (int i = 0; i < 100000; ++i) {
            const double ma = test::log_uniform(rng, 1e-3, 1e3);
            const double mb = test::log_uniform(rng, 1e-3, 1e3);
            const double sa = test::log_uniform(rng, 0.05, 50.0);
            const double sb = test::log_uniform(rng, 0.05, 50.0);
            Body a;
            Body b;
            a.inv_mass = 1.0 / ma;
            b.inv_mass = kind == 1 ? 0.0 : 1.0 / mb;
            a.inv_inertia = kind == 2 ? 0.0 : 6.0 / (ma * sa * sa);
            b.inv_inertia = kind == 0 ? 6.0 / (mb * sb * sb) : 0.0;
            const double turn = test::uniform(rng, 0.0, 6.283185307179586);
            const Vec2 n{std::cos(turn), std::sin(turn)};
            a.state.position = {test::uniform(rng, -10, 10), test::uniform(rng, -10, 10)};
            const double arm = test::uniform(rng, 0.0, 1.4 * sa);
            const double at = test::uniform(rng, 0.0, 6.283185307179586);
            const Vec2 p = a.state.position + Vec2{arm * std::cos(at), arm * std::sin(at)};
            b.state.position = p - test::uniform(rng, 0.0, 1.4 * sb) * n;
            a.state.velocity = {test::uniform(rng, -5, 5), test::uniform(rng, -5, 5)};
            a.state.angular_velocity = a.rotates() ? test::uniform(rng, -3, 3) : 0.0;
            if (!b.is_static()) {
                b.state.velocity = {test::uniform(rng, -5, 5), test::uniform(rng, -5, 5)};
                b.state.angular_velocity = b.rotates() ? test::uniform(rng, -3, 3) : 0.0;
            }
            if (relative_normal_velocity(a, b, p, n) >= 0.0) {
                continue;
            }
            const auto energy = [](const Body& body) {
                if (body.is_static()) {
                    return 0.0;
                }
                const double inertia = body.rotates() ? 1.0 / body.inv_inertia : 0.0;
                return 0.5 / body.inv_mass * dot(body.state.velocity, body.state.velocity) +
                       0.5 * inertia * body.state.angular_velocity * body.state.angular_velocity;
            };
            const double before = energy(a) + energy(b);
            resolve_collision(a, b, Contact{p, n, 0.0}, 1.0);
            const double after = energy(a) + energy(b);
            worst = std::max(worst, std::abs(after - before) / before / DBL_EPSILON);
        }
    }
    INFO("largest change: " << worst << " epsilons");
    CHECK(worst > 1.0); // the measurement measures something
    CHECK(worst <= energy_ulps_per_collision / 2.0);
}

TEST_CASE("impulse stress: list, choose, JSON, bad names", "[unit][stress]") {
    std::ostringstream out, err;
    REQUIRE(cli::stress_verb({"--list"}, out, err) == cli::exit_ok);
    CHECK(out.str().find("speed-1000") != std::string::npos);
    CHECK(out.str().find("long-room") != std::string::npos);

    std::ostringstream table;
    CHECK(cli::stress_verb({"--case", "speed-1000,corner-bisector"}, table, err) == cli::exit_ok);
    CHECK(table.str().find("refused: bodies[1]: 'disc' and 'wall' close at up to 1000 m/s") !=
          std::string::npos);
    CHECK(table.str().find("2 cases: 1 passed, 1 refused as expected, 0 failed") !=
          std::string::npos);

    std::ostringstream json;
    CHECK(cli::stress_verb({"--json", "--case", "mass-1e6-e1"}, json, err) == cli::exit_ok);
    const auto parsed = nlohmann::json::parse(json.str());
    CHECK(parsed["passed"] == true);
    CHECK(parsed["cases"][0]["name"] == "mass-1e6-e1");
    CHECK(parsed["cases"][0]["rows"].size() >= 6);

    CHECK_THROWS_AS(cli::stress_verb({"--case", "nonsense"}, out, err), cli::UsageError);
    CHECK_THROWS_AS(cli::stress_verb({"extra"}, out, err), cli::UsageError);
}
