// `impulse sweep`: the grid, its error and work measurements, the Pareto
// fronts and the verb's outputs. No test limits wall-clock time.
#include "cli.h"
#include "input_error.h"
#include "scene.h"
#include "sweep.h"
#include "sweep_plot.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace impulse;
using namespace impulse::harness;

namespace {

std::string drop_box_path() {
    return std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes/drop-box.json";
}

SweepConfig small_config(const Scene& scene) {
    SweepConfig config = default_sweep_config(scene);
    config.dts = {1.0 / 60.0, 1.0 / 240.0};
    // The scene's own tolerance: an impact time is exact to within
    // toi_tolerance, so 1e-9 s would already be a relative error of 2e-9.
    config.toi_tolerances = {1e-12};
    config.box2d = false;
    config.repeats = 2;
    return config;
}

// Well-formed enough for any XML reader: one root, every tag closed in order,
// attributes quoted, no bare '&' or '<' in text.
bool well_formed_xml(const std::string& text, std::string& why) {
    std::vector<std::string> open;
    std::size_t i = 0;
    int roots = 0;
    while (i < text.size()) {
        if (text[i] == '&') {
            const std::size_t semi = text.find(';', i);
            if (semi == std::string::npos || semi - i > 6) {
                why = "bare & at " + std::to_string(i);
                return false;
            }
        }
        if (text[i] != '<') {
            ++i;
            continue;
        }
        const std::size_t close = text.find('>', i);
        if (close == std::string::npos) {
            why = "unclosed tag at " + std::to_string(i);
            return false;
        }
        const std::string tag = text.substr(i + 1, close - i - 1);
        i = close + 1;
        if (tag.empty() || tag.find('<') != std::string::npos) {
            why = "bad tag '" + tag + "'";
            return false;
        }
        if (tag.front() == '?') {
            continue;
        }
        std::size_t quotes = 0;
        for (const char c : tag) {
            quotes += c == '"' ? 1 : 0;
        }
        if (quotes % 2 != 0) {
            why = "unbalanced quotes in '" + tag + "'";
            return false;
        }
        if (tag.front() == '/') {
            if (open.empty() || open.back() != tag.substr(1)) {
                why = "unexpected </" + tag.substr(1) + ">";
                return false;
            }
            open.pop_back();
            continue;
        }
        const std::string name = tag.substr(0, tag.find_first_of(" \n/"));
        if (open.empty()) {
            ++roots;
        }
        if (tag.back() != '/') {
            open.push_back(name);
        }
    }
    if (!open.empty() || roots != 1) {
        why = "unclosed <" + (open.empty() ? std::string("?") : open.back()) + "> or " +
              std::to_string(roots) + " roots";
        return false;
    }
    return true;
}

} // namespace

TEST_CASE("The Pareto front keeps exactly the non-dominated points", "[sweep]") {
    // (cost, error)
    const std::vector<std::pair<double, double>> points = {
        {1.0, 1e-2}, // 0: front (cheapest)
        {2.0, 1e-3}, // 1: front
        {2.5, 1e-2}, // 2: dominated by 0 and 1
        {3.0, 1e-6}, // 3: front
        {4.0, 1e-6}, // 4: dominated by 3 (same error, more cost)
        {3.0, 1e-5}, // 5: dominated by 3 (same cost, more error)
        {5.0, 1e-9}, // 6: front
        {0.5, 1.0},  // 7: front (cheapest of all)
        {6.0, 1e-3}, // 8: dominated
    };
    CHECK(pareto_front(points) == std::vector<std::size_t>{7, 0, 1, 3, 6});
    // Identical points do not dominate each other.
    CHECK(pareto_front({{1.0, 1.0}, {1.0, 1.0}}) == std::vector<std::size_t>{0, 1});
    CHECK(pareto_front({}).empty());

    // Fronts are per family.
    std::vector<SweepPoint> sweep(3);
    for (SweepPoint& p : sweep) {
        p.ok = true;
    }
    sweep[0].family = "a";
    sweep[0].cost_median = 1.0;
    sweep[0].error = 1.0;
    sweep[1].family = "a";
    sweep[1].cost_median = 2.0;
    sweep[1].error = 2.0;
    sweep[2].family = "b"; // dominated by sweep[0], but in its own family
    sweep[2].cost_median = 3.0;
    sweep[2].error = 3.0;
    mark_fronts(sweep);
    CHECK(sweep[0].on_front);
    CHECK_FALSE(sweep[1].on_front);
    CHECK(sweep[2].on_front);
}

TEST_CASE("Sweep error on drop-box is exact to rounding for verlet and rk4, not euler", "[sweep]") {
    const Scene scene = load_scene(drop_box_path());
    const SweepResult result = run_sweep(scene, small_config(scene));
    CHECK(result.against_exact);
    CHECK(result.error_reference.find("exact answers") != std::string::npos);
    REQUIRE(result.points.size() == 2 * 4 * 2 * 1);
    for (const SweepPoint& p : result.points) {
        INFO(p.family << " dt " << p.dt << ": " << p.failure);
        if (p.integrator == Integrator::symplectic_euler) {
            // Its bounces die out sooner: a Zeno cascade inside the scene at
            // coarse steps, which the sweep reports as a failed point.
            CHECK((p.ok || p.failure.find("Zeno") != std::string::npos ||
                   p.failure.find("resting contact") != std::string::npos));
            continue;
        }
        REQUIRE(p.ok);
        if (p.integrator == Integrator::verlet || p.integrator == Integrator::rk4) {
            CHECK(p.error < 1e-9);
        } else if (p.integrator == Integrator::euler) {
            CHECK(p.error > 1e-6);
        }
        CHECK(p.cost_median > 0.0);
        CHECK(p.cost_spread >= 0.0);
    }
}

TEST_CASE("Sweep work counters are deterministic and secant needs fewer toi iterations",
          "[sweep]") {
    const Scene scene = load_scene(drop_box_path());
    SweepConfig config = small_config(scene);
    config.repeats = 3;
    const SweepResult first = run_sweep(scene, config);
    const SweepResult second = run_sweep(scene, config);
    REQUIRE(first.points.size() == second.points.size());
    for (std::size_t i = 0; i < first.points.size(); ++i) {
        const SweepPoint& a = first.points[i];
        const SweepPoint& b = second.points[i];
        INFO(a.family << " dt " << a.dt);
        CHECK(a.ok == b.ok);
        if (!a.ok) {
            continue;
        }
        CHECK(a.work_identical);
        CHECK(a.work.steps > 0);
        CHECK(a.work.steps == b.work.steps);
        CHECK(a.work.narrow_phase_queries == b.work.narrow_phase_queries);
        CHECK(a.work.toi_iterations == b.work.toi_iterations);
        CHECK(a.work.collisions == b.work.collisions);
    }
    for (const SweepPoint& bisection : first.points) {
        if (bisection.toi != TimeOfImpactMethod::bisection || !bisection.ok) {
            continue;
        }
        for (const SweepPoint& secant : first.points) {
            if (secant.toi == TimeOfImpactMethod::secant && secant.ok &&
                secant.dt == bisection.dt && secant.integrator == bisection.integrator &&
                secant.toi_tolerance == bisection.toi_tolerance) {
                INFO(bisection.family << " vs " << secant.family << " dt " << secant.dt);
                CHECK(bisection.work.toi_iterations > 0);
                CHECK(secant.work.toi_iterations < bisection.work.toi_iterations);
            }
        }
    }
}

TEST_CASE("A grid point the engine refuses is reported, not thrown", "[sweep]") {
    const Scene scene = load_scene(drop_box_path());
    SweepConfig config = small_config(scene);
    config.dts = {1.0 / 60.0};
    config.integrators = {Integrator::verlet};
    config.toi_methods = {TimeOfImpactMethod::bisection};
    // No bracket can shrink to 1e-300 s: the time-of-impact search gives up.
    config.toi_tolerances = {1e-12, 1e-300};
    config.repeats = 1;
    SweepResult result;
    REQUIRE_NOTHROW(result = run_sweep(scene, config));
    REQUIRE(result.points.size() == 2);
    CHECK(result.points[0].ok);
    CHECK_FALSE(result.points[1].ok);
    CHECK(result.points[1].failure.find("toi_tolerance") != std::string::npos);
    CHECK_FALSE(result.points[1].on_front);
}

TEST_CASE("A scene without exact answers is measured against a reference run", "[sweep]") {
    Scene scene = load_scene(drop_box_path());
    scene.expectations.clear();
    SweepConfig config = small_config(scene);
    config.integrators = {Integrator::euler, Integrator::rk4};
    config.toi_methods = {TimeOfImpactMethod::secant};
    config.repeats = 1;
    const SweepResult result = run_sweep(scene, config);
    CHECK_FALSE(result.against_exact);
    CHECK(result.error_reference.find("against a reference run at") != std::string::npos);
    for (const SweepPoint& p : result.points) {
        INFO(p.family << " dt " << p.dt);
        REQUIRE(p.ok);
        CHECK(std::isfinite(p.error));
        if (p.integrator == Integrator::rk4) {
            CHECK(p.error < 1e-6);
        } else {
            CHECK(p.error > 1e-6);
        }
    }
}

TEST_CASE("impulse sweep --json has one entry per grid point; the SVG is well-formed", "[sweep]") {
    const std::string svg_path = "/tmp/impulse-test-sweep-" + std::to_string(::getpid()) + ".svg";
    std::ostringstream out, err;
    const int code = cli::sweep_verb({drop_box_path(),
                                      "--json",
                                      "--dt",
                                      "0.016666666666666666,0.008333333333333333",
                                      "--integrator",
                                      "verlet,euler",
                                      "--toi",
                                      "bisection,secant",
                                      "--toi-tolerance",
                                      "1e-9",
                                      "--box2d-substeps",
                                      "1",
                                      "--box2d-iterations",
                                      "8/3,30/10",
                                      "--repeats",
                                      "1",
                                      "--svg",
                                      svg_path,
                                      "--with",
#ifdef IMPULSE_WITH_BOX2D
                                      "box2d-2.4"
#else
                                      "none"
#endif
                                     },
                                     out, err);
    REQUIRE(code == 0);
    const nlohmann::json j = nlohmann::json::parse(out.str());
    std::size_t expected = 2 * 2 * 2 * 1;
#ifdef IMPULSE_WITH_BOX2D
    expected += 2 * 1 * 2;
#endif
    REQUIRE(j.at("points").size() == expected);
    CHECK(j.at("against_exact") == true);
    std::size_t box2d = 0;
    for (const auto& p : j.at("points")) {
        CHECK(p.at("ok") == true);
        CHECK(p.at("error").is_number());
        CHECK(p.at("cost_median").is_number());
        CHECK(p.at("work").at("steps").get<long long>() > 0);
        box2d += p.at("engine") == "box2d" ? 1 : 0;
    }
#ifdef IMPULSE_WITH_BOX2D
    CHECK(box2d == 4);
#endif

    std::ifstream in(svg_path);
    std::stringstream svg;
    svg << in.rdbuf();
    std::remove(svg_path.c_str());
    std::string why;
    CHECK(well_formed_xml(svg.str(), why));
    INFO(why);
    CHECK(svg.str().find("<polyline") != std::string::npos);
    CHECK(svg.str().find("s/s, log") != std::string::npos);

    // The SVG text is a function of the result alone.
    SweepResult fixed;
    fixed.scene = "x";
    SweepPoint a;
    a.family = "impulse verlet/secant";
    a.ok = true;
    a.error = 1e-12;
    a.cost_median = 1e-3;
    a.on_front = true;
    SweepPoint b = a;
    b.family = "box2d";
    b.box2d = true;
    b.error = 0.0;
    fixed.points = {a, b};
    CHECK(sweep_svg(fixed) == sweep_svg(fixed));
    CHECK(well_formed_xml(sweep_svg(fixed), why));
}

TEST_CASE("impulse sweep rejects bad options with a usage error", "[sweep]") {
    std::ostringstream out, err;
    CHECK_THROWS_AS(cli::sweep_verb({drop_box_path(), "--integrator", "leapfrog"}, out, err),
                    cli::UsageError);
    CHECK_THROWS_AS(cli::sweep_verb({drop_box_path(), "--box2d-iterations", "8"}, out, err),
                    cli::UsageError);
    CHECK_THROWS_AS(cli::sweep_verb({drop_box_path(), "--repeats", "0"}, out, err),
                    cli::UsageError);
    CHECK(cli::sweep_verb({"--help"}, out, err) == 0);
    CHECK(out.str().find("--box2d-iterations") != std::string::npos);
}

TEST_CASE("impulse sweep prints the targets after the table and under \"targets\" in --json",
          "[sweep]") {
    // One impulse and one Box2D point, both at 60 Hz.
    std::vector<std::string> grid = {drop_box_path()};
    std::istringstream words("--dt 0.016666666666666666 --integrator verlet --toi secant "
                             "--toi-tolerance 1e-12 --box2d-substeps 1 --box2d-iterations 8/3 "
                             "--repeats 1");
    for (std::string word; words >> word;) {
        grid.push_back(word);
    }
    {
        std::ostringstream out, err;
        std::vector<std::string> args = grid;
        args.emplace_back("--no-box2d");
        REQUIRE(cli::sweep_verb(args, out, err) == 0);
        CHECK(out.str().find("\ntargets: not measured (no Box2D points)\n") != std::string::npos);
    }
#ifdef IMPULSE_WITH_BOX2D
    {
        // Which verdict holds depends on this run's timings; the wording does not.
        std::ostringstream out, err;
        REQUIRE(cli::sweep_verb(grid, out, err) == 0);
        INFO(out.str());
        CHECK(out.str().find("\ntargets (wall-clock costs of this run; noisy):\n"
                             "  error at Box2D's 60 Hz cost: Box2D 1/60 sub 1, it 8/3: error ") !=
              std::string::npos);
        CHECK(out.str().find("\n  Pareto front: impulse's front dominates ") != std::string::npos);
    }
    {
        std::ostringstream out, err;
        std::vector<std::string> args = grid;
        args.emplace_back("--json");
        REQUIRE(cli::sweep_verb(args, out, err) == 0);
        const nlohmann::json t = nlohmann::json::parse(out.str()).at("targets");
        CHECK(t.at("measured") == true);
        const nlohmann::json& error = t.at("error_at_box2d_60hz_cost");
        CHECK(error.at("measured") == true);
        CHECK(error.at("box2d_point") == 1); // impulse points come first
        CHECK(error.at("required_ratio") == 1e6);
        CHECK(error.at("met").is_boolean());
        CHECK(error.at("verdict").get<std::string>().rfind(
                  "error at Box2D's 60 Hz cost: Box2D 1/60 sub 1, it 8/3: ", 0) == 0);
        CHECK(t.at("pareto_front").at("box2d_front_points") == 1);
    }
#endif
}

namespace {

std::string bullet_path() {
    return std::string(IMPULSE_SOURCE_DIR) + "/harness/scenes/bullet.json";
}

// One impulse setting (verlet/secant at the scene's tolerance), no Box2D.
SweepConfig one_setting(const Scene& scene, double dt) {
    SweepConfig config = default_sweep_config(scene);
    config.dts = {dt};
    config.integrators = {Integrator::verlet};
    config.toi_methods = {TimeOfImpactMethod::secant};
    config.toi_tolerances = {1e-12};
    config.box2d = false;
    config.repeats = 1;
    return config;
}

} // namespace

TEST_CASE("The ccd option adds a grid dimension: both settings, each its own family", "[sweep]") {
    SweepPoint p;
    p.integrator = Integrator::verlet;
    p.toi = TimeOfImpactMethod::secant;
    CHECK(sweep_family(p) == "impulse verlet/secant");
    p.ccd = true;
    CHECK(sweep_family(p) == "impulse verlet/secant+ccd");

    const Scene drop = load_scene(drop_box_path());
    SECTION("default: the scene's own setting only") {
        CHECK(default_sweep_config(drop).ccd.empty());
        const SweepResult off = run_sweep(drop, one_setting(drop, 1.0 / 60.0));
        REQUIRE(off.points.size() == 1);
        CHECK_FALSE(off.points[0].ccd);
        CHECK(off.points[0].family == "impulse verlet/secant");

        const Scene bullet = load_scene(bullet_path()); // "ccd": true
        REQUIRE(bullet.solver.ccd);
        const SweepResult on = run_sweep(bullet, one_setting(bullet, 1.0 / 30.0));
        REQUIRE(on.points.size() == 1);
        CHECK(on.points[0].ccd);
        CHECK(on.points[0].family == "impulse verlet/secant+ccd");
        // A scene without exact answers: the reference run catches the hit too.
        CHECK_FALSE(on.against_exact);
        CHECK(on.error_reference.find("ccd on") != std::string::npos);
    }
    SECTION("off,on: every impulse setting twice, ccd varying fastest") {
        SweepConfig config = one_setting(drop, 1.0 / 60.0);
        config.dts = {1.0 / 60.0, 1.0 / 120.0};
        config.toi_methods = {TimeOfImpactMethod::bisection, TimeOfImpactMethod::secant};
        config.ccd = {false, true};
        const SweepResult r = run_sweep(drop, config);
        REQUIRE(r.points.size() == 2 * 2 * 2);
        std::set<std::string> families;
        for (std::size_t i = 0; i < r.points.size(); ++i) {
            const SweepPoint& q = r.points[i];
            INFO(i << ": " << q.family << " " << q.failure);
            CHECK(q.ccd == (i % 2 == 1));
            CHECK(q.family == sweep_family(q));
            CHECK((q.family.find("+ccd") != std::string::npos) == q.ccd);
            families.insert(q.family);
            REQUIRE(q.ok);
            if (i % 2 == 1) {
                // The same setting without ccd: drop-box has nothing to
                // tunnel through, so the answer is the same to the tolerance.
                const SweepPoint& without = r.points[i - 1];
                CHECK_FALSE(without.ccd);
                CHECK(without.dt == q.dt);
                CHECK(without.toi == q.toi);
                CHECK(q.error == Approx(without.error).margin(1e-9));
                CHECK(q.work.narrow_phase_queries > without.work.narrow_phase_queries);
            }
        }
        CHECK(families ==
              std::set<std::string>{"impulse verlet/bisection", "impulse verlet/bisection+ccd",
                                    "impulse verlet/secant", "impulse verlet/secant+ccd"});
        // Exact answers: no reference run, nothing about ccd to say.
        CHECK(r.against_exact);
    }
    SECTION("the reference run uses ccd when a grid point does, and says so") {
        Scene no_exact = drop;
        no_exact.expectations.clear();
        SweepConfig config = one_setting(no_exact, 1.0 / 60.0);
        config.ccd = {false};
        const SweepResult off = run_sweep(no_exact, config);
        CHECK(off.error_reference.find("ccd off") != std::string::npos);
        config.ccd = {false, true};
        const SweepResult on = run_sweep(no_exact, config);
        CHECK(on.error_reference.find("ccd on") != std::string::npos);
    }
    SECTION("ccd on with local stepping is an input error; off is fine") {
        Scene local = drop;
        local.solver.stepping = Stepping::local;
        SweepConfig config = one_setting(local, 1.0 / 60.0);
        config.ccd = {false, true};
        try {
            (void)run_sweep(local, config);
            FAIL("ccd on with local stepping was accepted");
        } catch (const InputError& e) {
            const std::string what = e.what();
            INFO(what);
            CHECK(what.find("ccd on") != std::string::npos);
            CHECK(what.find("\"stepping\": \"local\"") != std::string::npos);
        }
        config.ccd = {false};
        CHECK_NOTHROW(run_sweep(local, config));
    }
}

TEST_CASE("impulse sweep --ccd: JSON and CSV carry the setting; bad values are usage errors",
          "[sweep]") {
    const std::vector<std::string> grid = {drop_box_path(),
                                           "--dt",
                                           "0.016666666666666666",
                                           "--integrator",
                                           "verlet",
                                           "--toi",
                                           "secant",
                                           "--toi-tolerance",
                                           "1e-12",
                                           "--ccd",
                                           "off,on",
                                           "--repeats",
                                           "1",
                                           "--no-references"};
    {
        std::ostringstream out, err;
        std::vector<std::string> args = grid;
        args.emplace_back("--json");
        REQUIRE(cli::sweep_verb(args, out, err) == 0);
        const nlohmann::json points = nlohmann::json::parse(out.str()).at("points");
        REQUIRE(points.size() == 2);
        CHECK(points[0].at("ccd") == false);
        CHECK(points[0].at("family") == "impulse verlet/secant");
        CHECK(points[1].at("ccd") == true);
        CHECK(points[1].at("family") == "impulse verlet/secant+ccd");
    }
    {
        std::ostringstream out, err;
        std::vector<std::string> args = grid;
        args.emplace_back("--csv");
        REQUIRE(cli::sweep_verb(args, out, err) == 0);
        std::istringstream lines(out.str());
        std::string header, off, on;
        std::getline(lines, header);
        std::getline(lines, off);
        std::getline(lines, on);
        CHECK(header.rfind("engine,family,dt,integrator,toi,toi_tolerance,ccd,substeps,", 0) == 0);
        CHECK(off.find(",verlet,secant,1e-12,false,") != std::string::npos);
        CHECK(on.rfind("impulse,impulse verlet/secant+ccd,", 0) == 0);
        CHECK(on.find(",verlet,secant,1e-12,true,") != std::string::npos);
    }
    {
        std::ostringstream out, err;
        REQUIRE(cli::sweep_verb(grid, out, err) == 0);
        CHECK(out.str().find("\nimpulse verlet/secant+ccd ") != std::string::npos);
    }
    std::ostringstream out, err;
    CHECK_THROWS_AS(cli::sweep_verb({drop_box_path(), "--ccd", "yes"}, out, err), cli::UsageError);
    CHECK_THROWS_AS(cli::sweep_verb({drop_box_path(), "--ccd", "off,"}, out, err), cli::UsageError);
}

TEST_CASE("The cost of ccd on bullet: without it the disc tunnels, with it the error is tiny",
          "[sweep]") {
    // impulse sweep bullet --dt 1/30 --integrator verlet --toi secant --ccd off,on
    //   --repeats 1 --no-box2d
    const Scene scene = load_scene(bullet_path());
    SweepConfig config = default_sweep_config(scene);
    config.dts = {1.0 / 30.0};
    config.integrators = {Integrator::verlet};
    config.toi_methods = {TimeOfImpactMethod::secant};
    config.ccd = {false, true};
    config.box2d = false;
    config.repeats = 1;
    const SweepResult r = run_sweep(scene, config);
    // bullet declares no drop, corner-impact or head-on answer: a reference
    // run, which must not tunnel.
    CHECK_FALSE(r.against_exact);
    CHECK(r.error_reference.find("ccd on") != std::string::npos);
    REQUIRE(r.points.size() == config.toi_tolerances.size() * 2);
    for (std::size_t i = 0; i + 1 < r.points.size(); i += 2) {
        const SweepPoint& off = r.points[i];
        const SweepPoint& on = r.points[i + 1];
        INFO("toi_tolerance " << off.toi_tolerance << ": off " << off.failure << ", on "
                              << on.failure);
        REQUIRE(off.ok);
        REQUIRE(on.ok);
        CHECK_FALSE(off.ccd);
        CHECK(on.ccd);
        CHECK(on.toi_tolerance == off.toi_tolerance);
        // Off: the disc passes the wall and flies on at +1000 m/s where the
        // reference comes back at -1000 m/s, 90 m the other side: error ~ 2.
        CHECK(off.error > 1.0);
        CHECK(off.work.collisions == 0);
        // On: the hit is found and the bounce is the reference's.
        CHECK(on.error < 1e-6);
        CHECK(on.work.collisions == 1);
        // What it costs: ccd's samples are narrow-phase queries.
        CHECK(on.work.steps == off.work.steps);
        CHECK(on.work.narrow_phase_queries > off.work.narrow_phase_queries);
        CHECK(on.family == "impulse verlet/secant+ccd");
        CHECK(off.family == "impulse verlet/secant");
    }
}
