// The observables `impulse box2d` compares (harness/study/observables.h) on small
// trajectories written by hand: one "impulse" run and one "Box2D" run of the
// same scene, each value derived in the comments beside it from the physics
// and the hand-made frames, never copied from a program's output. Most numbers
// are chosen to be exact in binary (g = 8, halves and quarters), so a value at
// a tolerance's boundary is exactly there. The verb itself is in
// test_box2d_verb.cpp.
#include "cli.h"
#include "observables.h"
#include "scene.h"
#include "support/trajectories.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using impulse::harness::compare_observables;
using impulse::harness::ObservableRow;
using impulse::harness::parse_scene;
using impulse::harness::Scene;
using impulse::harness::Trajectory;
using impulse::harness::TrajectoryEvent;
using namespace impulse::test;

namespace {

const std::string test_file = "scenes/test.json";

TrajectoryEvent hit(double t, const std::string& a, const std::string& b, double vn_before = -1.0,
                    double vn_after = 0.5) {
    TrajectoryEvent e;
    e.t = t;
    e.a = a;
    e.b = b;
    e.normal[1] = 1.0;
    e.vn_before = vn_before;
    e.vn_after = vn_after;
    return e;
}

// Frames of one body at rest at (0, y) from t = 0 to `end` every `dt`, with
// the frames in `shown` (t, y, vy) put in their place.
std::vector<Frame> frames_of(double dt, double end, double y,
                             const std::vector<std::vector<double>>& shown) {
    std::vector<Frame> frames;
    for (int k = 0; k * dt <= end; ++k) {
        frames.push_back({k * dt, 0.0, y, 0.0, 0.0, 0.0, 0.0});
    }
    for (const std::vector<double>& s : shown) {
        for (Frame& f : frames) {
            if (f[0] == s[0]) {
                f[2] = s[1];
                f[5] = s[2];
            }
        }
    }
    return frames;
}

// The drop of docs/physics.md with numbers exact in binary: g = 8, e = 0.5, a disc
// of radius 0.5 whose centre is at 2.5 over ground whose top is y = 0, so the
// gap h0 = 2 and the centre's height at contact y0 - h0 = 0.5. Then v1 =
// sqrt(2 g h0) = 4 sqrt(2), t1 = v1 / g = sqrt(2) / 2, impact 2 at t1 + 2 e v1 /
// g = sqrt(2), apex n = e^(2n) h0: 0.5 and 0.125.
std::string drop_scene(const std::string& observables) {
    return R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.25, "duration": 3,
        "gravity": [0, -8], "restitution": 0.5,
        "bodies": [
          {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
          {"name": "ball", "shape": {"circle": 0.5}, "position": [0, 2.5]}],
        "box2d": {"observables": )" +
           observables + "}}";
}

// The impulse run: impacts at 0.6875 and 1.375 s; the first frames after them,
// 0.75 s (y 0.75, vy 2) and 1.5 s (y 0.5625, vy 1), put the apexes
// y + vy^2 / (2 g) - 0.5 at 0.75 + 0.25 - 0.5 = 0.5 and 0.5625 + 0.0625 - 0.5 =
// 0.125.
Trajectory impulse_drop() {
    return trajectory_of({"ball"},
                         frames_of(0.25, 3.0, 2.5, {{0.75, 0.75, 2.0}, {1.5, 0.5625, 1.0}}),
                         {hit(0.6875, "ball", "ground"), hit(1.375, "ball", "ground")});
}

// The Box2D run: impacts stamped with the ends of the steps that solved them,
// 0.75 and 1.5 s, whose own frames show them done: (y 1, vy 2) gives apex
// 1 + 0.25 - 0.5 = 0.75, (y 0.625, vy 1) gives 0.625 + 0.0625 - 0.5 = 0.1875.
Trajectory box2d_drop(int impacts = 2) {
    std::vector<TrajectoryEvent> events = {hit(0.75, "ball", "ground"), hit(1.5, "ball", "ground")};
    events.resize(static_cast<std::size_t>(impacts));
    return trajectory_of({"ball"}, frames_of(0.25, 3.0, 2.5, {{0.75, 1.0, 2.0}, {1.5, 0.625, 1.0}}),
                         events);
}

std::vector<ObservableRow> compare(const std::string& scene_text, const Trajectory& impulse,
                                   const Trajectory& box2d) {
    const Scene scene = parse_scene(scene_text, test_file);
    return compare_observables(scene, impulse, box2d);
}

} // namespace

TEST_CASE("impact times: each run's own, against the drop ladder", "[observables]") {
    // Differences 0.75 - 0.6875 = 0.0625 and 1.5 - 1.375 = 0.125: both within
    // atol 0.125, the second exactly at it.
    const std::vector<ObservableRow> rows =
        compare(drop_scene(R"([{"kind": "impact-times", "body": "ball", "count": 2,
                                "atol": 0.125}])"),
                impulse_drop(), box2d_drop());
    REQUIRE(rows.size() == 2);
    CHECK(rows[0].path == "box2d.observables[0]");
    CHECK(rows[0].name == "impact 1 time of 'ball' (s)");
    REQUIRE(rows[0].exact.has_value());
    CHECK(*rows[0].exact == Approx(std::sqrt(2.0) / 2.0).epsilon(1e-15));
    CHECK(rows[0].impulse == 0.6875);
    CHECK(rows[0].box2d == 0.75);
    CHECK(rows[0].tolerance == 0.125);
    CHECK(rows[0].within);
    CHECK(rows[0].note.empty());
    CHECK(rows[1].name == "impact 2 time of 'ball' (s)");
    CHECK(*rows[1].exact == Approx(std::sqrt(2.0)).epsilon(1e-15));
    CHECK(rows[1].impulse == 1.375);
    CHECK(rows[1].box2d == 1.5);
    CHECK(rows[1].within);

    // Just under 0.125 the second is outside.
    const std::vector<ObservableRow> tighter =
        compare(drop_scene(R"([{"kind": "impact-times", "body": "ball", "count": 2,
                                "atol": 0.1249}])"),
                impulse_drop(), box2d_drop());
    CHECK(tighter[0].within);
    CHECK_FALSE(tighter[1].within);
}

TEST_CASE("apex heights: y + vy^2 / (2 g) above the contact height", "[observables]") {
    // Apex 1: impulse 0.5 (exact e^2 h0 = 0.5), Box2D 0.75: difference 0.25.
    // tolerance = atol + rtol |impulse| = 0.125 + 0.25 x 0.5 = 0.25: at the
    // boundary, within. Apex 2: impulse 0.125, Box2D 0.1875, tolerance 0.125 +
    // 0.25 x 0.125 = 0.15625 >= 0.0625.
    const std::vector<ObservableRow> rows =
        compare(drop_scene(R"([{"kind": "apex-heights", "body": "ball", "count": 2,
                                "atol": 0.125, "rtol": 0.25}])"),
                impulse_drop(), box2d_drop());
    REQUIRE(rows.size() == 2);
    CHECK(rows[0].name == "apex 1 of 'ball' (m)");
    CHECK(rows[0].exact == 0.5);
    CHECK(rows[0].impulse == 0.5);
    CHECK(rows[0].box2d == 0.75);
    CHECK(rows[0].tolerance == 0.25);
    CHECK(rows[0].within);
    CHECK(rows[1].exact == 0.125);
    CHECK(rows[1].impulse == 0.125);
    CHECK(rows[1].box2d == 0.1875);
    CHECK(rows[1].tolerance == 0.15625);
    CHECK(rows[1].within);

    // A hair less relative tolerance and apex 1 is outside: 0.125 + 0.2499 x 0.5 < 0.25.
    const std::vector<ObservableRow> tighter =
        compare(drop_scene(R"([{"kind": "apex-heights", "body": "ball", "count": 1,
                                "atol": 0.125, "rtol": 0.2499}])"),
                impulse_drop(), box2d_drop());
    REQUIRE(tighter.size() == 1);
    CHECK_FALSE(tighter[0].within);
}

TEST_CASE("apex ratios: apex n over apex n - 1, apex 0 being h0", "[observables]") {
    // Impulse: 0.5 / 2 = 0.25 and 0.125 / 0.5 = 0.25; Box2D: 0.75 / 2 = 0.375
    // and 0.1875 / 0.75 = 0.25; exact e^2 = 0.25.
    const std::vector<ObservableRow> rows =
        compare(drop_scene(R"([{"kind": "apex-ratios", "body": "ball", "count": 2,
                                "atol": 0.125}])"),
                impulse_drop(), box2d_drop());
    REQUIRE(rows.size() == 2);
    CHECK(rows[0].name == "apex 1 / apex 0 of 'ball'");
    CHECK(rows[0].exact == 0.25);
    CHECK(rows[0].impulse == 0.25);
    CHECK(rows[0].box2d == 0.375);
    CHECK(rows[0].within); // 0.125 <= 0.125
    CHECK(rows[1].name == "apex 2 / apex 1 of 'ball'");
    CHECK(rows[1].impulse == 0.25);
    CHECK(rows[1].box2d == 0.25);
    CHECK(rows[1].within);
}

TEST_CASE("a run with fewer impacts than asked has no value, a note, and fails", "[observables]") {
    const std::vector<ObservableRow> rows =
        compare(drop_scene(R"([{"kind": "impact-times", "body": "ball", "count": 3, "atol": 1},
                       {"kind": "apex-heights", "body": "ball", "count": 2, "atol": 1},
                       {"kind": "apex-ratios", "body": "ball", "count": 2, "atol": 1}])"),
                impulse_drop(), box2d_drop(1));
    REQUIRE(rows.size() == 7);
    // Impact 3: neither run has it; impact 2: only the impulse run.
    CHECK_FALSE(rows[2].impulse.has_value());
    CHECK_FALSE(rows[2].box2d.has_value());
    CHECK_FALSE(rows[2].within);
    CHECK(rows[2].note == "The impulse run has 2 impacts of 'ball', fewer than 3. The Box2D run "
                          "has 1 impact of 'ball', fewer than 3.");
    CHECK(rows[1].impulse == 1.375);
    CHECK_FALSE(rows[1].box2d.has_value());
    CHECK_FALSE(rows[1].within);
    CHECK(rows[1].note == "The Box2D run has 1 impact of 'ball', fewer than 2.");
    // Apex 1 is there in both, apex 2 and its ratio only in the impulse run.
    CHECK(rows[3].within);
    CHECK(rows[3].box2d == 0.75);
    CHECK(rows[4].impulse == 0.125);
    CHECK_FALSE(rows[4].box2d.has_value());
    CHECK_FALSE(rows[4].within);
    CHECK(rows[4].note == "The Box2D run has 1 impact of 'ball', fewer than 2.");
    CHECK(rows[5].within);
    CHECK_FALSE(rows[6].box2d.has_value());
    CHECK_FALSE(rows[6].within);
    // Without a value the tolerance is atol alone, and nothing is within it.
    CHECK(rows[2].tolerance == 1.0);
}

TEST_CASE("an apex needs a frame between its impact and the next", "[observables]") {
    // The Box2D run's first impact is stamped 0.625 s and its second 0.75 s,
    // the time of the first frame after the first: that frame already shows
    // the second impact done.
    const Trajectory box2d =
        trajectory_of({"ball"}, frames_of(0.25, 3.0, 2.5, {{0.75, 1.0, 2.0}}),
                      {hit(0.625, "ball", "ground"), hit(0.75, "ball", "ground")});
    const std::vector<ObservableRow> rows =
        compare(drop_scene(R"([{"kind": "apex-heights", "body": "ball", "count": 1,
                                "atol": 1}])"),
                impulse_drop(), box2d);
    REQUIRE(rows.size() == 1);
    CHECK_FALSE(rows[0].box2d.has_value());
    CHECK(rows[0].note == "The Box2D run has no frame between impact 1 of 'ball' and the next.");
}

TEST_CASE("post-impact velocity: both runs read at the same frame time", "[observables]") {
    // The impulse run hits at 0.6875 s, its first frame after is 0.75 s (vy 2);
    // Box2D resolves the impact in the step ending at 1 s. Both are read at
    // 1 s: impulse vy 0 (2 less g x 0.25), Box2D vy 1.5. The drop's exact vy at
    // 1 s: e v1 - g (1 - t1) = 2 sqrt(2) - 8 + 4 sqrt(2) = 6 sqrt(2) - 8.
    const Trajectory impulse =
        trajectory_of({"ball"}, frames_of(0.25, 3.0, 2.5, {{0.75, 0.75, 2.0}, {1.0, 1.0, 0.0}}),
                      {hit(0.6875, "ball", "ground")});
    const Trajectory box2d = trajectory_of({"ball"}, frames_of(0.25, 3.0, 2.5, {{1.0, 1.0, 1.5}}),
                                           {hit(1.0, "ball", "ground")});
    const std::string scene =
        drop_scene(R"([{"kind": "post-impact-velocity", "body": "ball", "impact": 1,
                        "atol": 1, "rtol": 0.25}])");
    const std::vector<ObservableRow> rows = compare(scene, impulse, box2d);
    REQUIRE(rows.size() == 3);
    CHECK(rows[0].name == "vx after impact 1 of 'ball' (m/s)");
    CHECK(rows[0].exact == 0.0);
    CHECK(rows[0].impulse == 0.0);
    CHECK(rows[0].box2d == 0.0);
    CHECK(rows[1].name == "vy after impact 1 of 'ball' (m/s)");
    REQUIRE(rows[1].exact.has_value());
    CHECK(*rows[1].exact == Approx(6.0 * std::sqrt(2.0) - 8.0).epsilon(1e-14));
    CHECK(rows[1].impulse == 0.0);
    CHECK(rows[1].box2d == 1.5);
    CHECK(rows[1].tolerance == 1.0); // 1 + 0.25 x |0|
    CHECK_FALSE(rows[1].within);     // 1.5 > 1
    CHECK(rows[2].name == "omega after impact 1 of 'ball' (rad/s)");
    CHECK(rows[2].exact == 0.0);
    CHECK(rows[2].within);
    CHECK(rows[1].note.empty());

    // When the impulse run's next impact comes before the common frame, each
    // run is read at its own first frame, and the note says so: impulse at
    // 0.75 s (vy 2), Box2D at 1 s (vy 1.5), difference 0.5 within 1 + 0.25 x 2.
    const Trajectory bouncing =
        trajectory_of({"ball"}, frames_of(0.25, 3.0, 2.5, {{0.75, 0.75, 2.0}, {1.0, 1.0, 0.0}}),
                      {hit(0.6875, "ball", "ground"), hit(0.875, "ball", "ground")});
    const std::vector<ObservableRow> own = compare(scene, bouncing, box2d);
    CHECK(own[1].impulse == 2.0);
    CHECK(own[1].box2d == 1.5);
    CHECK(own[1].tolerance == 1.5);
    CHECK(own[1].within);
    CHECK(own[1].note.find("Read at each run's own first frame after the impact (t = 0.75 s and "
                           "1 s)") == 0);
}

TEST_CASE("post-impact velocity of a corner impact: docs/physics.md's formula", "[observables]") {
    // No gravity: a unit square turned by atan(3/4) (cos 0.8, sin 0.6) falls at
    // 2 m/s onto ground whose top is y = 0. Its corners sit at (-0.1, -0.7),
    // (0.7, -0.1), (0.1, 0.7), (-0.7, 0.1) from its centre: the lowest has
    // rx = -0.1. M = 1, I = M (1 + 1) / 12 = 1/6, e = 0.5:
    //   j = (1 + e) v / (1/M + rx^2 / I) = 3 / 1.06
    //   vy' = -2 + j = 0.8301886792..., w' = rx j / I = -0.6 x 3 / 1.06 = -1.6981132075...
    const std::string scene = R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.25,
        "duration": 3, "gravity": [0, 0], "restitution": 0.5,
        "bodies": [
          {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
          {"name": "square", "shape": {"box": [0.5, 0.5]}, "mass": 1, "angle": 0.6435011087932844,
           "position": [0, 1.7], "velocity": [0, -2]}],
        "box2d": {"observables": [{"kind": "post-impact-velocity", "body": "square",
                                   "impact": 1, "atol": 0.25}]}})";
    auto run = [](double t_hit, double vy, double omega) {
        std::vector<Frame> frames;
        for (int k = 0; k <= 12; ++k) {
            const double t = 0.25 * k;
            const bool after = t >= t_hit;
            frames.push_back({t, 0.0, 1.7, 0.6435, 0.0, after ? vy : -2.0, after ? omega : 0.0});
        }
        return trajectory_of({"square"}, frames, {hit(t_hit, "square", "ground")});
    };
    const std::vector<ObservableRow> rows =
        compare(scene, run(0.5, 0.8125, -1.75), run(0.75, 0.875, -1.5));
    REQUIRE(rows.size() == 3);
    CHECK(rows[0].exact == 0.0);
    REQUIRE(rows[1].exact.has_value());
    CHECK(*rows[1].exact == Approx(-2.0 + 3.0 / 1.06).epsilon(1e-12));
    CHECK(rows[1].impulse == 0.8125);
    CHECK(rows[1].box2d == 0.875);
    CHECK(rows[1].within); // 0.0625 <= 0.25
    REQUIRE(rows[2].exact.has_value());
    CHECK(*rows[2].exact == Approx(-0.6 * 3.0 / 1.06).epsilon(1e-12));
    CHECK(rows[2].within); // exactly 0.25 apart: at the boundary
}

TEST_CASE("post-impact velocity of a head-on pair: docs/physics.md's 1D answer", "[observables]") {
    // Free space, e = 0.5, discs of 3 kg at 2 m/s and 1 kg at -2 m/s along x:
    //   vA' = (3 x 2 + 1 x -2 - 1 x 0.5 x 4) / 4 = 0.5
    //   vB' = (3 x 2 + 1 x -2 + 3 x 0.5 x 4) / 4 = 2.5
    const std::string scene = R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.25,
        "duration": 2, "gravity": [0, 0], "restitution": 0.5,
        "bodies": [
          {"name": "a", "shape": {"circle": 0.5}, "mass": 3, "velocity": [2, 0]},
          {"name": "b", "shape": {"circle": 0.5}, "mass": 1, "position": [3, 0],
           "velocity": [-2, 0]}],
        "box2d": {"observables": [
          {"kind": "post-impact-velocity", "body": "a", "impact": 1, "atol": 0.001},
          {"kind": "post-impact-velocity", "body": "b", "impact": 1, "atol": 0.001}]}})";
    auto run = [](double t_hit, double va, double vb) {
        std::vector<Frame> frames;
        for (int k = 0; k <= 8; ++k) {
            const double t = 0.25 * k;
            const bool after = t >= t_hit;
            frames.push_back({t, 0.0, 0.0, 0.0, after ? va : 2.0, 0.0, 0.0, //
                              3.0, 0.0, 0.0, after ? vb : -2.0, 0.0, 0.0});
        }
        return trajectory_of({"a", "b"}, frames, {hit(t_hit, "a", "b")});
    };
    const std::vector<ObservableRow> rows =
        compare(scene, run(0.5, 0.5, 2.5), run(0.75, 0.5, 2.501953125));
    REQUIRE(rows.size() == 6);
    CHECK(rows[0].name == "vx after impact 1 of 'a' (m/s)");
    CHECK(*rows[0].exact == Approx(0.5).epsilon(1e-15));
    CHECK(rows[0].within);
    CHECK(rows[1].exact == 0.0);
    CHECK(rows[2].exact == 0.0);
    CHECK(rows[3].name == "vx after impact 1 of 'b' (m/s)");
    CHECK(*rows[3].exact == Approx(2.5).epsilon(1e-15));
    CHECK(rows[3].impulse == 2.5);
    CHECK(rows[3].box2d == 2.501953125);
    CHECK_FALSE(rows[3].within); // 2^-9 > 0.001
}

TEST_CASE("restitution residual: (vn_after + e vn_before) / |vn_before|, the largest",
          "[observables]") {
    // e = 0.5. Impulse: -4 -> 2 gives 0, -2 -> 1 gives 0. Box2D: -4 -> 2.5 gives
    // 0.125, -1 -> 0.25 gives -0.25 (the largest in magnitude, sign kept); an
    // event with vn_before 0 has no residual; the other ball's event
    // (-1 -> 1, residual 0.5) does not count for 'ball'.
    const Trajectory impulse = trajectory_of(
        {"ball"}, frames_of(0.25, 3.0, 2.5, {}),
        {hit(0.6875, "ball", "ground", -4.0, 2.0), hit(1.375, "ball", "ground", -2.0, 1.0)});
    const Trajectory box2d = trajectory_of(
        {"ball"}, frames_of(0.25, 3.0, 2.5, {}),
        {hit(0.75, "ball", "ground", -4.0, 2.5), hit(1.0, "other", "ground", -1.0, 1.0),
         hit(1.25, "ball", "ground", 0.0, 0.0), hit(1.5, "ball", "ground", -1.0, 0.25)});
    const std::string both =
        R"({"kind": "restitution-residual", "body": "ball", "atol": 0.25},
           {"kind": "restitution-residual", "atol": 0.25})";
    const Scene scene = parse_scene(
        R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.25, "duration": 3,
            "gravity": [0, -8], "restitution": 0.5,
            "bodies": [
              {"name": "ground", "static": true, "shape": {"box": [50, 0.5]}, "position": [0, -0.5]},
              {"name": "ball", "shape": {"circle": 0.5}, "position": [0, 2.5]},
              {"name": "other", "shape": {"circle": 0.5}, "position": [5, 2.5]}],
            "box2d": {"observables": [)" +
            both + "]}}",
        test_file);
    const std::vector<ObservableRow> rows = compare_observables(scene, impulse, box2d);
    REQUIRE(rows.size() == 2);
    CHECK(rows[0].name == "largest restitution residual of 'ball'");
    CHECK(rows[0].exact == 0.0);
    CHECK(rows[0].impulse == 0.0);
    CHECK(rows[0].box2d == -0.25);
    CHECK(rows[0].within); // 0.25 <= 0.25
    // Every event: 'other' counts now, residual (1 - 0.5) / 1 = 0.5.
    CHECK(rows[1].name == "largest restitution residual");
    CHECK(rows[1].box2d == 0.5);
    CHECK_FALSE(rows[1].within);

    // No collisions of the body: no value.
    const Trajectory quiet = trajectory_of({"ball"}, frames_of(0.25, 3.0, 2.5, {}), {});
    const std::vector<ObservableRow> none = compare_observables(scene, impulse, quiet);
    CHECK_FALSE(none[0].box2d.has_value());
    CHECK(none[0].note == "The Box2D run has no collision of 'ball' to measure.");
    CHECK_FALSE(none[0].within);
    CHECK(none[1].note == "The Box2D run has no collision to measure.");
}

TEST_CASE("momentum, angular momentum and energy: the largest drift from frame 0",
          "[observables]") {
    // Free space, e = 1: all three conserved, exact 0. One body 'a' of 2 kg,
    // a disc of radius 0.5 (I = M r^2 / 2 = 0.25). Impulse frames keep every
    // total; Box2D's frame 1 moves it from (1, 0) at v (0, 1) to (1, 0) at
    // v (0.5, 1.5), w from 0 to 2:
    //   |dP| = 2 |(0.5, 0.5)| = sqrt(2)
    //   L = m (x vy - y vx) + I w: 2 x 1 = 2 -> 2 x 1.5 + 0.25 x 2 = 3.5, drift 1.5
    //   E = m v^2 / 2 + I w^2 / 2: 1 -> (0.25 + 2.25) + 0.5 = 3, drift 2
    // Frame 2 comes back to the start: the largest is frame 1's.
    const std::string scene = R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.5,
        "duration": 1, "gravity": [0, 0],
        "bodies": [{"name": "a", "shape": {"circle": 0.5}, "mass": 2, "position": [1, 0],
                    "velocity": [0, 1]}],
        "box2d": {"observables": [{"kind": "momentum", "atol": 1.5},
                                  {"kind": "angular-momentum", "atol": 1.5},
                                  {"kind": "energy", "atol": 1.5}]}})";
    const Trajectory impulse = trajectory_of({"a"},
                                             {{0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0},
                                              {0.5, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0},
                                              {1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0}},
                                             {});
    const Trajectory box2d = trajectory_of({"a"},
                                           {{0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0},
                                            {0.5, 1.0, 0.0, 0.0, 0.5, 1.5, 2.0},
                                            {1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0}},
                                           {});
    const std::vector<ObservableRow> rows = compare(scene, impulse, box2d);
    REQUIRE(rows.size() == 3);
    CHECK(rows[0].name == "momentum drift |P(t) - P(0)| (kg m/s)");
    CHECK(rows[0].exact == 0.0);
    CHECK(rows[0].impulse == 0.0);
    CHECK(*rows[0].box2d == Approx(std::sqrt(2.0)).epsilon(1e-15));
    CHECK(rows[0].within); // 1.414 <= 1.5
    CHECK(rows[1].name == "angular momentum drift |L(t) - L(0)| (kg m^2/s)");
    CHECK(rows[1].box2d == 1.5);
    CHECK(rows[1].within); // at the boundary
    CHECK(rows[2].name == "energy drift |E(t) - E(0)| (J)");
    CHECK(rows[2].box2d == 2.0);
    CHECK_FALSE(rows[2].within);
}

TEST_CASE("conserved quantities have an exact 0 only where the scene conserves them",
          "[observables]") {
    // Under gravity with static ground and e = 0.5: neither momentum nor
    // energy is conserved; the drifts are still compared. Potential energy
    // counts: the ball's fall from y 2.5 to 1.5 under g = 8 turns 1 kg x 8 x 1
    // = 8 J into motion; with vy = -4 (kinetic 8 J) the total stays.
    const std::string text =
        drop_scene(R"([{"kind": "momentum", "atol": 0}, {"kind": "energy", "atol": 0}])");
    const Scene scene = parse_scene(text, test_file);
    const double mass = scene.bodies[1].mass; // pi / 4 from density 1
    const Trajectory falling = trajectory_of(
        {"ball"}, {{0.0, 0.0, 2.5, 0.0, 0.0, 0.0, 0.0}, {0.5, 0.0, 1.5, 0.0, 0.0, -4.0, 0.0}}, {});
    const std::vector<ObservableRow> rows = compare_observables(scene, falling, falling);
    REQUIRE(rows.size() == 2);
    CHECK_FALSE(rows[0].exact.has_value());
    CHECK(*rows[0].impulse == Approx(4.0 * mass).epsilon(1e-15));
    CHECK(rows[0].within); // identical runs: 0 <= 0
    CHECK_FALSE(rows[1].exact.has_value());
    CHECK(*rows[1].impulse == Approx(0.0).margin(1e-13));
}

TEST_CASE("a scene without observables compares nothing", "[observables]") {
    const Scene scene = parse_scene(R"({"schema": "impulse/scene@1", "name": "t", "dt": 0.5,
        "duration": 1, "bodies": [{"name": "a", "shape": {"circle": 0.5}}]})",
                                    test_file);
    const Trajectory t = trajectory_of({"a"}, {{0.0, 0, 0, 0, 0, 0, 0}}, {});
    CHECK(compare_observables(scene, t, t).empty());
}
