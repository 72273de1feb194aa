// ULP and relative differences at the channel's scale
// (harness/gate/scaled_difference.h, docs/gate-rules.md "ULP and relative
// differences"): near zero and across a sign change a few rounding errors
// report a few ULP, and a golden 0 gives a finite relative difference.
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

// comparing.h's sample: box.vx is 0, 0, 0, 2 (its scale 2) and box.omega is 0
// throughout. Its events are the same in every run compared here.

// Every channel bounded by `ulp` ULP alone.
Tolerances every_channel(std::uint64_t ulp) {
    return impulse::test::comparing::every_channel(tol(0.0, 0.0, ulp));
}

} // namespace

TEST_CASE("ULPs near zero are counted at the channel's scale", "[ulp]") {
    // box.vx holds 0, 0, 0, 2 in the golden: its scale is 2, where doubles
    // are 2^-51 apart. A value near zero there is what is left of a
    // cancellation, and a change of k rounding errors of that size is k ULP.
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
        CHECK(c.first_divergences[0].ulp == 1); // 2e-300 is far below one spacing, 2^-51
        gold.frames[1][4] = 0x1p-53;
        value.frames[1][4] = -0x1p-53;
        c = compare(gold, value, std::nullopt);
        CHECK(c.first_divergences[0].ulp == 1); // 2^-52 / 2^-51 rounds up to 1
        // A ULP tolerance bounds the same count: 1 ULP passes.
        CHECK(compare(gold, value, every_channel(1)).passed);
        CHECK_FALSE(compare(gold, value, every_channel(0)).passed);
    }
    SECTION("a golden 0 gives a finite relative difference") {
        Trajectory value = gold_base;
        value.frames[0][4] = 1e-10; // box.vx golden 0, scale 2
        value.frames[0][6] = 1e-10; // box.omega: 0 in every golden frame
        const Comparison c = compare(gold_base, value, std::nullopt);
        REQUIRE(c.first_divergences.size() == 2);
        CHECK(c.first_divergences[0].column == "box.vx");
        CHECK(c.first_divergences[0].rel_diff == 1e-10 / 2.0);
        CHECK(c.first_divergences[1].column == "box.omega");
        CHECK(c.first_divergences[1].rel_diff == 1.0); // a channel of zeros: relative to new
        CHECK(std::isfinite(summary(c, Channel::velocity).max_rel));
        CHECK(std::isfinite(summary(c, Channel::angular_velocity).max_rel));
    }
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
