// Dense contact in the stress matrix (issue 14; harness/study/stress.h): the
// pile rows' checkers (drift, at rest, the support impulse under a column, the
// energy scale of a resting pile, the 1e-6 m overlap bound through the grid)
// each fed a made-up violation, what each pile row asks of the engine, and,
// hidden while the engine misses them, the real rows.
#include "stress.h"
#include "support/stress_rows.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

using namespace impulse;
using namespace impulse::harness;
using impulse::test::passes;
using impulse::test::row_of;
using impulse::test::states_of;

namespace {

// A column of two 1 x 0.5 m boxes, 1 kg under 3 kg, at rest on static ground.
Scene column_of_two() {
    return parse_scene(
        R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.1, "duration": 1,
            "gravity": [0, -9.81], "solver": {"integrator": "verlet", "resting": true},
            "bodies": [
           {"name": "ground", "static": true, "shape": {"box": [5, 0.5]}, "position": [0, -0.5]},
           {"name": "under", "shape": {"box": [0.5, 0.25]}, "mass": 1, "position": [0, 0.25]},
           {"name": "over", "shape": {"box": [0.5, 0.25]}, "mass": 3, "position": [0, 0.75]}]})",
        "test.json");
}

const StressCase& case_named(const std::vector<StressCase>& cases, const std::string& name) {
    for (const StressCase& c : cases) {
        if (c.name == name) {
            return c;
        }
    }
    FAIL("no stress case " << name);
    return cases.front();
}

void require_holds(const StressCase& c) {
    const StressResult r = run_stress_case(c);
    INFO(c.name << ": " << c.description);
    INFO("refusal: " << r.refusal << "; stopped: " << r.stopped);
    for (const StressRow& row : r.rows) {
        INFO(row.invariant << " worst " << row.worst << " bound " << row.bound << " (" << row.detail
                           << ")");
        CHECK(row.passed);
    }
    CHECK(r.passed());
}

} // namespace

TEST_CASE("the pile rows' checkers catch a violation made by hand", "[unit][stress]") {
    SECTION("drift: a body of a resting column that slides or sinks") {
        const Scene scene = column_of_two();
        StressChecks checks;
        checks.drifts = {{{1.0, 0.0}, 1e-6}, {{0.0, 1.0}, 1e-6}};
        StressMonitor monitor(scene, checks);
        std::vector<BodyState> states = states_of(scene);
        monitor.observe(0.0, states);
        states[2].position.x += 0.9e-6;
        monitor.observe(0.1, states);
        CHECK(passes(monitor, "drift in x"));
        states[2].position.x += 0.2e-6;
        monitor.observe(0.2, states);
        const StressRow x = row_of(monitor.rows(), "drift in x");
        CHECK_FALSE(x.passed);
        CHECK(x.worst == Approx(1.1e-6).epsilon(1e-9));
        CHECK(x.detail == "largest: 'over' at t = 0.2 s");
        CHECK(passes(monitor, "drift in y"));
        states[1].position.y -= 2e-6; // the lower box sinks into the ground
        monitor.observe(0.3, states);
        CHECK_FALSE(passes(monitor, "drift in y"));
    }
    SECTION("at rest: kinetic energy left after the stated time, or a run too short") {
        // The 3 kg box has fallen 0.5 m (released 3 g 0.5 J) and still moves.
        const Scene scene = column_of_two();
        StressChecks checks;
        checks.at_rest = AtRestCheck{0.5, 1e-9};
        const double released = 3.0 * 9.81 * 0.5;
        const auto worst_with = [&](double speed, double until) {
            StressMonitor monitor(scene, checks);
            std::vector<BodyState> states = states_of(scene);
            monitor.observe(0.0, states);
            states[2].position.y -= 0.5;
            states[2].velocity.y = -speed;
            for (double t = 0.1; t <= until + 1e-12; t += 0.1) {
                monitor.observe(t, states);
            }
            return row_of(monitor.rows(), "at rest");
        };
        // K = 1.5 v^2 against released: v = 1e-5 is 1.5e-10 J, 1e-11 of it.
        CHECK(worst_with(1e-5, 1.0).passed);
        const StressRow moving = worst_with(1e-3, 1.0);
        CHECK_FALSE(moving.passed);
        CHECK(moving.worst == Approx(1.5e-6 / released).epsilon(1e-9));
        // Moving before `after` is not judged; a run ending before it fails.
        CHECK_FALSE(worst_with(0.0, 0.4).passed);
    }
    SECTION("support: a contact impulse that is not the weight above times h") {
        const Scene scene = column_of_two();
        StressChecks checks;
        checks.supports = {{{1, 2}, 1e-9}};
        const double g = 9.81;
        const double h = 0.1;
        const auto worst_with = [&](double dv_over, double dv_under) {
            StressMonitor monitor(scene, checks);
            std::vector<BodyState> states = states_of(scene);
            monitor.observe(0.0, states);
            states[2].velocity.y += dv_over;
            states[1].velocity.y += dv_under;
            monitor.observe(h, states);
            return row_of(monitor.rows(), "support impulse under 'over''s column");
        };
        // Held still: the contacts gave exactly 3 g h and 4 g h.
        const StressRow still = worst_with(0.0, 0.0);
        CHECK(still.passed);
        CHECK(still.worst < 1e-15);
        // The top box gains 1e-6 m/s: 3e-6 more than 3 g h under it, and under
        // the lower box 3e-6 more than 4 g h; the larger relative error is the top's.
        const StressRow rising = worst_with(1e-6, 0.0);
        CHECK_FALSE(rising.passed);
        CHECK(rising.worst == Approx(3e-6 / (3.0 * g * h)).epsilon(1e-6));
        CHECK(rising.detail.find("under 'over' at t = 0.1 s") != std::string::npos);
        // The lower box sinks while the top one holds: the error is in the lower contact.
        const StressRow sinking = worst_with(0.0, -1e-6);
        CHECK_FALSE(sinking.passed);
        CHECK(sinking.worst == Approx(1e-6 / (4.0 * g * h)).epsilon(1e-6));
        CHECK(sinking.detail.find("under 'under'") != std::string::npos);
    }
    SECTION("energy gained at rest: judged against the energy held above the ground") {
        // 1 kg at 0.25 m and 3 kg at 0.75 m above the ground's top: 2.5 g J.
        const Scene scene = column_of_two();
        StressChecks checks;
        checks.energy_scale_floor = 2.5 * 9.81;
        StressMonitor monitor(scene, checks);
        std::vector<BodyState> states = states_of(scene);
        monitor.observe(0.0, states);
        states[2].position.y += 1e-12; // 3 g 1e-12 J: 1.2e-12 of the floor
        monitor.observe(0.1, states);
        const StressRow row = row_of(monitor.rows(), "energy gain");
        CHECK_FALSE(row.passed);
        CHECK(row.worst == Approx(3.0 * 9.81 * 1e-12 / (2.5 * 9.81)).epsilon(1e-3));
    }
    SECTION("an overlap bound of 1e-6 m, found among 1000 bodies by the grid") {
        const std::vector<StressCase> cases = stress_cases();
        const StressCase& pile = case_named(cases, "pile-discs-1000");
        REQUIRE(pile.scene.bodies.size() == 1003); // floor, two walls, 1000 discs
        StressMonitor monitor(pile.scene, pile.checks);
        std::vector<BodyState> states = states_of(pile.scene);
        monitor.observe(0.0, states);
        CHECK(passes(monitor, "interpenetration"));
        // The first and the last disc moved out of the box, 100 m to the
        // right, the last 0.5e-6 then 2e-6 m into the first: the grid must
        // find the pair, 999 bodies apart in the list.
        const SceneBody& first = pile.scene.bodies[3];
        const SceneBody& last = pile.scene.bodies[1002];
        const double touching = first.shape.radius + last.shape.radius;
        states[3].position = {100.0, 0.0};
        for (const double depth : {0.5e-6, 2e-6}) {
            states[1002].position = {100.0 + touching - depth, 0.0};
            monitor.observe(depth * 1e6, states);
        }
        const StressRow row = row_of(monitor.rows(), "interpenetration");
        CHECK_FALSE(row.passed);
        CHECK(row.bound == 1e-6);
        CHECK(row.worst == Approx(2e-6).epsilon(1e-6));
        CHECK(row.detail == "'" + first.name + "' and '" + last.name + "' at t = 2 s");
    }
}

TEST_CASE("the stress matrix's pile rows: what each asks of the engine", "[unit][stress]") {
    const std::vector<StressCase> cases = stress_cases();
    const StressCase& column = case_named(cases, "pile-column-50");
    CHECK(column.scene.bodies.size() == 51);
    CHECK(column.scene.solver.resting);
    CHECK(column.scene.solver.resting_method == RestingMethod::time_stepping);
    REQUIRE(column.checks.supports.size() == 1);
    CHECK(column.checks.supports[0].column.size() == 50);
    // (n^2 / 2) d / (|g| h^2) for n = 50: 1250 times 1e-9 m over 9.81 m/s^2
    // times (1/64 s)^2 (docs/physics.md, "A stack solved iteratively").
    CHECK(column.checks.supports[0].rtol == Approx(1250.0 * 1e-9 * 4096.0 / 9.81).epsilon(1e-12));
    CHECK(column.checks.overlap_bound == 1e-6);
    CHECK_FALSE(column.slow);

    const StressCase& mass = case_named(cases, "pile-mass-1e3");
    REQUIRE(mass.checks.supports.size() == 2);
    CHECK(mass.scene.bodies[2].mass == 1000.0 * mass.scene.bodies[1].mass);
    CHECK(mass.scene.bodies[3].mass == 1000.0 * mass.scene.bodies[4].mass);
    // Two bodies a column: (2^2 / 2) d / (|g| h^2).
    CHECK(mass.checks.supports[0].rtol ==
          Approx(2.0 * mass.scene.solver.contact_tolerance / (9.81 * mass.scene.dt * mass.scene.dt))
              .epsilon(1e-12));

    const StressCase& discs = case_named(cases, "pile-discs-1000");
    CHECK(discs.scene.solver.stepping == Stepping::local);
    CHECK(time_stepping_from_start(discs.scene.solver)); // resting with local stepping
    REQUIRE(discs.checks.at_rest);
    CHECK(discs.checks.at_rest->after == 6.0);
    CHECK(discs.checks.energy_gain);
    CHECK(discs.slow);
}

// The slow row (1000 discs, a few seconds) runs here and under the stress
// label (`impulse stress`), not in the unit pass over the matrix.
TEST_CASE("the pile rows hold: the column, the 1:1000 stacks and 1000 discs",
          "[stress][stress-piles]") {
    for (const StressCase& c : stress_cases()) {
        if (c.name.rfind("pile-", 0) == 0) {
            require_holds(c);
        }
    }
}
