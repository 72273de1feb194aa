// The momentum-balance expectation (harness/gate/expectations.h) on small
// trajectories written by hand: the walls' impulses account for the change of
// a gas's momentum. Every number is derived in the comments beside it.
#include "expectations.h"
#include "scene.h"
#include "support/expectation_results.h"
#include "support/trajectories.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

using impulse::harness::ExpectationResult;
using impulse::harness::Trajectory;
using impulse::harness::TrajectoryEvent;
using namespace impulse::test;

namespace {

// No gravity, e = 1. A static wall whose left face is x = 5; disc a (mass 1,
// r 0.5) from the origin at (4, 1); discs b and c (mass 2) on y = 3, 3 m
// apart, closing at 1 m/s each. Frames every 0.5 s:
//   b and c touch at t = 1.0 (their gap of 2 m closes at 2 m/s) and, equal
//   masses with e = 1, swap velocities: j = 2 * 2 * 2 * 2 / 4 = 4, n = (-1, 0)
//   from c toward b. Momentum passes between them; the total does not change.
//   a's right side reaches the wall at x = 4.5 / 4 = 1.125 s: n = (-1, 0)
//   toward a, j = 1 * (1 + 1) * 4 = 8, so a leaves at (-4, 1) and at t = 1.5
//   is at 4.5 - 4 * 0.375 = 3.
// P(0) = (4 + 2 - 2, 1) = (4, 1); P(1.5) = (-4 - 2 + 2, 1) = (-4, 1): the
// change (-8, 0) is the wall's j n. Scale at t = 0: |(4, 1)| + 2 + 2 =
// sqrt(17) + 4 = 8.123...; from t = 1.125 on, plus |j| = 8.
const std::string balance_scene = R"({
    "schema": "impulse/scene@1", "name": "balance", "gravity": [0, 0], "restitution": 1,
    "dt": 0.5, "duration": 1.5,
    "bodies": [
        {"name": "wall", "static": true, "shape": {"box": [0.5, 5]}, "position": [5.5, 0]},
        {"name": "a", "shape": {"circle": 0.5}, "mass": 1, "velocity": [4, 1]},
        {"name": "b", "shape": {"circle": 0.5}, "mass": 2, "position": [-1.5, 3],
         "velocity": [1, 0]},
        {"name": "c", "shape": {"circle": 0.5}, "mass": 2, "position": [1.5, 3],
         "velocity": [-1, 0]}]})";

const TrajectoryEvent pair_event = make_event(1.0, "b", "c", 0, 3, -1, 0, 4.0, -2.0, 2.0);
const TrajectoryEvent wall_event = make_event(1.125, "a", "wall", 5, 1.125, -1, 0, 8.0, -4.0, 4.0);

Trajectory balance_trajectory(std::vector<TrajectoryEvent> events = {pair_event, wall_event}) {
    return trajectory_of(
        {"a", "b", "c"},
        {{0.0, 0, 0.0, 0, 4, 1, 0, -1.5, 3, 0, 1, 0, 0, 1.5, 3, 0, -1, 0, 0},
         {0.5, 2, 0.5, 0, 4, 1, 0, -1.0, 3, 0, 1, 0, 0, 1.0, 3, 0, -1, 0, 0},
         // The pair's event is at this frame's time, so the frame shows its result.
         {1.0, 4, 1.0, 0, 4, 1, 0, -0.5, 3, 0, -1, 0, 0, 0.5, 3, 0, 1, 0, 0},
         {1.5, 3, 1.5, 0, -4, 1, 0, -1.0, 3, 0, -1, 0, 0, 1.0, 3, 0, 1, 0, 0}},
        std::move(events));
}

// A disc (mass 1, r 0.5) rattling between two walls with faces at x = +-1.5,
// at 4 m/s from the origin: it hits the right wall at t = 0.25 and the left at
// 0.75, each time j = 8 and its velocity flips. Frames every 0.25 s fall on
// the events: P = 4, -4, -4, 4, 4, and the sums of j n up to each are 0, -8,
// -8, 0, 0.
const std::string rattle_scene = R"({
    "schema": "impulse/scene@1", "name": "rattle", "gravity": [0, 0], "restitution": 1,
    "dt": 0.25, "duration": 1,
    "bodies": [
        {"name": "left", "static": true, "shape": {"box": [0.5, 2]}, "position": [-2, 0]},
        {"name": "right", "static": true, "shape": {"box": [0.5, 2]}, "position": [2, 0]},
        {"name": "a", "shape": {"circle": 0.5}, "mass": 1, "velocity": [4, 0]}]})";

Trajectory rattle_trajectory(std::vector<TrajectoryEvent> events) {
    return trajectory_of({"a"},
                         {{0.00, 0, 0, 0, 4, 0, 0},
                          {0.25, 1, 0, 0, -4, 0, 0},
                          {0.50, 0, 0, 0, -4, 0, 0},
                          {0.75, -1, 0, 0, 4, 0, 0},
                          {1.00, 0, 0, 0, 4, 0, 0}},
                         std::move(events));
}

const std::string balance = R"([{"kind": "momentum-balance", "rtol": 1e-10}])";

} // namespace

TEST_CASE("momentum-balance: the walls' impulses account for the change", "[expectations]") {
    SECTION("as derived; the pair's own event changes nothing") {
        const std::vector<ExpectationResult> results =
            evaluate(balance_scene, balance, balance_trajectory());
        INFO(listing(results));
        REQUIRE(results.size() == 1);
        CHECK(results[0].passed);
        CHECK(results[0].path == "expectations[0]");
        CHECK(results[0].what.rfind("momentum balance (", 0) == 0);
    }
    SECTION("the static body may be a: the impulse on b is -j n") {
        const TrajectoryEvent flipped =
            make_event(1.125, "wall", "a", 5, 1.125, 1, 0, 8.0, -4.0, 4.0);
        CHECK(failures(evaluate(balance_scene, balance,
                                balance_trajectory({pair_event, flipped}))) == 0);
    }
    SECTION("without the wall's event, momentum is off by 8 after it") {
        const std::vector<ExpectationResult> results =
            evaluate(balance_scene, balance, balance_trajectory({pair_event}));
        require_only_failure(results, "momentum balance");
        CHECK(results[0].what == "momentum balance (x), nearest to its tolerance at t = 1.5 s");
        CHECK(results[0].expected == 4.0);
        CHECK(results[0].actual == -4.0);
    }
    SECTION("the pair's event counted as a wall's would be off by 4") {
        // Make c static in the scene's eyes by naming the wall instead: then the
        // event gives b j n = (-4, 0) that its partner does not return.
        const TrajectoryEvent as_wall = make_event(1.0, "b", "wall", 0, 3, -1, 0, 4.0, -2.0, 2.0);
        require_only_failure(
            evaluate(balance_scene, balance, balance_trajectory({as_wall, wall_event})),
            "momentum balance (x)");
    }
    SECTION("rtol is of |m v| at t = 0 plus the |j| given so far") {
        // At t = 0.5 the scale is sqrt(17) + 4 = 8.12: rtol 1e-10 allows 8.1e-10.
        // At t = 1.5 it is 16.12: 1.6e-9 allowed.
        Trajectory t = balance_trajectory();
        t.frames[3][4] += 1.5e-9; // a's vx at t = 1.5
        CHECK(failures(evaluate(balance_scene, balance, t)) == 0);
        t.frames[3][4] += 0.2e-9;
        require_only_failure(evaluate(balance_scene, balance, t), "at t = 1.5 s");
        Trajectory early = balance_trajectory();
        early.frames[1][11] += 1.5e-9; // b's vy at t = 0.5: P.y moves by 2 * 1.5e-9
        const std::vector<ExpectationResult> results = evaluate(balance_scene, balance, early);
        require_only_failure(results, "momentum balance (y)");
        CHECK(results[0].what == "momentum balance (y), nearest to its tolerance at t = 0.5 s");
        CHECK(std::abs(results[0].actual - (1.0 + 3e-9)) <= 1e-15);
    }
    SECTION("a NaN fails") {
        Trajectory t = balance_trajectory();
        t.frames[2][5] = std::nan("");
        require_only_failure(evaluate(balance_scene, balance, t), "at t = 1 s");
    }
    SECTION("an event naming a body the scene lacks") {
        const TrajectoryEvent ghost =
            make_event(1.125, "a", "ghost", 5, 1.125, -1, 0, 8.0, -4.0, 4.0);
        const std::vector<ExpectationResult> results =
            evaluate(balance_scene, balance, balance_trajectory({pair_event, ghost}));
        INFO(listing(results));
        REQUIRE(results.size() == 1);
        CHECK_FALSE(results[0].passed);
        CHECK(results[0].detail == "event 1 names 'ghost', which is not a body of the scene");
    }
}

TEST_CASE("momentum-balance counts an event at a frame's own time, in time order",
          "[expectations]") {
    const TrajectoryEvent right = make_event(0.25, "a", "right", 1.5, 0, -1, 0, 8.0, -4.0, 4.0);
    const TrajectoryEvent left = make_event(0.75, "a", "left", -1.5, 0, 1, 0, 8.0, -4.0, 4.0);
    CHECK(failures(evaluate(rattle_scene, balance, rattle_trajectory({right, left}))) == 0);
    // Recorded out of order, as a run whose bodies keep their own clocks may.
    CHECK(failures(evaluate(rattle_scene, balance, rattle_trajectory({left, right}))) == 0);
    // Without the first, the frame at its time is already off by 8.
    const std::vector<ExpectationResult> results =
        evaluate(rattle_scene, balance, rattle_trajectory({left}));
    require_only_failure(results, "momentum balance (x)");
    CHECK(results[0].what == "momentum balance (x), nearest to its tolerance at t = 0.25 s");
}
