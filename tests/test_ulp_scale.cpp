// ULP and relative differences at the channel's scale
// (harness/gate/scaled_difference.h, docs/gate-rules.md "ULP and relative
// differences"): near zero and across a sign change a few rounding errors
// report a few ULP, and a golden 0 gives a finite relative difference.
#include "channel_scale.h"
#include "compare.h"
#include "scaled_difference.h"
#include "support/comparing.h"
#include "tolerance.h"
#include "trajectory.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>

using namespace impulse::harness;
using namespace impulse::test::comparing;

namespace {

// comparing.h's sample: box.vx is 0, 0, 0, 2 and box.vy reaches -5, so the
// velocity's scale is 5; box.omega is 0 throughout. Its events are the same
// in every run compared here.

// Every channel bounded by `ulp` ULP alone.
Tolerances every_channel(std::uint64_t ulp) {
    return impulse::test::comparing::every_channel(tol(0.0, 0.0, ulp));
}

} // namespace

TEST_CASE("ULPs near zero are counted at the channel's scale", "[ulp]") {
    // box.vx holds 0, 0, 0, 2 in the golden and box.vy reaches -5: the
    // velocity's scale is 5, where doubles are 2^-50 apart. A value near zero
    // there is what is left of a cancellation, and a change of k rounding
    // errors of that size is k ULP (here k 2^-51, so at most k).
    const Trajectory gold_base = sample();
    SECTION("a 1 to 4 ULP change near zero reports at most 4") {
        for (int k = 1; k <= 4; ++k) {
            Trajectory gold = gold_base;
            gold.frames[1][4] = 1e-17;
            Trajectory value = gold;
            value.frames[1][4] = 1e-17 + k * 0x1p-51;
            const Comparison c = compare(gold, value, std::nullopt);
            REQUIRE(c.first_divergences.size() == 1);
            INFO("k = " << k);
            CHECK(c.first_divergences[0].ulp >= 1);
            CHECK(c.first_divergences[0].ulp <= 4);
            CHECK(summary(c, Channel::velocity).max_ulp <= 4);
            // Counted on the line of doubles it would be about 10^15.
            CHECK(ulp_distance(gold.frames[1][4], value.frames[1][4]) > 1000000000000ULL);
        }
    }
    SECTION("a sign change across zero reports the small number") {
        Trajectory gold = gold_base;
        gold.frames[1][4] = 1e-300;
        Trajectory value = gold;
        value.frames[1][4] = -1e-300;
        Comparison c = compare(gold, value, std::nullopt);
        REQUIRE(c.first_divergences.size() == 1);
        CHECK(c.first_divergences[0].ulp == 1); // 2e-300 is far below one spacing, 2^-50
        gold.frames[1][4] = 0x1p-53;
        value.frames[1][4] = -0x1p-53;
        c = compare(gold, value, std::nullopt);
        CHECK(c.first_divergences[0].ulp == 1); // 2^-52 / 2^-50 rounds up to 1
        // A ULP tolerance bounds the same count: 1 ULP passes.
        CHECK(compare(gold, value, every_channel(1)).passed);
        CHECK_FALSE(compare(gold, value, every_channel(0)).passed);
    }
    SECTION("a golden 0 gives a finite relative difference") {
        Trajectory value = gold_base;
        value.frames[0][4] = 1e-10; // box.vx golden 0, scale 5 (box.vy's)
        value.frames[0][6] = 1e-10; // box.omega: 0 in every golden frame
        const Comparison c = compare(gold_base, value, std::nullopt);
        REQUIRE(c.first_divergences.size() == 2);
        CHECK(c.first_divergences[0].column == "box.vx");
        CHECK(c.first_divergences[0].rel_diff == 1e-10 / 5.0);
        CHECK(c.first_divergences[1].column == "box.omega");
        CHECK(c.first_divergences[1].rel_diff == 1.0); // a channel of zeros: relative to new
        CHECK(std::isfinite(summary(c, Channel::velocity).max_rel));
        CHECK(std::isfinite(summary(c, Channel::angular_velocity).max_rel));
    }
}

TEST_CASE("a body's vector components share a scale and an angle's is at least a radian", "[ulp]") {
    Trajectory gold = sample();
    for (std::vector<double>& frame : gold.frames) {
        frame[1] = 0.0;   // box.x: dropped straight, 0 in every frame; box.y up to 3
        frame[3] = 1e-15; // box.angle: a rounding's turn, never more
    }
    const std::vector<double> scales = column_scales(gold);
    CHECK(scales[0] == 0.75); // t: its own largest
    CHECK(scales[1] == 3.0);  // box.x takes box.y's
    CHECK(scales[2] == 3.0);  // box.y
    CHECK(scales[3] == 1.0);  // box.angle: 1 rad
    CHECK(scales[4] == 5.0);  // box.vx takes box.vy's
    CHECK(scales[5] == 5.0);  // box.vy
    CHECK(scales[6] == 0.0);  // box.omega: all zeros, no partner
    Trajectory value = gold;
    value.frames[2][1] = 0x1p-51;         // one rounding error at y's scale, 3 (spacing 2^-51)
    value.frames[2][3] = 1e-15 + 0x1p-52; // one rounding error of a radian
    const Comparison c = compare(gold, value, std::nullopt);
    REQUIRE(c.first_divergences.size() == 2);
    CHECK(c.first_divergences[0].column == "box.x");
    CHECK(c.first_divergences[0].ulp == 1);
    CHECK(c.first_divergences[0].rel_diff == 0x1p-51 / 3.0);
    CHECK(c.first_divergences[1].column == "box.angle");
    CHECK(c.first_divergences[1].ulp == 1);
    CHECK(c.first_divergences[1].rel_diff < 2.3e-16);
    // Each on its own would read about 2^52 ULP and a relative difference of
    // 1 (x, a column of zeros) or 0.2 (the angle).
    CHECK(ulp_at_scale(0.0, 0x1p-51, 0.0) > 1000000000000ULL);
    // A ULP tolerance of 1 passes both.
    CHECK(compare(gold, value, every_channel(1)).passed);
}

TEST_CASE("ulp_at_scale and relative_at_scale", "[ulp]") {
    CHECK(ulp_at_scale(1.0, up(1.0, 3), 0.0) == 3); // same binade: the count of doubles
    CHECK(ulp_at_scale(1.0, up(1.0, 3), 1.5) == 3);
    CHECK(ulp_at_scale(0.0, -0.0, 1.0) == 0);
    CHECK(ulp_at_scale(-tiny, tiny, 0.0) == 2);
    CHECK(ulp_at_scale(quiet_nan, 1.0, 1.0) == UINT64_MAX);
    CHECK(ulp_at_scale(1.0, inf, 1.0) == UINT64_MAX);
    CHECK(ulp_at_scale(-std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                       0.0) == UINT64_MAX);
    CHECK(relative_at_scale(0.0, 0.5, 2.0) == 0.25);
    CHECK(relative_at_scale(4.0, 5.0, 2.0) == 0.25); // |gold| above the scale: relative to it
    CHECK(relative_at_scale(0.0, 0.5, 0.0) == 1.0);
    CHECK(relative_at_scale(-0.0, 0.0, 0.0) == 0.0);
}
