// The dense-contact expectations `max-overlap` and `at-rest` (docs/formats.md):
// judged through the real binary on runs whose answers physics gives, read
// strictly, and fed made-up violations in process.
#include "expectations.h"
#include "scene.h"
#include "support/files.h"
#include "support/outcome.h"
#include "support/scene_text.h"
#include "support/tool.h"
#include "support/trajectories.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse::test;
using impulse::harness::ExpectationResult;

namespace {

constexpr double g = 9.81;

// A disc of radius 0.5 released with its lowest point 1 m above static ground.
// Its first impact is at t1 = sqrt(2 / g); with e = 1 it bounces back to 1 m
// forever, so its energy is all released at every impact, t1 (2n + 1).
std::string bouncing_ball(double e, const std::string& solver, double duration,
                          const std::string& expectations) {
    return R"({"schema":"impulse/scene@1","name":"b","restitution":)" + std::to_string(e) +
           R"(,"dt":0.016666666666666666,"duration":)" + std::to_string(duration) + "," + solver +
           R"("bodies":[{"name":"ground","static":true,"shape":{"box":[5,0.5]},"position":[0,-0.5]},
             {"name":"ball","shape":{"circle":0.5},"mass":1,"position":[0,1.5]}],
             "expectations":[)" +
           expectations + "]}";
}

// The time quoted after `lead` in a message, e.g. "not at rest at t = 1.35 s".
double time_after(const std::string& text, const std::string& lead) {
    const std::size_t at = text.find(lead);
    REQUIRE(at != std::string::npos);
    return std::stod(text.substr(at + lead.size()));
}

Outcome run_scene(const TempDir& tmp, const std::string& text) {
    const fs::path scene = tmp.dir / "s.json";
    spit(scene, text);
    return run_tool({"run", scene.string(), "--out", (tmp.dir / "t.json").string()});
}

} // namespace

TEST_CASE("at-rest fails on a ball that bounces forever, naming the time of an impact",
          "[rest-expectations]") {
    const TempDir tmp;
    const Outcome o = run_scene(tmp, bouncing_ball(1.0, R"("solver":{"integrator":"verlet"},)", 2.0,
                                                   R"({"kind":"at-rest","after":1,"rtol":0.001})"));
    require_exit(o, 1);
    CHECK(has(o.err, "expectations[0]: at rest from t = 1 s"));
    // With e = 1 (and verlet, exact in free fall) the kinetic energy is all the
    // energy released, so the worst frame is the one nearest the speed's peak,
    // at the impact 3 t1.
    const double t1 = std::sqrt(2.0 / g);
    CHECK(std::abs(time_after(o.err, "not at rest at t = ") - 3.0 * t1) <= 1.0 / 60.0);
}

TEST_CASE("at-rest passes on drop-rest after its cascade ends, and fails before it",
          "[rest-expectations]") {
    // drop-rest (harness/scenes/drop-rest.json): e = 0.5, resting on; the
    // cascade of bounces ends at t_inf = t1 (1 + e) / (1 - e) = 3 t1 = 1.355 s
    // (docs/physics.md), after which the ball lies still.
    const double t_inf = 3.0 * std::sqrt(2.0 / g);
    const std::string solver = R"("solver":{"integrator":"verlet","toi":"secant","resting":true},)";
    const TempDir tmp;
    const std::string after = std::to_string(t_inf + 0.05);
    const Outcome rests =
        run_scene(tmp, bouncing_ball(0.5, solver, 2.0,
                                     R"({"kind":"at-rest","after":)" + after + R"(,"rtol":1e-9})"));
    require_exit(rests, 0);

    // From t1 / 2 the ball is still falling to its first impact, with all
    // that it released as kinetic energy.
    const double t1 = std::sqrt(2.0 / g);
    const Outcome moving =
        run_scene(tmp, bouncing_ball(0.5, solver, 2.0,
                                     R"({"kind":"at-rest","after":)" + std::to_string(t1 / 2.0) +
                                         R"(,"rtol":1e-9})"));
    require_exit(moving, 1);
    CHECK(time_after(moving.err, "not at rest at t = ") < t_inf);
}

TEST_CASE("max-overlap passes on the canonical stack of ten boxes", "[rest-expectations]") {
    nlohmann::json stack =
        nlohmann::json::parse(slurp(fs::path(IMPULSE_SOURCE_DIR) / "harness/scenes/stack.json"));
    stack["duration"] = 2.0;
    stack["expectations"] = nlohmann::json::parse(
        R"([{"kind":"max-overlap","atol":1e-6},{"kind":"at-rest","after":0,"rtol":1e-9,"atol":1e-12}])");
    stack.erase("box2d");
    // Built at rest, the stack releases nothing: released(t) is 0 up to the
    // rounding of its potential energy (about 1e-13 J of some 500 J), which
    // may be negative, so at-rest needs an atol here, far above K's rounding.
    const TempDir tmp;
    require_exit(run_scene(tmp, stack.dump()), 0);
}

TEST_CASE("max-overlap and at-rest are read strictly, one sentence with the JSON path",
          "[rest-expectations]") {
    const TempDir tmp;
    struct Bad {
        std::string expectation;
        std::string where;
        std::string says;
    };
    const std::vector<Bad> bad = {
        {R"({"kind":"max-overlap","rtol":1e-6})", "expectations[0].rtol", "atol alone"},
        {R"({"kind":"max-overlap"})", "expectations[0]", "atol"},
        {R"({"kind":"max-overlap","atol":-1})", "expectations[0].atol", ""},
        {R"({"kind":"max-overlap","atol":1e-6,"after":1})", "expectations[0].after", "unknown key"},
        {R"({"kind":"at-rest","rtol":1e-9})", "expectations[0].after", "required"},
        {R"({"kind":"at-rest","after":1,"atol":1e-9})", "expectations[0]", "must give rtol"},
        {R"({"kind":"at-rest","after":3,"rtol":1e-9})", "expectations[0].after", "duration 2 s"},
        {R"({"kind":"at-rest","after":-1,"rtol":1e-9})", "expectations[0].after", ""},
        {R"({"kind":"at-rest","after":"1","rtol":1e-9})", "expectations[0].after", ""},
        // rtol times the energies the gate sums must stay finite (1e308 of it
        // overflowed to an infinite bound, and a run at rest then failed "0 J
        // is more than inf J"); 2^60 is the bound, 1.2e18 just past it.
        {R"({"kind":"at-rest","after":1,"rtol":1.2e18})", "expectations[0].rtol", "at most 2^60"},
        {R"({"kind":"at-rest","after":1,"rtol":1e308})", "expectations[0].rtol", "at most 2^60"},
    };
    for (const Bad& b : bad) {
        const fs::path scene = tmp.dir / "s.json";
        const fs::path out = tmp.dir / "t.json";
        spit(out, "kept");
        spit(scene, bouncing_ball(0.5, "", 2.0, b.expectation));
        const Outcome o = run_tool({"run", scene.string(), "--out", out.string()});
        INFO(b.expectation << "\n" << o.err);
        require_exit(o, 2);
        CHECK(o.err.rfind(scene.string() + ": " + b.where + ": ", 0) == 0);
        CHECK(has(o.err, b.says));
        CHECK(o.err.find('\n') == o.err.size() - 1);
        CHECK(slurp(out) == "kept");
    }
}

TEST_CASE("made-up violations: the overlap's pair and time, the moving frame's time",
          "[rest-expectations]") {
    // Two discs of radius 0.5 on no ground, no gravity: at t = 1 their centres
    // are 0.9 apart (0.1 deep), at t = 2 0.95 apart; b moves at t = 2 only.
    const impulse::harness::Scene scene = impulse::harness::parse_scene(
        R"({"schema":"impulse/scene@1","name":"m","dt":1,"duration":2,"gravity":[0,0],
            "bodies":[{"name":"a","shape":{"circle":0.5},"mass":2},
                      {"name":"b","shape":{"circle":0.5},"mass":2,"position":[2,0]}],
            "expectations":[{"kind":"max-overlap","atol":0.01},
                            {"kind":"at-rest","after":1,"rtol":0,"atol":0.5}]})",
        test_file);
    const impulse::harness::Trajectory t =
        trajectory_of({"a", "b"},
                      {{0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0},
                       {1, 0, 0, 0, 0, 0, 0, 0.9, 0, 0, 0, 0, 0},
                       {2, 0, 0, 0, 0, 0, 0, 0.95, 0, 0, 1, 0, 0}},
                      {});
    const std::vector<ExpectationResult> results =
        impulse::harness::evaluate_expectations(scene, t);
    REQUIRE(results.size() == 2);
    CHECK_FALSE(results[0].passed);
    CHECK(has(results[0].what, "'a' and 'b' at t = 1 s"));
    CHECK(results[0].actual == Approx(0.1).margin(1e-12));
    // b's kinetic energy at t = 2 is 2 x 1^2 / 2 = 1 J, more than the 0.5 J allowed.
    CHECK_FALSE(results[1].passed);
    CHECK(has(results[1].what, "at t = 2 s"));
    CHECK(results[1].actual == 1.0);
    CHECK(results[1].allowed == 0.5);
}
