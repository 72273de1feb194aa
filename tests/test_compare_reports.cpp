// Comparing trajectories, what the reports say: structural differences, a
// short description of many divergent columns, columns that are no body
// channel, and the `impulse diff` verb (test_compare.cpp has the metric and
// the rule).
#include "cli.h"
#include "compare.h"
#include "input_error.h"
#include "sha256.h"
#include "support/comparing.h"
#include "support/tool.h"
#include "tolerance.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace impulse::harness;
using Catch::Contains;
using impulse::test::Outcome;
using namespace impulse::test::comparing;

TEST_CASE("structural differences are listed and what is comparable is compared", "[compare]") {
    const Trajectory gold = sample();

    SECTION("different columns") {
        Trajectory value = gold;
        value.columns.back() = "box.spin";
        value.frames[3][1] = 0.75; // box.x still compared
        const Comparison c = compare(gold, value, std::nullopt);
        CHECK_FALSE(c.passed);
        CHECK_FALSE(c.identical);
        REQUIRE(c.structural.size() == 2);
        CHECK_THAT(c.structural[0], Contains("only in the golden: box.omega"));
        CHECK_THAT(c.structural[1], Contains("only in the new trajectory: box.spin"));
        REQUIRE(c.first_divergences.size() == 1);
        CHECK(c.first_divergences[0].column == "box.x");
        CHECK(summary(c, Channel::angular_velocity).compared == 0);
    }
    SECTION("the same columns in another order") {
        Trajectory value = gold;
        std::swap(value.columns[1], value.columns[2]);
        for (auto& frame : value.frames) {
            std::swap(frame[1], frame[2]);
        }
        const Comparison c = compare(gold, value, std::nullopt);
        REQUIRE(c.structural.size() == 1);
        CHECK_THAT(c.structural[0], Contains("different order"));
        CHECK(c.first_divergences.empty()); // matched by name, every value equal
    }
    SECTION("fewer frames") {
        Trajectory value = gold;
        value.frames.pop_back();
        value.frames[1][2] = 2.5;
        const Comparison c = compare(gold, value, every_channel(tol(1, 0, 0)));
        CHECK_FALSE(c.passed); // within tolerance, but the shapes differ
        REQUIRE(c.structural.size() == 1);
        CHECK(c.structural[0] == "frame counts differ: golden 4, new 3; the first 3 are compared");
        CHECK(summary(c, Channel::position).compared == 2 * 3 + 4);
    }
    SECTION("fewer events") {
        Trajectory value = gold;
        value.events.pop_back();
        const Comparison c = compare(gold, value, std::nullopt);
        REQUIRE(c.structural.size() == 1);
        CHECK(c.structural[0] == "event counts differ: golden 2, new 1; the first 1 are compared");
        CHECK(summary(c, Channel::impulse).compared == 1);
        CHECK(c.first_divergences.empty());
        CHECK_THAT(describe(c), Contains("the trajectories differ in shape:\n  event counts"));
    }
    SECTION("an event between other bodies is not compared") {
        Trajectory value = gold;
        value.events[0].b = "wall";
        value.events[0].impulse = 9.0;
        value.events[1].a = "ball";
        const Comparison c = compare(gold, value, std::nullopt);
        REQUIRE(c.structural.size() == 1);
        CHECK(c.structural[0] == "events[0] is between box and ground in the golden but between "
                                 "box and wall in the new trajectory, and 1 later event also "
                                 "pairs other bodies; events with other bodies are not compared");
        CHECK(summary(c, Channel::impulse).compared == 0);
    }
    SECTION("another scene") {
        Trajectory value = gold;
        value.scene = "spin";
        const Comparison c = compare(gold, value, std::nullopt);
        REQUIRE(c.structural.size() == 1);
        CHECK(c.structural[0] == "the scene names differ: golden 'drop', new 'spin'");
        CHECK_FALSE(c.passed);
    }
}

TEST_CASE("a description of hundreds of divergent columns stays short", "[compare]") {
    Trajectory gold;
    gold.scene = "crowd";
    gold.columns = {"t"};
    gold.frames = {{0.0}, {0.5}};
    for (int body = 0; body < 100; ++body) {
        gold.columns.push_back("b" + std::to_string(body) + ".x");
        gold.frames[0].push_back(1.0);
        gold.frames[1].push_back(1.0);
    }
    Trajectory value = gold;
    for (std::size_t i = 1; i < value.columns.size(); ++i) {
        value.frames[1][i] = 2.0;
    }
    const Comparison c = compare(gold, value, std::nullopt);
    CHECK(c.first_divergences.size() == 100);
    const std::vector<std::string> lines = lines_of(describe(c));
    REQUIRE(lines.size() == 1 + 40 + 1 + 3);
    CHECK(lines[41] == "  ... and 60 more");
    CHECK(lines[42] == "per channel:");
    // 1 -> 2 is a difference of 1 at the spacing of doubles at 2, 2^-51.
    CHECK(lines[43] == "  position    100/200 values differ  max abs 1  max rel 1  max ulp " +
                           std::to_string(std::uint64_t{1} << 51));
    CHECK(lines[44] == "  event_time  0/2 values differ      max abs 0  max rel 0  max ulp 0");
}

TEST_CASE("impulse diff compares two trajectory files", "[compare]") {
    const Trajectory gold = sample();
    Trajectory moved = gold;
    moved.frames[2][2] = up(1.0);
    const TempFile a("a.json", write_trajectory(gold));
    const TempFile a_again("a-again.json", write_trajectory(gold));
    const TempFile b("b.json", write_trajectory(moved));

    SECTION("identical files: exit 0") {
        const Outcome o = diff({a.str(), a_again.str()});
        CHECK(o.exit_code == 0);
        CHECK(o.out == "identical\n");
    }
    SECTION("a 1-ULP change: exit 1 with the divergence") {
        const Outcome o = diff({a.str(), b.str()});
        CHECK(o.exit_code == 1);
        CHECK_THAT(o.out, Contains(b.str() + " differs from " + a.str() + ":\n"));
        CHECK_THAT(o.out, Contains("box.y  t = 0.5  golden 1  new 1.0000000000000002"));
        CHECK_THAT(o.out, Contains("ulp 1"));
    }
    SECTION("tolerance mode") {
        const Outcome pass = diff({a.str(), b.str(), "--tolerance", "--ulp", "1"});
        CHECK(pass.exit_code == 0);
        CHECK(pass.out.rfind("within tolerance\n", 0) == 0);
        CHECK_THAT(pass.out, Contains("0/12 values differ"));

        const Outcome fail =
            diff({a.str(), b.str(), "--tolerance", "--atol", "0", "--ulp=position=0"});
        CHECK(fail.exit_code == 1);
        CHECK_THAT(fail.out, Contains("box.y"));

        CHECK(diff({a.str(), b.str(), "--tolerance", "--atol",
                    "position=1e-15,angle=0,"
                    "velocity=0,angular_velocity=0,"
                    "impulse=0,event_time=0"})
                  .exit_code == 0);
    }
    SECTION("a different scene_sha256 is noted, not failed") {
        Trajectory other = gold;
        other.scene_sha256 = sha256_hex("edited drop scene");
        const TempFile c("c.json", write_trajectory(other));
        const Outcome o = diff({a.str(), c.str()});
        CHECK(o.exit_code == 0);
        CHECK_THAT(o.out, Contains("scene_sha256 differs"));
        CHECK_THAT(o.out, Contains("identical"));
    }
    SECTION("another scene is a difference") {
        Trajectory other = gold;
        other.scene = "spin";
        const TempFile c("c.json", write_trajectory(other));
        const Outcome o = diff({a.str(), c.str()});
        CHECK(o.exit_code == 1);
        CHECK_THAT(o.out, Contains("the scene names differ: golden 'drop', new 'spin'"));
    }
    SECTION("--help") {
        const Outcome o = diff({"--help"});
        CHECK(o.exit_code == 0);
        CHECK_THAT(o.out, Contains("usage: impulse diff A B"));
        CHECK_THAT(o.out, Contains("--tolerance"));
    }
    SECTION("bad input throws what main turns into exit 2") {
        using impulse::harness::cli::UsageError;
        const TempFile corrupt("corrupt.json", "{\"schema\": \"impulse/trajectory@1\",");
        CHECK_THROWS_WITH(diff({a.str(), corrupt.str()}), Contains(corrupt.str()));
        CHECK_THROWS_AS(diff({a.str(), corrupt.str()}), InputError);
        CHECK_THROWS_AS(diff({a.str(), "/nonexistent/impulse/b.json"}), InputError);
        CHECK_THROWS_AS(diff({a.str()}), UsageError);
        CHECK_THROWS_WITH(diff({a.str(), b.str(), "--ulp", "1"}), Contains("add --tolerance"));
        CHECK_THROWS_WITH(diff({a.str(), b.str(), "--tolerance", "--atol", "lots"}),
                          Contains("--atol") && Contains("'lots'"));
        CHECK_THROWS_WITH(diff({a.str(), b.str(), "--tolerance", "--atol", "position=1"}),
                          Contains("angle, velocity, angular_velocity, impulse, event_time") &&
                              Contains(a.str()));
        CHECK_THROWS_WITH(diff({a.str(), b.str(), "--tolerance"}), Contains("position"));
    }
    SECTION("through the tool's main: exit codes and one sentence") {
        const TempFile corrupt("corrupt.json", "<<<<<<< HEAD\n");
        const Outcome broken = impulse_main({"diff", a.str(), corrupt.str()});
        CHECK(broken.exit_code == 2);
        CHECK_THAT(broken.err, Contains(corrupt.str()));
        CHECK(impulse_main({"diff", a.str(), b.str(), "--tolerance"}).exit_code == 2);
        CHECK(impulse_main({"diff", a.str(), b.str(), "--tolerance", "--rtol", "x"}).exit_code ==
              2);
        CHECK(impulse_main({"diff", a.str(), b.str()}).exit_code == 1);
        CHECK(impulse_main({"diff", a.str(), a_again.str()}).exit_code == 0);
    }
}

TEST_CASE("a column that is no body channel is compared bit for bit, never by tolerance",
          "[compare]") {
    // Found by fuzz/fuzz_diff: such a column was always reported as a
    // difference, so a trajectory was not identical to itself.
    Trajectory gold = sample();
    gold.columns.push_back("box.spin_energy");
    for (std::size_t k = 0; k < gold.frames.size(); ++k) {
        gold.frames[k].push_back(0.5 * static_cast<double>(k));
    }
    const Comparison same = compare(gold, gold, std::nullopt);
    CHECK(same.identical);
    CHECK(same.structural.empty());

    Trajectory changed = gold;
    changed.frames[2].back() = 7.0;
    const Comparison differs = compare(gold, changed, std::nullopt);
    CHECK_FALSE(differs.identical);
    REQUIRE(differs.structural.size() == 1);
    CHECK(differs.structural[0].find("box.spin_energy") != std::string::npos);
}
