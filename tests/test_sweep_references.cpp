// `impulse sweep` on piles and beside every reference engine: a pile's two
// error axes through the real binary, a fake Node reference (found through
// IMPULSE_REFERENCES_DIR, as the registry finds Box2D v3) with its own front,
// the plot's colours, markers and time-step labels, and the verdict sentence
// computed from made-up points with a known answer.
#include "support/files.h"
#include "support/tool.h"
#include "sweep.h"
#include "sweep_plot.h"
#include "sweep_verdict.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impulse;
using namespace impulse::harness;
using namespace impulse::test;

namespace {

const std::string root = IMPULSE_SOURCE_DIR;

// Five discs of radii 0.1 to 0.5 and masses 0.05 to 5 (1:100) dropped into
// an open box (inner faces at x = +-2, floor at y = 0), settled by
// time-stepping: a pile, with a pile's expectations and no exact answers.
const std::string pile_scene = R"({"schema":"impulse/scene@1","name":"sweep-pile","restitution":0.5,
 "dt":0.016666666666666666,"duration":1,
 "solver":{"integrator":"verlet","toi":"secant","resting":true,"resting_method":"time-stepping"},
 "bodies":[
  {"name":"floor","static":true,"shape":{"box":[2,0.5]},"position":[0,-0.5]},
  {"name":"left","static":true,"shape":{"box":[0.25,1.5]},"position":[-2.25,1.5]},
  {"name":"right","static":true,"shape":{"box":[0.25,1.5]},"position":[2.25,1.5]},
  {"name":"p0","shape":{"circle":0.1},"mass":0.05,"position":[-0.9,0.6]},
  {"name":"p1","shape":{"circle":0.5},"mass":5,"position":[0,0.8]},
  {"name":"p2","shape":{"circle":0.25},"mass":1.2,"position":[0.7,1.6]},
  {"name":"p3","shape":{"circle":0.3},"mass":1.8,"position":[-0.5,1.9]},
  {"name":"p4","shape":{"circle":0.15},"mass":0.4,"position":[0.2,2.6]}],
 "expectations":[{"kind":"max-overlap","atol":0.01},{"kind":"energy-non-increasing","atol":1e-6}]}
)";

// One disc in free flight, nothing to hit: no exact answers, so the error is
// against impulse's reference run (rk4, exact for constant gravity).
const std::string fall_scene = R"({"schema":"impulse/scene@1","name":"sweep-fall","restitution":0.5,
 "dt":0.016666666666666666,"duration":0.5,
 "bodies":[{"name":"ball","shape":{"circle":0.1},"mass":1,"position":[0,10]}]}
)";

nlohmann::json json_of(const Outcome& o) {
    INFO(o.out << o.err);
    REQUIRE(o.exit_code == 0);
    return nlohmann::json::parse(o.out);
}

// The families the legend names, each with its colour and marker.
std::map<std::string, std::pair<std::string, std::string>> legend_of(const std::string& svg) {
    std::map<std::string, std::pair<std::string, std::string>> legend;
    const std::regex entry("<g class=\"legend-entry\" data-family=\"([^\"]*)\" "
                           "data-colour=\"([^\"]*)\" data-marker=\"([^\"]*)\">");
    for (std::sregex_iterator i(svg.begin(), svg.end(), entry), end; i != end; ++i) {
        legend[(*i)[1]] = {(*i)[2], (*i)[3]};
    }
    return legend;
}

SweepPoint made_up(const std::string& family, double dt, double cost, double error) {
    SweepPoint p;
    p.dt = dt;
    p.ok = true;
    p.cost_median = cost;
    p.error = error;
    if (family == "box2d") {
        p.box2d = true;
        p.substeps = 1;
        p.velocity_iterations = 8;
        p.position_iterations = 3;
    } else if (family.rfind("impulse ", 0) != 0) {
        p.reference = family;
        p.engine = family;
        p.substeps = 4;
    } else {
        p.integrator =
            family.find("rk4") != std::string::npos ? Integrator::rk4 : Integrator::verlet;
        p.toi = family.find("bisection") != std::string::npos ? TimeOfImpactMethod::bisection
                                                              : TimeOfImpactMethod::secant;
        p.ccd = family.find("+ccd") != std::string::npos;
        p.toi_tolerance = 1e-12;
    }
    p.family = sweep_family(p);
    return p;
}

SweepResult made_up_result(std::vector<SweepPoint> points) {
    SweepResult r;
    r.scene = "made-up";
    r.points = std::move(points);
    r.references = {{"box2d", "Box2D 2.4.1"}, {"box2d-3", "Box2D v3"}, {"chipmunk", "Chipmunk2D"}};
    mark_fronts(r.points);
    return r;
}

} // namespace

TEST_CASE("A pile's sweep: finite overlap and energy errors per point, every family in the plot",
          "[sweep][sweep-references]") {
    const TempDir dir;
    spit(dir.dir / "pile.json", pile_scene);
    const fs::path svg = dir.dir / "pile.svg";
    std::vector<std::string> args = {"sweep",
                                     (dir.dir / "pile.json").string(),
                                     "--json",
                                     "--dt",
                                     "0.016666666666666666,0.008333333333333333",
                                     "--integrator",
                                     "verlet,symplectic-euler",
                                     "--toi",
                                     "secant",
                                     "--toi-tolerance",
                                     "1e-9",
                                     "--repeats",
                                     "1",
                                     "--svg",
                                     svg.string(),
                                     "--box2d-substeps",
                                     "1",
                                     "--box2d-iterations",
                                     "8/3",
                                     "--root",
                                     root,
                                     "--with"};
#ifdef IMPULSE_WITH_BOX2D
    args.emplace_back("box2d-2.4");
#else
    args.emplace_back("none");
#endif
    const nlohmann::json j = json_of(run_tool(args));
    CHECK(j.at("pile") == true);
    CHECK(j.at("against_exact") == false);
    CHECK(j.at("cost_unit").get<std::string>().find("body-step") != std::string::npos);
    std::set<std::string> families;
    for (const nlohmann::json& p : j.at("points")) {
        INFO(p.dump());
        families.insert(p.at("family").get<std::string>());
        if (!p.at("ok").get<bool>()) {
            continue;
        }
        // Finite, and an overlap no deeper than the smallest disc's radius:
        // a deeper one would mean a disc inside another.
        REQUIRE(p.at("error").is_number());
        REQUIRE(p.at("energy_error").is_number());
        CHECK(p.at("error").get<double>() >= 0.0);
        CHECK(p.at("error").get<double>() < 0.1);
        CHECK(p.at("energy_error").get<double>() >= 0.0);
        CHECK(p.at("cost_median").get<double>() > 0.0);
    }
    // impulse's points all ran: time-stepping settles any pile.
    for (const nlohmann::json& p : j.at("points")) {
        if (p.at("engine") == "impulse") {
            CHECK(p.at("ok") == true);
        }
    }
#ifdef IMPULSE_WITH_BOX2D
    CHECK(families.count("box2d") == 1);
    bool overlap_verdict = false, energy_verdict = false;
    for (const nlohmann::json& v : j.at("verdicts")) {
        overlap_verdict = overlap_verdict || v.at("axis") == "overlap";
        energy_verdict = energy_verdict || v.at("axis") == "energy";
        CHECK(v.at("headline").get<std::string>().rfind("impulse at Box2D 2.4.1's cost: ", 0) == 0);
    }
    CHECK(overlap_verdict);
    CHECK(energy_verdict);
#endif
    const std::string picture = slurp(svg);
    const auto legend = legend_of(picture);
    for (const std::string& f : families) {
        CHECK(legend.count(f) == 1);
    }
    CHECK(picture.find("deepest overlap of any pair") != std::string::npos);
    CHECK(picture.find("energy gained over the run") != std::string::npos);
    CHECK(picture.find("seconds per body-step") != std::string::npos);
}

TEST_CASE("A fake Node reference gets its own front, its error first order in its step",
          "[sweep][sweep-references]") {
    // A references folder as npm ci leaves it, Box2D v3's program replaced by
    // tests/engines/fake_reference.mjs; Rapier's package is absent.
    const TempDir refs;
    fs::create_directories(refs.dir / "node_modules" / "box2d3-wasm");
    spit(refs.dir / "node_modules" / "box2d3-wasm" / "package.json", "{}\n");
    fs::create_directories(refs.dir / "box2d-v3");
    fs::copy_file(root + "/tests/engines/fake_reference.mjs", refs.dir / "box2d-v3" / "engine.mjs");
    const TempDir dir;
    spit(dir.dir / "fall.json", fall_scene);
    const fs::path svg = dir.dir / "fall.svg";
    const Outcome o = run_tool({"sweep",
                                (dir.dir / "fall.json").string(),
                                "--json",
                                "--dt",
                                "0.016666666666666666,0.008333333333333333",
                                "--integrator",
                                "verlet",
                                "--toi",
                                "secant",
                                "--toi-tolerance",
                                "1e-9",
                                "--repeats",
                                "1",
                                "--with",
                                "box2d-3",
                                "--reference-substeps",
                                "1,2",
                                "--svg",
                                svg.string(),
                                "--root",
                                root},
                               {"IMPULSE_REFERENCES_DIR=" + refs.dir.string()});
    const nlohmann::json j = json_of(o);
    // (dt, substeps) -> error
    std::map<std::pair<double, int>, double> fake;
    bool on_front = false;
    for (const nlohmann::json& p : j.at("points")) {
        if (p.at("engine") != "box2d-3") {
            continue;
        }
        INFO(p.dump());
        CHECK(p.at("family") == "box2d-3");
        REQUIRE(p.at("ok") == true);
        REQUIRE(p.at("error").is_number());
        fake[{p.at("dt").get<double>(), p.at("substeps").get<int>()}] = p.at("error").get<double>();
        on_front = on_front || p.at("on_front").get<bool>();
    }
    REQUIRE(fake.size() == 4);
    CHECK(on_front);
    // Symplectic Euler in sub-steps of h misses the height by g T h / 2: the
    // error depends on h = dt / substeps alone, and halves with it.
    const double h60 = 0.016666666666666666, h120 = 0.008333333333333333;
    CHECK(fake.at({h60, 2}) == Approx(fake.at({h120, 1})).epsilon(1e-6));
    CHECK(fake.at({h60, 1}) == Approx(2.0 * fake.at({h120, 1})).epsilon(1e-6));
    CHECK(fake.at({h120, 2}) == Approx(0.5 * fake.at({h120, 1})).epsilon(1e-6));
    bool verdict = false;
    for (const nlohmann::json& v : j.at("verdicts")) {
        if (v.at("reference") == "box2d-3") {
            verdict = true;
            CHECK(v.at("headline").get<std::string>().rfind("impulse at Box2D v3's cost: ", 0) ==
                  0);
        }
    }
    CHECK(verdict);
    const auto legend = legend_of(slurp(svg));
    CHECK(legend.count("box2d-3") == 1);
    CHECK(legend.count("impulse verlet/secant") == 1);
}

TEST_CASE("The plot gives every family its own colour and marker and labels the time steps",
          "[sweep][sweep-references]") {
    std::vector<SweepPoint> points;
    for (const std::string family :
         {"impulse verlet/secant", "impulse verlet/bisection", "impulse rk4/secant",
          "impulse verlet/secant+ccd", "box2d", "box2d-3", "chipmunk"}) {
        points.push_back(made_up(family, 1.0 / 60.0, 1e-3, 1e-3));
        points.push_back(made_up(family, 1.0 / 240.0, 4e-3, 1e-5));
    }
    const std::string svg = sweep_svg(made_up_result(points));
    const auto legend = legend_of(svg);
    REQUIRE(legend.size() == 7);
    std::set<std::pair<std::string, std::string>> styles;
    std::set<std::string> reference_colours, impulse_colours;
    for (const auto& [family, style] : legend) {
        styles.insert(style);
        (family.rfind("impulse", 0) == 0 ? impulse_colours : reference_colours).insert(style.first);
    }
    CHECK(styles.size() == legend.size()); // no two families drawn alike
    CHECK(reference_colours.size() == 3);  // each reference its own colour...
    for (const std::string& c : reference_colours) {
        CHECK(impulse_colours.count(c) == 0); // ...none of impulse's
    }
    // Okabe and Ito's colour-blind-safe palette, and a grey.
    const std::set<std::string> palette = {"#56B4E9", "#009E73", "#0072B2", "#000000",
                                           "#D55E00", "#CC79A7", "#E69F00", "#7F7F7F"};
    for (const auto& [family, style] : legend) {
        CHECK(palette.count(style.first) == 1);
    }
    // Each front point's time step beside it: both steps, for all 7 families.
    std::size_t at_60 = 0, at_240 = 0;
    const std::regex label("<text class=\"dt-label\"[^>]*>(1/[0-9]+)</text>");
    for (std::sregex_iterator i(svg.begin(), svg.end(), label), end; i != end; ++i) {
        at_60 += (*i)[1] == "1/60" ? 1 : 0;
        at_240 += (*i)[1] == "1/240" ? 1 : 0;
    }
    CHECK(at_60 == 7);
    CHECK(at_240 == 7);
    CHECK(svg.find("lower left is better") != std::string::npos);
    CHECK(svg.find("impulse at Box2D 2.4.1&apos;s cost: ") != std::string::npos);
}

TEST_CASE("The verdict is computed from the points: orders of magnitude at the reference's cost",
          "[sweep][sweep-references]") {
    const double hz60 = 1.0 / 60.0;
    const SweepResult r = made_up_result({
        made_up("impulse verlet/secant", 1.0 / 30.0, 5e-4, 1e-7),   // the affordable best
        made_up("impulse verlet/secant", 1.0 / 120.0, 2e-3, 1e-12), // better, but dearer
        made_up("impulse rk4/secant", 1.0 / 30.0, 9e-4, 1e-6),
        made_up("box2d", hz60, 1e-3, 1e-2),       // 5 orders worse at its cost
        made_up("box2d", 1.0 / 30.0, 5e-4, 1e-1), // not nearest 60 Hz
        made_up("box2d-3", hz60, 1e-4, 1e-3),     // cheaper than every impulse point
        made_up("chipmunk", hz60, 1e-3, 1e-9),    // 2 orders better than 1e-7
    });
    const std::vector<ReferenceVerdict> v = reference_verdicts(r, SweepAxis::error);
    REQUIRE(v.size() == 3);

    CHECK(v[0].family == "box2d");
    REQUIRE(v[0].measured);
    CHECK(v[0].reference_point == 3);
    REQUIRE(v[0].found);
    CHECK(v[0].impulse_point == 0);
    CHECK(v[0].orders == Approx(5.0));
    CHECK(verdict_headline(r, v[0], SweepAxis::error) ==
          "impulse at Box2D 2.4.1's cost: 5.0 orders of magnitude more accurate");
    // Box2D's front: (5e-4, 1e-1) and (1e-3, 1e-2), both beaten by (5e-4, 1e-7).
    CHECK(v[0].front_size == 2);
    CHECK(v[0].dominates());

    CHECK(!v[1].found);
    CHECK(verdict_headline(r, v[1], SweepAxis::error) ==
          "impulse at Box2D v3's cost: no impulse point costs that little");
    CHECK(!v[1].dominates());

    CHECK(v[2].orders == Approx(-2.0));
    CHECK(verdict_headline(r, v[2], SweepAxis::error) ==
          "impulse at Chipmunk2D's cost: 2.0 orders of magnitude less accurate");
    CHECK(v[2].front_size == 1);
    CHECK(v[2].front_dominated == 0);
    const std::string sentence = verdict_sentence(r, v[2], SweepAxis::error);
    CHECK(sentence.find("impulse's front does not dominate Chipmunk2D's (0 of its 1 front point "
                        "dominated)") != std::string::npos);

    // On a pile the axis is named: the energy gained, from its own numbers.
    SweepResult pile = r;
    pile.pile = true;
    for (SweepPoint& p : pile.points) {
        p.energy_error = p.error * 10.0;
    }
    const std::vector<ReferenceVerdict> e = reference_verdicts(pile, SweepAxis::energy);
    CHECK(verdict_headline(pile, e[0], SweepAxis::energy) ==
          "impulse at Box2D 2.4.1's cost: 5.0 orders of magnitude more accurate in energy gained");
}
