// Issue 14's last absurd inputs, through the real tool: scales the engine and
// the gate cannot resolve in double precision. A pile so heavy its energies
// overflow, a listed body whose weight does, a contact band as wide as a
// body, walls thinner than it, and gravity whose per-step fall time-stepping
// cannot cancel to the contact tolerance. Every case ends in exit code 2 and
// one sentence naming the file and the JSON path, with nothing written, no
// --out file destroyed and no golden touched (support/bad_input.h runs each
// through run, render, check and bless); each rule is also checked at its
// edge, where the scene runs. The rules: docs/refusals-and-progress.md,
// "Scales the engine cannot resolve".
#include "support/bad_input.h"
#include "support/input_pile.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

// The input tests' pile (support/input_pile.h): six bodies of both kinds
// dropped for five steps, named drop-box.
const std::string pile = input_pile();

// A ball of radius 0.25 m above a ground 1 m thick (inradius 0.5 m).
const std::string ball = R"({
  "schema": "impulse/scene@1",
  "name": "drop-box",
  "dt": 0.01,
  "duration": 0.05,
  "solver": {"integrator": "verlet"},
  "bodies": [
    {"name": "ground", "static": true, "shape": {"box": [5, 0.5]}, "position": [0, -0.5]},
    {"name": "ball", "shape": {"circle": 0.25}, "mass": 1, "position": [0, 2]}
  ]
}
)";

std::string pile_value(const std::string& key, const std::string& value) {
    return with_pile_value(pile, key, value);
}

std::string pile_solver(const std::string& block) {
    return with_pile_solver(pile, block);
}

std::string with_gravity(const std::string& scene, const std::string& gravity) {
    return replace_once(scene, R"(  "dt": )", R"(  "gravity": )" + gravity + R"(,
  "dt": )");
}

std::string ball_edit(const std::string& from, const std::string& to) {
    return replace_once(ball, from, to);
}

std::string ball_solver(const std::string& keys) {
    return ball_edit(R"("solver": {"integrator": "verlet"})",
                     R"("solver": {"integrator": "verlet", )" + keys + "}");
}

// Four gas bodies in a room with no gravity: `solver` (a line, or empty) and
// `more` gas keys after max_speed.
std::string gas_scene(const std::string& solver, const std::string& more) {
    return R"({
  "schema": "impulse/scene@1",
  "name": "drop-box",
  "gravity": [0, 0],
  "dt": 0.01,
  "duration": 0.05,
)" + solver +
           R"(  "gas": {"count": 4, "shape": {"circle": 0.1}, "mass": 1, "spacing": 0.5, "max_speed": 1)" +
           more + R"(}
}
)";
}

// `run` of a scene the rules accept: exit 0, nothing on stderr.
void require_runs(const std::string& text) {
    const TempDir dir;
    const fs::path scene = dir.dir / "scene.json";
    spit(scene, text);
    const fs::path out = dir.dir / "out.json";
    const Outcome o = run_tool({"run", scene.string(), "--out", out.string()});
    INFO(o.err);
    CHECK(o.exit_code == 0);
    CHECK(o.err.empty());
    CHECK(fs::exists(out));
}

} // namespace

TEST_CASE("The scenes the extreme cases start from are valid", "[extreme-input]") {
    require_runs(pile);
    require_runs(ball);
}

TEST_CASE("A pile whose energies overflow is exit 2 at pile.density[1] or gravity",
          "[extreme-input]") {
    // Two rows at spacing 0.71 reach 2 x 2 x 0.71 = 2.84 m up (beyond the
    // side walls' 3 x 0.71 / 2 + 1 = 2.065 m), and the gate's sums must stay
    // within 2^960 = 2^-64 of the largest double.
    const std::string limit = "within 2^-64 of the largest double, 9.7453140114e+288 J";
    const std::vector<BadFile> cases = {
        // Masses finite (the heaviest square 0.25 x 1e306 kg), energies not.
        bad_text("density 1e306", pile_value("density", "[1, 1e306]"), "pile.density[1]",
                 "gives the pile an energy scale of"),
        bad_text("density 1e306: the reach and the limit", pile_value("density", "[1, 1e306]"),
                 "pile.density[1]", "the box's reach 2.84 m"),
        bad_text("density 1e306: the limit", pile_value("density", "[1, 1e306]"), "pile.density[1]",
                 limit),
        bad_text("density 1e308: the mass is finite, its energy is not",
                 pile_value("density", "[1, 1e308]"), "pile.density[1]",
                 "an energy scale of inf J"),
        // 6 x 0.25 kg x 1e290 m/s^2 x 2.84 m = 4.3e290 J even at 1 kg/m^2:
        // the gravity is what to change.
        bad_text("gravity 1e290 under a light pile", with_gravity(pile, "[0, -1e290]"), "gravity",
                 "use a smaller gravity"),
        // |g| = 1e200 squares to inf: measured with hypot, not a dot product.
        bad_text("gravity 1e200 with 1e100 kg/m^2",
                 with_gravity(pile_value("density", "[1, 1e100]"), "[0, -1e200]"),
                 "pile.density[1]", "use a smaller density[1]"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
    // 6 x 0.25 x 1e280 x 9.81 x 2.84 = 4.2e281 J: within the limit, it runs.
    require_runs(pile_value("density", "[1, 1e280]"));
}

TEST_CASE("A listed or gas body whose weight overflows is exit 2 at its mass or density",
          "[extreme-input]") {
    const std::vector<BadFile> cases = {
        // 1e308 kg x 9.81 m/s^2 is inf: this ran into NaN and wrote a partial
        // trajectory over --out.
        bad_text("mass 1e308", ball_edit(R"("mass": 1)", R"("mass": 1e308)"), "bodies[1].mass",
                 "gives 'ball' a mass of 1e+308 kg, whose weight m |g| under the scene's "
                 "gravity overflows double precision"),
        // A box of half sides 1 m (4 m^2) at 2e307 kg/m^2: 8e307 kg, finite;
        // its weight 7.8e308 N is not.
        bad_text("density 2e307",
                 ball_edit(R"("shape": {"circle": 0.25}, "mass": 1)",
                           R"("shape": {"box": [1, 1]}, "density": 2e307)"),
                 "bodies[1].density", "use a smaller density or gravity"),
        // The gas block's bodies fall under the default gravity too.
        bad_text("gas mass 1e308", R"({"schema": "impulse/scene@1", "name": "drop-box",
  "dt": 0.01, "duration": 0.05,
  "gas": {"count": 4, "shape": {"circle": 0.1}, "mass": 1e308, "spacing": 0.5, "max_speed": 1}})",
                 "gas.mass", "gives each gas body a mass of 1e+308 kg, whose weight m |g|"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
    // 1e307 kg weighs 9.81e307 N, finite: it runs.
    require_runs(ball_edit(R"("mass": 1)", R"("mass": 1e307)"));
}

TEST_CASE("A mass or inertia below the smallest normal double is exit 2 at its key: 1/m is inf",
          "[extreme-input]") {
    // 1 / 1e-310 overflows; before, the first contact turned the run into
    // NaN blamed on "gravity, speeds, sizes, dt or duration".
    const std::vector<BadFile> cases = {
        bad_text("mass 1e-310", ball_edit(R"("mass": 1)", R"("mass": 1e-310)"), "bodies[1].mass",
                 "gives a mass of 1e-310 kg, below the smallest normal double"),
        bad_text("inertia 1e-310", ball_edit(R"("mass": 1)", R"("mass": 1, "inertia": 1e-310)"),
                 "bodies[1].inertia", "gives a moment of inertia of 1e-310 kg m^2"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
    // 1e-306 kg: its inertia m r^2 / 2 = 1e-306 / 32 = 3.1e-308 kg m^2 is
    // normal too, so both inverses are finite: it loads and runs.
    require_runs(ball_edit(R"("mass": 1)", R"("mass": 1e-306)"));
}

TEST_CASE("A contact band as wide as the thinnest body is exit 2 at solver.contact_tolerance",
          "[extreme-input]") {
    const std::string rule = "but the band in which bodies count as touching must be thinner "
                             "than the thinnest body";
    const std::vector<BadFile> cases = {
        bad_text(
            "contact_tolerance 1e300 in a pile",
            pile_solver(R"({"integrator": "verlet", "resting": true, "contact_tolerance": 1e300})"),
            "solver.contact_tolerance", rule),
        // The ball's inradius is its radius, 0.25 m: a band of exactly that is
        // refused (it must be below), naming the ball.
        bad_text("contact_tolerance equal to the ball's radius",
                 ball_solver(R"("contact_tolerance": 0.25)"), "solver.contact_tolerance",
                 "bodies[1] 'ball', whose inradius (half its thickness) is 0.25 m"),
        // A box's inradius is its smaller half extent: 0.1 m here.
        bad_text("contact_tolerance equal to a thin box's half thickness",
                 replace_once(ball_solver(R"("contact_tolerance": 0.1)"),
                              R"("shape": {"circle": 0.25})", R"("shape": {"box": [1, 0.1]})"),
                 "solver.contact_tolerance", "use a solver.contact_tolerance below 0.1 m"),
        // The default band, 1e-9 m, is wider than a ball of radius 1e-10 m.
        bad_text("the default band and a ball 2e-10 m across",
                 ball_edit(R"("circle": 0.25)", R"("circle": 1e-10)"), "solver.contact_tolerance",
                 "is 1e-09 m, but the band"),
        // A triangle 1e-15 m tall has no thickness in double precision (its
        // inradius rounds to -0): the shape is at fault, not the band, which
        // the sentence used to ask to be "below -0.0 m".
        bad_text("a triangle too flat to have a thickness",
                 ball_edit(R"("circle": 0.25)", R"("polygon": [[-0.1, 0], [0.1, 0], [0, 1e-15]])"),
                 "bodies[1].shape", "no thickness to double precision"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
    // Just below the ball's radius, it runs (toi_tolerance is not bound to it).
    require_runs(ball_solver(R"("contact_tolerance": 0.24999999999999997)"));
}

TEST_CASE("Walls thinner than twice the contact band are exit 2 at the block's wall_thickness",
          "[extreme-input]") {
    // A wall's inradius is half its thickness; it must be above
    // contact_tolerance (1e-9 m by default).
    const std::string gas = gas_scene("", R"(, "wall_thickness": 1e-300)");
    const std::vector<BadFile> cases = {
        bad_text(
            "pile walls 1e-300 m thick", pile_value("seed", "1, \"wall_thickness\": 1e-300"),
            "pile.wall_thickness",
            "makes 'floor' of the pile block, whose inradius (half its thickness) is 5e-301 m"),
        bad_text("pile walls 1e-300 m thick: the cure",
                 pile_value("seed", "1, \"wall_thickness\": 1e-300"), "pile.wall_thickness",
                 "use walls thicker than 2e-09 m"),
        bad_text("gas walls 1e-300 m thick", gas, "gas.wall_thickness",
                 "not more than solver.contact_tolerance 1e-09 m"),
        // Exactly twice the band: an inradius equal to it is refused.
        bad_text("pile walls 2e-9 m thick", pile_value("seed", "1, \"wall_thickness\": 2e-9"),
                 "pile.wall_thickness", "whose inradius (half its thickness) is 1e-09 m"),
        // A band wider than the pile's bodies is the band's fault, not the walls'.
        bad_text("thin walls and a band wider than the bodies",
                 replace_once(pile_solver(R"({"integrator": "verlet", "resting": true,
                                              "contact_tolerance": 1})"),
                              R"("seed": 1)", R"("seed": 1, "wall_thickness": 1e-300)"),
                 "solver.contact_tolerance", "must be thinner than the thinnest body"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
    // One ULP thicker than twice the band: it runs.
    require_runs(pile_value("seed", "1, \"wall_thickness\": 2.0000000000000004e-9"));
}

TEST_CASE("Gravity whose per-step fall time-stepping cannot cancel is exit 2 at gravity",
          "[extreme-input]") {
    const std::string time_stepping =
        R"({"integrator": "verlet", "resting": true, "resting_method": "time-stepping"})";
    const std::string within = "only for a fall within 281474.976710656 m";
    const std::vector<BadFile> cases = {
        // This ran to exit 0 without max-overlap: the first step left pairs
        // 0.29 m deep and every energy NaN.
        bad_text("gravity 1e200 with time-stepping",
                 with_gravity(pile_solver(time_stepping), "[0, -1e200]"), "gravity", within),
        bad_text("gravity 1e200 with auto and local stepping",
                 with_gravity(pile_solver(R"({"integrator": "verlet", "resting": true,
                                              "stepping": "local"})"),
                              "[0, -1e200]"),
                 "gravity", "gives a fall of |g| dt^2 = "),
        // 3e9 m/s^2 x (0.01 s)^2 = 3e5 m, past 2^48 x 1e-9 m = 2.8e5 m.
        bad_text("gravity 3e9 with time-stepping",
                 with_gravity(pile_solver(time_stepping), "[0, -3e9]"), "gravity", within),
        // The event model tests pairs at the step's ends: its bound is the
        // tunnelling refusal, which names the pile's faster body.
        bad_text("gravity 1e200 with events",
                 with_gravity(pile_solver(R"({"integrator": "verlet", "resting": true,
                                              "resting_method": "events"})"),
                              "[0, -1e200]"),
                 "pile", "could close at a speed that overflows double precision"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
    // At the edge: contact_tolerance 2^-48 m puts the limit at 1 m, and
    // g = 2^14 m/s^2 with dt = 2^-7 s falls exactly 2^14 x 2^-14 = 1 m per
    // step: it runs. One ULP more gravity is refused. The ball and a smaller
    // ground are moved within that 1 m of the origin, where the positions
    // of listed bodies must lie (docs/refusals-and-progress.md).
    const std::string near_origin =
        replace_once(replace_once(ball_solver(R"("resting": true, "resting_method": "time-stepping",
                                    "contact_tolerance": 3.552713678800501e-15)"),
                                  R"("shape": {"box": [5, 0.5]}, "position": [0, -0.5])",
                                  R"("shape": {"box": [0.4, 0.2]}, "position": [0, -0.2])"),
                     R"("position": [0, 2])", R"("position": [0, 0.5])");
    const std::string edge = replace_once(with_gravity(near_origin, "[0, -16384]"), R"("dt": 0.01)",
                                          R"("dt": 0.0078125)");
    require_runs(edge);
    require_scene_refused(bad_text("one ULP past the edge",
                                   replace_once(edge, "[0, -16384]", "[0, -16384.000000000004]"),
                                   "gravity", "only for a fall within 1 m"));
}

TEST_CASE("A first step's travel time-stepping cannot hold is exit 2 at the speed that gives it",
          "[extreme-input]") {
    const std::string time_stepping = R"("resting": true, "resting_method": "time-stepping")";
    const std::string ts_ball = ball_solver(time_stepping);
    const std::string within = "only for a step's travel within 281474.976710656 m";
    const std::string gas =
        gas_scene(R"(  "solver": {"integrator": "verlet", "resting": true, "stepping": "local"},
)",
                  "");
    const std::vector<BadFile> cases = {
        // These stopped at t = 0 with "use a smaller dt", which cannot help
        // at 1e20 m/s (1e18 m per step).
        bad_text("a ball at 1e20 m/s",
                 replace_once(ts_ball, R"("position": [0, 2])",
                              R"("position": [0, 2], "velocity": [0, -1e20])"),
                 "bodies[1].velocity", within),
        bad_text("a ball at 1e155 m/s with auto and local stepping",
                 replace_once(ball_solver(R"("resting": true, "stepping": "local")"),
                              R"("position": [0, 2])",
                              R"("position": [0, 2], "velocity": [1e155, 0])"),
                 "bodies[1].velocity", "moves 'ball' 1e+153 m in its first step"),
        // Turning: a square's corner 0.25 sqrt(2) m out x 1e20 rad/s x
        // 0.01 s (a spinning circle moves no point toward anything).
        bad_text("a square spinning at 1e20 rad/s",
                 replace_once(replace_once(ts_ball, R"("position": [0, 2])",
                                           R"("position": [0, 2], "angular_velocity": 1e20)"),
                              R"({"circle": 0.25})", R"({"box": [0.25, 0.25]})"),
                 "bodies[1].angular_velocity", "moves 'ball' 353553390593273792 m"),
        bad_text("a gas drawn up to 1e20 m/s",
                 replace_once(gas, "\"max_speed\": 1", "\"max_speed\": 1e20"), "gas.max_speed",
                 "moves the gas's fastest body 1e+18 m"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
    // The event model is bounded by the tunnelling refusal instead, which
    // names the pair.
    require_scene_refused(bad_text(
        "a ball at 1e20 m/s with events",
        replace_once(ball_solver(R"("resting": true, "resting_method": "events")"),
                     R"("position": [0, 2])", R"("position": [0, 2], "velocity": [0, -1e20])"),
        "bodies[1]", "could pass through the other between two steps"));
    // At the edge: contact_tolerance 2^-48 m puts the limit at 1 m, and 2^7
    // m/s for dt = 2^-7 s moves the ball exactly 1 m: it runs, sideways over
    // a ground held within that 1 m of the origin. One ULP faster is refused.
    const std::string near_origin = replace_once(
        replace_once(ball_solver(time_stepping + R"(, "contact_tolerance": 3.552713678800501e-15)"),
                     R"("shape": {"box": [5, 0.5]}, "position": [0, -0.5])",
                     R"("shape": {"box": [0.4, 0.2]}, "position": [0, -0.2])"),
        R"("position": [0, 2])", R"("position": [0, 0.5], "velocity": [128, 0])");
    const std::string edge = replace_once(near_origin, R"("dt": 0.01)", R"("dt": 0.0078125)");
    require_runs(edge);
    require_scene_refused(bad_text("one ULP past the edge",
                                   replace_once(edge, "[128, 0]", "[128.00000000000003, 0]"),
                                   "bodies[1].velocity", "only for a step's travel within 1 m"));
}

TEST_CASE("An energy that is not finite fails energy-non-increasing without a contradiction",
          "[extreme-input]") {
    // 1/2 1e300 kg (1e5 m/s)^2 = 5e309 J is inf. The weight is 0 (no
    // gravity), so the scene loads, runs, and the gate says why it cannot
    // judge: not "expected 0, got 0" beside an inf, nor "rose by NaN J".
    const std::string text =
        R"({"schema":"impulse/scene@1","name":"x","gravity":[0,0],"dt":0.01,"duration":0.05,)"
        R"("bodies":[{"name":"a","shape":{"circle":0.5},"mass":1e300,"velocity":[1e5,0]}],)"
        R"("expectations":[{"kind":"energy-non-increasing","rtol":1e-15}]})";
    const TempDir dir;
    const fs::path scene = dir.dir / "scene.json";
    spit(scene, text);
    const Outcome o = run_tool({"run", scene.string(), "--out", (dir.dir / "t.json").string()});
    INFO(o.err);
    CHECK(o.exit_code == 1);
    CHECK(o.err.rfind(scene.string() + ": expectations[0]: energy non-increasing", 0) == 0);
    CHECK(o.err.find("the energy is inf J at t = ") != std::string::npos);
    CHECK(o.err.find("beyond double precision") != std::string::npos);
    CHECK(o.err.find("expected 0, got 0") == std::string::npos);
    CHECK(o.err.find("rose by") == std::string::npos);
}
