// Issue 14's input surface, adversarially, through the real tool: the pile
// block, the solver keys resting, resting_method, stepping and contacts, and
// the expectation kinds max-overlap and at-rest. Every bad value ends in exit
// code 2 and one sentence naming the file and the JSON path, with nothing
// written, no --out file destroyed and no golden touched
// (support/bad_input.h runs each case through run, render, check and bless).
//
// The rules themselves are in docs/formats.md ("The pile block", the solver
// table, "Expectations"); test_pile.cpp checks the generator.
#include "support/bad_input.h"
#include "support/input_pile.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;

namespace {

// A valid pile scene (support/input_pile.h) with both pile expectations;
// every case below changes one thing in it.
const std::string valid_pile = input_pile(R"(  "expectations": [
    {"kind": "max-overlap", "atol": 1e-6},
    {"kind": "at-rest", "after": 0.05, "rtol": 1e9}
  ])");

std::string pile_edit(const std::string& from, const std::string& to) {
    return replace_once(valid_pile, from, to);
}

// The pile block's line with one member's value replaced.
std::string pile_value(const std::string& key, const std::string& value) {
    return with_pile_value(valid_pile, key, value);
}

std::string solver(const std::string& block) {
    return with_pile_solver(valid_pile, block);
}

const std::string at_rest = R"({"kind": "at-rest", "after": 0.05, "rtol": 1e9})";
const std::string max_overlap = R"({"kind": "max-overlap", "atol": 1e-6})";

std::string scene_at(const TempDir& dir, const std::string& text) {
    const fs::path scene = dir.dir / "scene.json";
    spit(scene, text);
    return scene.string();
}

} // namespace

TEST_CASE("The pile scene the input cases start from is valid", "[pile-input]") {
    const TempDir dir;
    const Outcome o = run_tool({"run", scene_at(dir, valid_pile)});
    INFO(o.err);
    CHECK(o.exit_code == 0);
    CHECK(o.err.empty());
    CHECK(o.out.find("\"pile-5.x\"") != std::string::npos);
}

TEST_CASE("A pile's count, shape, seed or keys out of range is exit 2 naming pile.KEY",
          "[pile-input]") {
    const std::string count_rule = "must be a whole number from 1 to 100000, got ";
    const std::string seed_rule = "must be a whole number from 0 to 9007199254740992, got ";
    const std::vector<BadFile> cases = {
        bad_text("count 0", pile_value("count", "0"), "pile.count", count_rule + "0"),
        bad_text("count -1", pile_value("count", "-1"), "pile.count", count_rule + "-1"),
        bad_text("count 1.5", pile_value("count", "1.5"), "pile.count", count_rule + "1.5"),
        bad_text("count 2^31", pile_value("count", "2147483648"), "pile.count",
                 count_rule + "2147483648"),
        bad_text("count 10^7: refused before anything is allocated", pile_value("count", "1e7"),
                 "pile.count", count_rule + "1e+07"),
        bad_text("count a string", pile_value("count", "\"6\""), "pile.count",
                 "must be a number, got \"6\""),
        bad_text("count missing", pile_edit(R"("count": 6, )", ""), "pile.count",
                 "is required but missing"),
        bad_text("columns 0", pile_edit(R"("seed": 1)", R"("seed": 1, "columns": 0)"),
                 "pile.columns", count_rule + "0"),
        bad_text("shape unknown", pile_value("shape", "\"triangle\""), "pile.shape",
                 "must be one of \"circle\", \"box\" or \"mixed\", got \"triangle\""),
        bad_text("shape a body's shape object", pile_value("shape", R"({"polygon": []})"),
                 "pile.shape", "must be one of \"circle\", \"box\" or \"mixed\", got an object"),
        bad_text("seed negative", pile_value("seed", "-1"), "pile.seed", seed_rule + "-1"),
        bad_text("seed 1e20", pile_value("seed", "1e20"), "pile.seed", seed_rule + "1e+20"),
        bad_text("seed not whole", pile_value("seed", "1.5"), "pile.seed", seed_rule + "1.5"),
        bad_text("random_angles not a bool",
                 pile_edit(R"("seed": 1)", R"("seed": 1, "random_angles": "yes")"),
                 "pile.random_angles", "must be true or false, got \"yes\""),
        bad_text("an unknown key", pile_edit(R"("seed": 1)", R"("seed": 1, "colour": "red")"),
                 "pile.colour", "unknown key"),
        bad_text("the block an array", pile_edit(line_of(valid_pile, "pile"), R"(  "pile": [6],)"),
                 "pile", "must be an object, got an array"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A pile's size or density out of range is exit 2 naming the entry to change",
          "[pile-input]") {
    const std::vector<BadFile> cases = {
        bad_text("size [0, 0]", pile_value("size", "[0, 0]"), "pile.size[0]", "must be > 0, got 0"),
        bad_text("size inverted", pile_value("size", "[0.25, 0.05]"), "pile.size",
                 "must be [min, max] with min <= max, got [0.25, 0.05]"),
        bad_text("size negative", pile_value("size", "[-0.1, 0.2]"), "pile.size[0]",
                 "must be > 0, got -0.1"),
        bad_text("size \"NaN\"", pile_value("size", "[\"NaN\", 0.2]"), "pile.size[0]",
                 "must be a number, got \"NaN\""),
        bad_text("size one number", pile_value("size", "[0.1]"), "pile.size",
                 "must be [min, max] in m, got 1 values"),
        // A circle of radius 1e-160: area pi 1e-320 is a subnormal above 0,
        // its inertia m r^2 / 2 ~ 1e-640 is 0 in double.
        bad_text("size so small the inertia underflows", pile_value("size", "[1e-160, 1e-160]"),
                 "pile.size[0]",
                 "gives the lightest circle the block can draw (size 1e-160 m, density 1 "
                 "kg/m^2) a moment of inertia of 0 kg m^2"),
        // pi 1e-600 underflows to 0 before any density multiplies it.
        bad_text("size so small the mass underflows", pile_value("size", "[1e-300, 1e-300]"),
                 "pile.size[0]", "a mass of 0 kg"),
        // Largest bounding diameter 2 sqrt(2) 1e300 > spacing 0.71.
        bad_text("size huge", pile_value("size", "[0.1, 1e300]"), "pile.spacing",
                 "must be more than the largest body's bounding diameter"),
        bad_text("density 0", pile_value("density", "[0, 1]"), "pile.density[0]",
                 "must be > 0, got 0"),
        bad_text("density negative", pile_value("density", "[-1, 1]"), "pile.density[0]",
                 "must be > 0, got -1"),
        bad_text("density inverted", pile_value("density", "[4, 1]"), "pile.density",
                 "must be [min, max] with min <= max, got [4, 1]"),
        // The lightest circle, r = 0.05: m = 1e-320 pi 0.0025, a subnormal;
        // I = m r^2 / 2 underflows to 0. At 1 kg/m^2 it would be fine, so the
        // density is what to change.
        bad_text("density so small the inertia underflows", pile_value("density", "[1e-320, 4]"),
                 "pile.density[0]",
                 "gives the lightest circle the block can draw (size 0.05 m, density 1e-320 "
                 "kg/m^2) a moment of inertia of 0 kg m^2"),
        // The heaviest circle, r = 5: m = 1e308 pi 25 overflows.
        bad_text("density so large the mass overflows",
                 pile_edit(R"("size": [0.05, 0.25], "density": [1, 4], "spacing": 0.71)",
                           R"("size": [0.05, 5], "density": [1, 1e308], "spacing": 15)"),
                 "pile.density[1]",
                 "gives the heaviest circle the block can draw (size 5 m, density 1e+308 "
                 "kg/m^2) a mass of inf kg"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A pile's spacing or walls out of range is exit 2 naming pile.spacing or "
          "pile.wall_thickness",
          "[pile-input]") {
    // Six bodies on 3 columns and 2 rows: the box reaches max(3 s / 2 + w,
    // 2 * 2 s) from the origin, 4 s for the default wall w = 1 m and a large
    // spacing s; the limit is 2^48 contact tolerances, 281474.976710656 m at
    // the default 1e-9 m.
    const std::string limit = "only within 281474.976710656 m of it";
    const std::vector<BadFile> cases = {
        bad_text("spacing 0", pile_value("spacing", "0"), "pile.spacing", "must be > 0, got 0"),
        bad_text("spacing negative", pile_value("spacing", "-1"), "pile.spacing",
                 "must be > 0, got -1"),
        // A square of half side 0.25 spans 2 sqrt(2) 0.25 = 0.7071... at 45 degrees.
        bad_text("spacing below the largest body's diagonal: overlapping at release",
                 pile_value("spacing", "0.5"), "pile.spacing",
                 "must be more than the largest body's bounding diameter 0.7071067811865476 m"),
        bad_text("spacing 1e154: a box that squares to infinity", pile_value("spacing", "1e154"),
                 "pile.spacing", "gives a box reaching 4e+154 m from the origin"),
        bad_text("spacing 1e300", pile_value("spacing", "1e300"), "pile.spacing", limit),
        bad_text("spacing 1e5: the box beyond the limit", pile_value("spacing", "1e5"),
                 "pile.spacing", "gives a box reaching 4e+05 m from the origin"),
        bad_text("wall_thickness 0", pile_edit(R"("seed": 1)", R"("seed": 1, "wall_thickness": 0)"),
                 "pile.wall_thickness", "must be > 0, got 0"),
        // 1.065 + 1e17 rounds to 1e17: the wall's face is lost to rounding.
        bad_text("wall_thickness 1e17",
                 pile_edit(R"("seed": 1)", R"("seed": 1, "wall_thickness": 1e17)"),
                 "pile.wall_thickness", "gives a box reaching 1e+17 m from the origin"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("The gas block's room is held to the pile's limit, at gas.spacing or "
          "gas.wall_thickness",
          "[pile-input]") {
    // Four bodies on a 2 x 2 lattice: the room reaches spacing + wall_thickness
    // from the origin (docs/formats.md, the gas block's step 2). Spacing 1e200
    // ran into NaN positions and wrote a partial trajectory over --out.
    const std::string gas = R"({
  "schema": "impulse/scene@1",
  "name": "drop-box",
  "gravity": [0, 0],
  "dt": 0.01,
  "duration": 0.05,
  "gas": {"count": 4, "shape": {"circle": 0.1}, "mass": 1, "spacing": 0.5, "max_speed": 1}
}
)";
    const std::vector<BadFile> cases = {
        bad_text("gas spacing 1e200", replace_once(gas, R"("spacing": 0.5)", R"("spacing": 1e200)"),
                 "gas.spacing", "gives a room reaching 1e+200 m from the origin"),
        bad_text(
            "gas walls 1e17 thick",
            replace_once(gas, R"("max_speed": 1)", R"("max_speed": 1, "wall_thickness": 1e17)"),
            "gas.wall_thickness", "gives a room reaching 1e+17 m from the origin"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A pile beside listed bodies or another block is exit 2 naming the pile",
          "[pile-input]") {
    const auto with_bodies = [](const std::string& bodies) {
        return pile_edit(R"(  "pile": )", "  \"bodies\": [" + bodies + "],\n  \"pile\": ");
    };
    // Three columns at spacing 0.71 from x = -1.065: pile-1 sits at (0, 0.355).
    const std::vector<BadFile> cases = {
        bad_text("a listed body named like a generated one",
                 with_bodies(R"({"name": "pile-5", "shape": {"circle": 0.1}, "position": [9, 9]})"),
                 "pile", "makes a body named \"pile-5\", which is already the name of bodies[0]"),
        bad_text("a listed body named floor",
                 with_bodies(R"({"name": "floor", "shape": {"circle": 0.1}, "position": [9, 9]})"),
                 "pile", "makes a body named \"floor\""),
        bad_text("a listed body inside the pile",
                 with_bodies(R"({"name": "x", "shape": {"circle": 0.1}, "position": [0, 0.4]})"),
                 "pile", "which overlaps bodies[0] 'x' at t = 0"),
        bad_text("a gas block too",
                 pile_edit(R"(  "pile": )", R"(  "gas": {"count": 4, "shape": {"circle": 0.1},
  "mass": 1, "spacing": 0.5, "max_speed": 1},
  "pile": )"),
                 "pile", "a scene has a gas block or a pile block, not both"),
        // Grains 2 mm thick dropped 95 m in a 10 m lattice, without resting
        // contact: 10 rows fall up to sqrt(2 g 95) ~ 43 m/s, 0.43 m per step.
        bad_text(
            "generated bodies that could tunnel are named at pile",
            replace_once(
                replace_once(
                    solver(R"({"integrator": "verlet"})"), line_of(valid_pile, "pile"),
                    R"(  "pile": {"count": 100, "shape": "circle", "size": [0.001, 0.001], "spacing": 10},)"),
                R"("duration": 0.05)", R"("duration": 10)"),
            "pile", "'pile-0' and 'pile-1' close at up to"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A dense-contact solver setting out of range is exit 2 naming solver.KEY",
          "[pile-input]") {
    const std::vector<BadFile> cases = {
        bad_text("resting_method unknown",
                 solver(R"({"resting": true, "resting_method": "magic"})"), "solver.resting_method",
                 "must be \"auto\" (the default), \"events\" or \"time-stepping\", got \"magic\""),
        bad_text("resting_method with resting false",
                 solver(R"({"resting": false, "resting_method": "auto"})"), "solver.resting_method",
                 "needs \"resting\": true in the solver block"),
        bad_text("resting_method without resting", solver(R"({"resting_method": "time-stepping"})"),
                 "solver.resting_method", "needs \"resting\": true"),
        bad_text("resting not a bool", solver(R"({"resting": "true"})"), "solver.resting",
                 "must be true or false, got \"true\""),
        bad_text("events with local stepping",
                 solver(R"({"resting": true, "stepping": "local", "resting_method": "events"})"),
                 "solver.resting_method",
                 "\"events\" is not available with \"stepping\": \"local\""),
        bad_text("simultaneous contacts with local stepping",
                 solver(R"({"resting": true, "stepping": "local", "contacts": "simultaneous"})"),
                 "solver.contacts", "is not available with \"stepping\": \"local\""),
        bad_text("simultaneous contacts with time-stepping, which would ignore them",
                 solver(R"({"resting": true, "resting_method": "time-stepping",
                            "contacts": "simultaneous"})"),
                 "solver.contacts", "is not used with \"resting_method\": \"time-stepping\""),
        bad_text("stepping unknown", solver(R"({"stepping": "Local"})"), "solver.stepping",
                 "must be \"world\" (the seed's) or \"local\", got \"Local\""),
        bad_text("duration 0", pile_edit(R"("duration": 0.05)", R"("duration": 0)"), "duration",
                 "must be > 0, got 0"),
        bad_text("dt longer than the duration", pile_edit(R"("dt": 0.01)", R"("dt": 1)"),
                 "duration", "must be >= dt (1), got 0.05"),
        bad_text("dt 1e-12 over 10 s",
                 pile_edit(R"("dt": 0.01,
  "duration": 0.05)",
                           R"("dt": 1e-12,
  "duration": 10)"),
                 "duration", "gives 10000000000000 steps; at most 10000000 are allowed"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A max-overlap or at-rest expectation out of range is exit 2 naming its key",
          "[pile-input]") {
    const auto rest = [](const std::string& entry) { return pile_edit(at_rest, entry); };
    const std::vector<BadFile> cases = {
        bad_text("at-rest without after", rest(R"({"kind": "at-rest", "rtol": 1e-9})"),
                 "expectations[1].after", "is required but missing"),
        bad_text("at-rest after negative", rest(R"({"kind": "at-rest", "after": -1, "rtol": 1})"),
                 "expectations[1].after", "must be >= 0, got -1"),
        bad_text("at-rest after the run",
                 rest(R"({"kind": "at-rest", "after": 0.0500001, "rtol": 1})"),
                 "expectations[1].after",
                 "must be at most the scene's duration 0.05 s, so that some frame is judged"),
        bad_text("at-rest rtol negative", rest(R"({"kind": "at-rest", "after": 0, "rtol": -1})"),
                 "expectations[1].rtol", "must be >= 0, got -1"),
        bad_text("at-rest rtol \"NaN\"", rest(R"({"kind": "at-rest", "after": 0, "rtol": "NaN"})"),
                 "expectations[1].rtol", "must be a number, got \"NaN\""),
        bad_text("at-rest with atol only", rest(R"({"kind": "at-rest", "after": 0, "atol": 1})"),
                 "expectations[1]", "an at-rest expectation must give rtol"),
        bad_text("at-rest with a body", rest(R"({"kind": "at-rest", "after": 0, "rtol": 1,
                                                "body": "pile-0"})"),
                 "expectations[1].body", "unknown key"),
        bad_text("max-overlap atol negative",
                 pile_edit(max_overlap, R"({"kind": "max-overlap", "atol": -1})"),
                 "expectations[0].atol", "must be >= 0, got -1"),
        bad_text("max-overlap with rtol",
                 pile_edit(max_overlap, R"({"kind": "max-overlap", "rtol": 1})"),
                 "expectations[0].rtol", "max-overlap judges a depth in metres against atol alone"),
        bad_text("max-overlap without a tolerance",
                 pile_edit(max_overlap, R"({"kind": "max-overlap"})"), "expectations[0]",
                 "must give atol or rtol (or both)"),
        bad_text(
            "energy-non-increasing with after",
            pile_edit(max_overlap, R"({"kind": "energy-non-increasing", "rtol": 0, "after": 1})"),
            "expectations[0].after", "unknown key"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("A pile scene that is not well-formed JSON is exit 2 and writes nothing",
          "[pile-input]") {
    const std::vector<BadFile> cases = {
        bad_text("cut inside the pile block", valid_pile.substr(0, valid_pile.find("\"spacing\"")),
                 std::nullopt, "not valid JSON"),
        bad_text("a shape name that is not UTF-8", pile_value("shape", "\"mi\xffxed\""),
                 "pile.shape", "ill-formed UTF-8"),
        bad_text("nested 10000 levels deep in the pile",
                 pile_value("seed", std::string(10000, '[') + std::string(10000, ']')), "",
                 "is nested too deeply"),
    };
    for (const BadFile& bad : cases) {
        require_scene_refused(bad);
    }
}

TEST_CASE("The pile's box may reach exactly 2^48 contact tolerances from the origin, no further",
          "[pile-input]") {
    // contact_tolerance 2^-48 m puts the limit at exactly 1 m. One circle of
    // radius 0.1 on one site at spacing s with walls w reaches max(s / 2 + w,
    // 2 s): spacing 0.5 and walls 0.75 reach 1 m both ways, on the limit. One ULP
    // more of spacing (2 s) or two of wall (0.25 + w; one rounds back to 1)
    // is over it.
    const std::string at_limit = R"({"schema": "impulse/scene@1", "name": "edge", "dt": 0.01,
  "duration": 0.02, "solver": {"contact_tolerance": 3.552713678800501e-15},
  "pile": {"count": 1, "shape": "circle", "size": [0.1, 0.1], "spacing": 0.5, "wall_thickness": 0.75}})";
    const TempDir dir;
    const fs::path out = dir.dir / "edge.json";
    const Outcome ran = run_tool({"run", scene_at(dir, at_limit), "--out", out.string()});
    INFO(ran.err);
    CHECK(ran.exit_code == 0);
    CHECK(fs::exists(out));

    const fs::path existing = dir.dir / "existing.json";
    spit(existing, "kept\n");
    const auto refused_at = [&](const std::string& text, const std::string& path) {
        const std::string scene = scene_at(dir, text);
        check_refused(run_tool({"run", scene, "--out", existing.string()}), scene, path,
                      "but positions resolve the contact tolerance only within 1 m of it");
        CHECK(slurp(existing) == "kept\n");
    };
    refused_at(replace_once(at_limit, R"("spacing": 0.5,)", R"("spacing": 0.5000000000000001,)"),
               "pile.spacing");
    refused_at(replace_once(at_limit, R"("wall_thickness": 0.75})",
                            R"("wall_thickness": 0.7500000000000002})"),
               "pile.wall_thickness");
}

TEST_CASE("Simultaneous contacts stay one setting away: accepted with resting_method auto",
          "[pile-input]") {
    // auto with world stepping may run the event model, which contacts
    // chooses for; only time-stepping, which ignores it, refuses it.
    const TempDir dir;
    const Outcome o = run_tool(
        {"run", scene_at(dir, solver(R"({"resting": true, "contacts": "simultaneous"})"))});
    INFO(o.err);
    CHECK(o.exit_code == 0);
    CHECK(o.err.empty());
}
