// Comparing trajectories: the ULP metric, the tolerance rule and its
// command-line form, exact and tolerance comparisons. Structural differences,
// long reports and the `impulse diff` verb are in test_compare_reports.cpp.
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

TEST_CASE("ulp_distance counts representable doubles between two values", "[compare]") {
    CHECK(ulp_distance(1.0, 1.0) == 0);
    CHECK(ulp_distance(1.0, std::nextafter(1.0, 2.0)) == 1);
    CHECK(ulp_distance(std::nextafter(1.0, 2.0), 1.0) == 1);
    CHECK(ulp_distance(1.0, std::nextafter(1.0, 0.0)) == 1); // across a binade boundary
    CHECK(ulp_distance(-1.0, std::nextafter(-1.0, -2.0)) == 1);
    CHECK(ulp_distance(1.0, up(1.0, 5)) == 5);

    SECTION("across zero") {
        CHECK(ulp_distance(0.0, -0.0) == 0);
        CHECK(ulp_distance(-0.0, tiny) == 1);
        CHECK(ulp_distance(0.0, -tiny) == 1);
        CHECK(ulp_distance(-tiny, tiny) == 2);
        CHECK(ulp_distance(std::nextafter(0.0, -1.0), std::nextafter(0.0, 1.0)) == 2);
        CHECK(ulp_distance(-1.0, 1.0) == 2 * bits_of(1.0));
        const double max = std::numeric_limits<double>::max();
        CHECK(ulp_distance(-max, max) == 2 * bits_of(max));
    }
    SECTION("infinities sit one step beyond the largest double; NaN saturates") {
        CHECK(ulp_distance(std::numeric_limits<double>::max(), inf) == 1);
        CHECK(ulp_distance(quiet_nan, 1.0) == UINT64_MAX);
        CHECK(ulp_distance(1.0, quiet_nan) == UINT64_MAX);
        CHECK(ulp_distance(quiet_nan, quiet_nan) == UINT64_MAX);
    }
}

TEST_CASE("within passes at the bound and fails one ULP past it", "[compare]") {
    SECTION("atol") {
        CHECK(within(tol(0.5, 0.0, 0), 1.0, 1.5));
        CHECK(within(tol(0.5, 0.0, 0), 1.0, 0.5));
        CHECK_FALSE(within(tol(0.5, 0.0, 0), 1.0, up(1.5)));
    }
    SECTION("rtol scales with the golden value") {
        CHECK(within(tol(0.0, 0.25, 0), 2.0, 2.5));
        CHECK(within(tol(0.0, 0.25, 0), -2.0, -2.5));
        CHECK_FALSE(within(tol(0.0, 0.25, 0), 2.0, up(2.5)));
        CHECK(within(tol(0.25, 0.125, 0), 2.0, 2.5)); // atol + rtol * |gold|
        CHECK_FALSE(within(tol(0.25, 0.125, 0), 2.0, up(2.5)));
    }
    SECTION("ulp alone suffices") {
        CHECK(within(tol(0.0, 0.0, 2), 1.0, up(1.0, 2)));
        CHECK_FALSE(within(tol(0.0, 0.0, 2), 1.0, up(1.0, 3)));
        CHECK(within(tol(0.0, 0.0, 1), -tiny, 0.0));
        CHECK(within(tol(0.0, 0.0, 0), 0.0, -0.0)); // the zeros are equal values
    }
    SECTION("zero tolerance is exact equality of values") {
        CHECK(within(tol(0.0, 0.0, 0), 1.0, 1.0));
        CHECK_FALSE(within(tol(0.0, 0.0, 0), 1.0, up(1.0)));
    }
    SECTION("NaN never passes") {
        CHECK_FALSE(within(tol(inf, 0.0, UINT64_MAX), quiet_nan, 1.0));
        CHECK_FALSE(within(tol(inf, 0.0, UINT64_MAX), 1.0, quiet_nan));
    }
}

TEST_CASE("column_channel maps frame columns to channels", "[compare]") {
    CHECK(column_channel("t") == Channel::event_time);
    CHECK(column_channel("box.x") == Channel::position);
    CHECK(column_channel("box.y") == Channel::position);
    CHECK(column_channel("box.angle") == Channel::angle);
    CHECK(column_channel("box.vx") == Channel::velocity);
    CHECK(column_channel("box.vy") == Channel::velocity);
    CHECK(column_channel("box.omega") == Channel::angular_velocity);
    CHECK(column_channel("wheel.left.omega") == Channel::angular_velocity);
    CHECK_FALSE(column_channel("box.z"));
    CHECK_FALSE(column_channel(".x"));
    CHECK_FALSE(column_channel("x"));
}

TEST_CASE("parse_tolerance_option reads one value or channel=value pairs", "[compare]") {
    SECTION("one value for every channel") {
        const Tolerances t = parse_tolerance_option("--atol", "1e-9", Tolerances{});
        for (const auto& slot : t.channels) {
            REQUIRE(slot);
            CHECK(slot->atol == 1e-9);
            CHECK(slot->rtol == 0.0);
            CHECK(slot->ulp == 0);
        }
    }
    SECTION("pairs replace one field and keep the others") {
        Tolerances base;
        base[Channel::position] = tol(1.0, 0.125, 4);
        const Tolerances t = parse_tolerance_option("--atol", "position=1e-9,velocity=1e-6", base);
        REQUIRE(t[Channel::position]);
        CHECK(t[Channel::position]->atol == 1e-9);
        CHECK(t[Channel::position]->rtol == 0.125);
        CHECK(t[Channel::position]->ulp == 4);
        REQUIRE(t[Channel::velocity]);
        CHECK(t[Channel::velocity]->atol == 1e-6);
        CHECK(t[Channel::velocity]->rtol == 0.0);
        CHECK_FALSE(t[Channel::angle]);
        CHECK_FALSE(t[Channel::event_time]);
    }
    SECTION("rtol and ulp set their own fields") {
        Tolerances t = parse_tolerance_option("--rtol", "angular_velocity=0.5", Tolerances{});
        t = parse_tolerance_option("--ulp", "3", t);
        CHECK(t[Channel::angular_velocity]->rtol == 0.5);
        CHECK(t[Channel::angular_velocity]->ulp == 3);
        CHECK(t[Channel::event_time]->ulp == 3);
        CHECK(t[Channel::event_time]->rtol == 0.0);
        t = parse_tolerance_option("--ulp", "impulse=18446744073709551615", t);
        CHECK(t[Channel::impulse]->ulp == UINT64_MAX);
    }
    SECTION("a negative zero is stored as zero") {
        const Tolerances t = parse_tolerance_option("--atol", "-0", Tolerances{});
        CHECK_FALSE(std::signbit(t[Channel::position]->atol));
    }
    SECTION("bad text names the option and the bad part") {
        const Tolerances base;
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "x", base),
                          Contains("--atol") && Contains("'x'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "", base), Contains("--atol"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "-1e-9", base), Contains("'-1e-9'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "inf", base), Contains("'inf'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "nan", base), Contains("'nan'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--rtol", "1e-9 ", base), Contains("--rtol"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "positon=1e-9", base),
                          Contains("'positon'") && Contains("position, angle, velocity"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "position=", base),
                          Contains("''") && Contains("'position='"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "position=1e-9,", base),
                          Contains("not channel=value"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "position=1e-9,1e-6", base),
                          Contains("'1e-6'") && Contains("not channel=value"));
        CHECK_THROWS_WITH(parse_tolerance_option("--atol", "position=1,position=2", base),
                          Contains("twice"));
        CHECK_THROWS_WITH(parse_tolerance_option("--ulp", "1.5", base),
                          Contains("--ulp") && Contains("'1.5'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--ulp", "velocity=-1", base),
                          Contains("'-1'") && Contains("'velocity=-1'"));
        CHECK_THROWS_WITH(parse_tolerance_option("--ulp", "18446744073709551616", base),
                          Contains("'18446744073709551616'"));
        CHECK_THROWS_AS(parse_tolerance_option("--atol", "x", base), std::invalid_argument);
        CHECK_THROWS_AS(parse_tolerance_option("--bogus", "1", base), std::invalid_argument);
    }
}

TEST_CASE("channels_without_tolerance lists what the golden needs", "[compare]") {
    const Trajectory gold = sample();
    Tolerances t;
    t[Channel::position] = tol(1e-9, 0.0, 0);
    t[Channel::velocity] = tol(1e-9, 0.0, 0);
    CHECK(channels_without_tolerance(gold, t) ==
          std::vector<Channel>{Channel::angle, Channel::angular_velocity, Channel::impulse,
                               Channel::event_time});
    CHECK(channels_without_tolerance(gold, every_channel(tol(0, 0, 0))).empty());

    Trajectory frames_only = gold;
    frames_only.events.clear();
    frames_only.columns = {"t", "box.x"};
    for (auto& frame : frames_only.frames) {
        frame.resize(2);
    }
    CHECK(channels_without_tolerance(frames_only, Tolerances{}) ==
          std::vector<Channel>{Channel::position, Channel::event_time});

    Trajectory empty = gold;
    empty.frames.clear();
    empty.events.clear();
    CHECK(channels_without_tolerance(empty, Tolerances{}).empty());
}

TEST_CASE("identical trajectories compare identical in both modes", "[compare]") {
    const Trajectory gold = sample();
    const Comparison exact = compare(gold, gold, std::nullopt);
    CHECK(exact.identical);
    CHECK(exact.passed);
    CHECK(exact.structural.empty());
    CHECK(exact.first_divergences.empty());
    // 4 frames x (t) + 2 events x (t) = 10 times; 4 x 2 + 2 x 2 positions.
    CHECK(summary(exact, Channel::event_time).compared == 6);
    CHECK(summary(exact, Channel::position).compared == 12);
    CHECK(summary(exact, Channel::impulse).compared == 2);
    CHECK(describe(exact) == "identical\n");

    const Comparison tolerant = compare(gold, gold, every_channel(tol(0, 0, 0)));
    CHECK(tolerant.identical);
    CHECK(tolerant.passed);
}

TEST_CASE("one value one ULP off", "[compare]") {
    const Trajectory gold = sample();
    Trajectory value = gold;
    value.frames[2][2] = up(value.frames[2][2]); // box.y at t = 0.5: 1 -> 1 + 2^-52

    SECTION("exact mode fails naming the column, the frame time and ulp 1") {
        const Comparison c = compare(gold, value, std::nullopt);
        CHECK_FALSE(c.identical);
        CHECK_FALSE(c.passed);
        CHECK(c.structural.empty());
        REQUIRE(c.first_divergences.size() == 1);
        const Divergence& d = c.first_divergences.front();
        CHECK(d.column == "box.y");
        CHECK(d.channel == Channel::position);
        CHECK(d.frame == 2);
        CHECK(d.t == 0.5);
        CHECK(d.gold == 1.0);
        CHECK(d.value == up(1.0));
        CHECK(d.abs_diff == 0x1p-52);
        // Relative to the column's largest golden |y| (3); 1 ULP at that
        // scale's spacing 2^-51 rounds up to 1.
        CHECK(d.rel_diff == 0x1p-52 / 3.0);
        CHECK(d.ulp == 1);

        const std::string text = describe(c);
        CHECK_THAT(text, Contains("first divergence per body and channel:"));
        CHECK_THAT(text, Contains("box.y  t = 0.5  golden 1  new 1.0000000000000002  abs 2.2e-16  "
                                  "rel 7.4e-17  ulp 1"));
        CHECK_THAT(text, Contains("per channel:"));
        CHECK_THAT(text, Contains("1/12 values differ"));
    }
    SECTION("tolerance mode with ulp 1 passes") {
        const Comparison c = compare(gold, value, every_channel(tol(0, 0, 1)));
        CHECK_FALSE(c.identical);
        CHECK(c.passed);
        CHECK(c.first_divergences.empty());
        CHECK(summary(c, Channel::position).differing == 0);
        CHECK(summary(c, Channel::position).max_ulp == 1); // how close it came
    }
    SECTION("tolerance mode with ulp 0 and atol 0 fails") {
        const Comparison c = compare(gold, value, every_channel(tol(0, 0, 0)));
        CHECK_FALSE(c.passed);
        REQUIRE(c.first_divergences.size() == 1);
        CHECK(c.first_divergences.front().column == "box.y");
    }
    SECTION("a missing tolerance is refused, never defaulted") {
        Tolerances t = every_channel(tol(0, 0, 1));
        t[Channel::event_time].reset();
        CHECK_THROWS_AS(compare(gold, value, t), std::invalid_argument);
    }
}

TEST_CASE("Negative and positive zero are told apart in exact mode only", "[compare]") {
    const Trajectory gold = sample();
    Trajectory value = gold;
    value.frames[1][6] = -0.0; // box.omega at t = 0.25

    const Comparison exact = compare(gold, value, std::nullopt);
    CHECK_FALSE(exact.identical);
    CHECK_FALSE(exact.passed);
    REQUIRE(exact.first_divergences.size() == 1);
    const Divergence& d = exact.first_divergences.front();
    CHECK(d.column == "box.omega");
    CHECK(d.channel == Channel::angular_velocity);
    CHECK(d.t == 0.25);
    CHECK(d.abs_diff == 0.0);
    CHECK(d.rel_diff == 0.0);
    CHECK(d.ulp == 0);
    CHECK_THAT(describe(exact), Contains("golden 0  new -0.0"));
    CHECK(summary(exact, Channel::angular_velocity).differing == 1);

    const Comparison tolerant = compare(gold, value, every_channel(tol(0, 0, 0)));
    CHECK_FALSE(tolerant.identical);
    CHECK(tolerant.passed);
}

TEST_CASE("a changed event impulse is the event's divergence", "[compare]") {
    const Trajectory gold = sample();
    Trajectory value = gold;
    value.events[1].impulse = 1.5; // golden 1.25
    value.events[1].vn_after = 1.0;

    const Comparison c = compare(gold, value, std::nullopt);
    CHECK_FALSE(c.passed);
    CHECK(c.structural.empty());
    // Only the first divergent field of the first divergent event is listed.
    REQUIRE(c.first_divergences.size() == 1);
    const Divergence& d = c.first_divergences.front();
    CHECK(d.column == "events[1].impulse");
    CHECK(d.channel == Channel::impulse);
    CHECK(d.frame == 1);
    CHECK(d.t == 0.7);
    CHECK(d.gold == 1.25);
    CHECK(d.value == 1.5);
    CHECK(d.abs_diff == 0.25);
    CHECK(d.rel_diff == 0.25 / 3.5); // relative to the largest golden impulse, 3.5
    CHECK(summary(c, Channel::impulse).differing == 1);
    CHECK(summary(c, Channel::velocity).differing == 1);
    CHECK_THAT(describe(c), Contains("events[1].impulse  t = 0.7  golden 1.25  new 1.5"));

    CHECK(compare(gold, value, every_channel(tol(0.5, 0, 0))).passed);
}

TEST_CASE("per-channel counts and maxima", "[compare]") {
    const Trajectory gold = sample();
    Trajectory value = gold;
    value.frames[1][1] = up(0.5);     // box.x: 0.5 + 2^-53, 1 ulp
    value.frames[2][2] = up(1.0, 3);  // box.y: 1 + 3 * 2^-52, 3 ulps
    value.frames[3][4] = 2.5;         // box.vx: 2 -> 2.5, at the velocity's scale 5 (box.vy)
    value.events[0].point[0] = 0.375; // events[0].point.x: 0.25 -> 0.375
    value.events[0].impulse = 3.5;    // unchanged
    value.frames[0][3] = up(0.5, 2);  // box.angle at t = 0

    const Comparison c = compare(gold, value, std::nullopt);
    const ChannelSummary& position = summary(c, Channel::position);
    CHECK(position.compared == 12); // box.x, box.y in 4 frames; point.x, point.y in 2 events
    CHECK(position.differing == 3);
    CHECK(position.max_abs == 0.125);
    // A contact point is measured at the scale of the bodies' positions too
    // (the largest |x| or |y| over the frames, 3), not only of the points' own.
    CHECK(position.max_rel == 0.125 / 3.0);
    CHECK(position.max_ulp == (std::uint64_t{1} << 48)); // 0.125 over the ULP of [2, 4), 2^-51

    const ChannelSummary& velocity = summary(c, Channel::velocity);
    CHECK(velocity.compared == 12);
    CHECK(velocity.differing == 1);
    CHECK(velocity.max_abs == 0.5);
    // box.vx shares box.vy's scale, 5: 0.5 / 5, and 0.5 over the ULP of [4, 8), 2^-50.
    CHECK(velocity.max_rel == 0.1);
    CHECK(velocity.max_ulp == (std::uint64_t{1} << 49));

    const ChannelSummary& angle = summary(c, Channel::angle);
    CHECK(angle.compared == 8); // box.angle in 4 frames; normal.x, normal.y in 2 events
    CHECK(angle.differing == 1);
    CHECK(angle.max_abs == 0x1p-52);
    CHECK(angle.max_ulp == 1); // 2^-52 at an angle's scale of at least 1 rad

    CHECK(summary(c, Channel::impulse).differing == 0);
    CHECK(summary(c, Channel::impulse).max_abs == 0.0);
    CHECK(summary(c, Channel::angular_velocity).compared == 4);
    CHECK(summary(c, Channel::event_time).compared == 6);

    // In column order, then the event.
    REQUIRE(c.first_divergences.size() == 5);
    CHECK(c.first_divergences[0].column == "box.x");
    CHECK(c.first_divergences[1].column == "box.y");
    CHECK(c.first_divergences[2].column == "box.angle");
    CHECK(c.first_divergences[3].column == "box.vx");
    CHECK(c.first_divergences[4].column == "events[0].point.x");

    SECTION("tolerance mode counts only values outside the tolerance") {
        Tolerances t = every_channel(tol(0, 0, 0));
        t[Channel::position] = tol(0.0, 0.0, 3); // the frame ULPs pass, the event point does not
        const Comparison tc = compare(gold, value, t);
        CHECK_FALSE(tc.passed);
        CHECK(summary(tc, Channel::position).differing == 1);
        CHECK(summary(tc, Channel::position).max_abs == 0.125);
        CHECK(summary(tc, Channel::velocity).differing == 1);
    }
    SECTION("the description has one aligned line per divergent column") {
        const std::vector<std::string> lines = lines_of(describe(c));
        REQUIRE(lines.size() >= 6);
        CHECK(lines[0] == "first divergence per body and channel:");
        const std::size_t t_at = lines[1].find("t = ");
        const std::size_t golden_at = lines[1].find("golden ");
        for (std::size_t i = 1; i <= 5; ++i) {
            CHECK(lines[i].find("t = ") == t_at);
            CHECK(lines[i].find("golden ") == golden_at);
        }
        CHECK_THAT(describe(c), Contains("3/12 values differ  max abs 0.12 "));
    }
}
