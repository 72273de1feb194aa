// The sweep's two targets against Box2D 2.4.1 (sweep_targets.cpp), judged on
// synthetic points with hand-picked costs and errors, so each verdict is known.
#include "sweep.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

using namespace impulse;
using namespace impulse::harness;

namespace {

// Synthetic points for the targets: hand-picked costs (s/s) and errors.
SweepPoint impulse_at(double dt, double cost, double error) {
    SweepPoint p;
    p.dt = dt;
    p.integrator = Integrator::verlet;
    p.toi = TimeOfImpactMethod::secant;
    p.toi_tolerance = 1e-12;
    p.family = sweep_family(p);
    p.ok = true;
    p.cost_median = cost;
    p.error = error;
    return p;
}

SweepPoint box2d_at(double dt, int substeps, int velocity, int position, double cost,
                    double error) {
    SweepPoint p;
    p.box2d = true;
    p.dt = dt;
    p.substeps = substeps;
    p.velocity_iterations = velocity;
    p.position_iterations = position;
    p.family = sweep_family(p);
    p.ok = true;
    p.cost_median = cost;
    p.error = error;
    return p;
}

SweepPoint box2d_60hz(double cost, double error) {
    return box2d_at(1.0 / 60.0, 1, 8, 3, cost, error);
}

SweepResult result_of(std::vector<SweepPoint> points) {
    SweepResult r;
    r.scene = "synthetic";
    r.points = std::move(points);
    return r;
}

} // namespace

TEST_CASE("Targets are met: an affordable impulse point 1e6 times better, Box2D's front dominated",
          "[sweep]") {
    const SweepResult r = result_of({
        impulse_at(1.0 / 30.0, 2e-4, 1e-8),   // 0: cheaper than Box2D at 60 Hz
        impulse_at(1.0 / 60.0, 4e-4, 1e-9),   // 1: exactly Box2D's cost, smaller error: the best
        impulse_at(1.0 / 960.0, 1e-2, 1e-12), // 2: smallest error, but dearer than Box2D
        [] {
            SweepPoint failed = impulse_at(1.0 / 120.0, 0.0, 0.0); // a refused point counts for
            failed.ok = false;                                     // nothing, however cheap
            return failed;
        }(),
        box2d_60hz(4e-4, 1e-1),                        // 4: front
        box2d_at(1.0 / 240.0, 1, 8, 3, 1.6e-3, 2e-2),  // 5: front
        box2d_at(1.0 / 60.0, 4, 30, 10, 3.2e-3, 3e-2), // 6: behind 5 on Box2D's own front
    });
    const SweepTargets t = evaluate_targets(r);
    CHECK(t.measured);
    REQUIRE(t.box2d_60hz_found);
    CHECK(t.box2d_60hz == 4);
    CHECK(t.error_target_measured);
    REQUIRE(t.impulse_found);
    CHECK(t.best_impulse == 1);
    CHECK_FALSE(t.impulse_error_zero);
    CHECK(t.error_ratio == Approx(1e8));
    CHECK(t.cost_margin == 1.0);
    CHECK(t.error_target_met);
    CHECK(t.box2d_front_size == 2);
    CHECK(t.box2d_front_dominated == 2);
    CHECK_FALSE(t.undominated_found);
    CHECK(t.front_target_met);
}

TEST_CASE("Target 1 is not met when the affordable impulse error is not 1e6 times smaller",
          "[sweep]") {
    SECTION("ratio 1e5") {
        const SweepResult r = result_of({
            impulse_at(1.0 / 30.0, 5e-4, 1e-7),   // 0: half Box2D's cost, 1e5 times smaller
            impulse_at(1.0 / 240.0, 2e-3, 1e-15), // 1: good enough, but dearer
            box2d_60hz(1e-3, 1e-2),               // 2
        });
        const SweepTargets t = evaluate_targets(r);
        REQUIRE(t.impulse_found);
        CHECK(t.best_impulse == 0);
        CHECK(t.error_ratio == Approx(1e5));
        CHECK(t.cost_margin == Approx(2.0));
        CHECK_FALSE(t.error_target_met);
        // Target 2 is judged on its own: point 0 dominates Box2D's only point.
        CHECK(t.front_target_met);
    }
    SECTION("no impulse point as cheap as Box2D at 60 Hz") {
        const SweepResult r = result_of({
            impulse_at(1.0 / 30.0, 2e-3, 1e-15),
            box2d_60hz(1e-3, 1e-2),
        });
        const SweepTargets t = evaluate_targets(r);
        CHECK(t.error_target_measured);
        CHECK_FALSE(t.impulse_found);
        CHECK_FALSE(t.error_target_met);
        CHECK_FALSE(t.front_target_met); // the impulse point costs more
        CHECK(t.undominated_found);
        CHECK(t.first_undominated == 1);
    }
}

TEST_CASE("Target 1 is not measured without Box2D's 60 Hz point", "[sweep]") {
    SECTION("the grid lacks dt 1/60 with 1 sub-step and 8/3 iterations") {
        const SweepResult r = result_of({
            impulse_at(1.0 / 60.0, 1e-5, 1e-15),
            box2d_at(1.0 / 120.0, 1, 8, 3, 1e-4, 1e-2),               // other dt
            box2d_at(1.0 / 60.0, 4, 8, 3, 1e-4, 1e-2),                // other sub-steps
            box2d_at(1.0 / 60.0, 1, 30, 10, 1e-4, 1e-2),              // other iterations
            box2d_at(1.0 / 60.0 * (1.0 + 1e-9), 1, 8, 3, 1e-4, 1e-2), // not within 1e-12
        });
        const SweepTargets t = evaluate_targets(r);
        CHECK(t.measured);
        CHECK_FALSE(t.box2d_60hz_found);
        CHECK_FALSE(t.error_target_measured);
        CHECK_FALSE(t.error_target_met);
        CHECK(t.front_target_met); // target 2 needs no particular point
    }
    SECTION("a dt typed in decimal is 1/60 to rounding; the closest wins") {
        const SweepResult r = result_of({
            box2d_at(0.0166666666666667, 1, 8, 3, 1e-4, 1e-2),
            box2d_at(1.0 / 60.0, 1, 8, 3, 1e-4, 1e-2),
        });
        const SweepTargets t = evaluate_targets(r);
        REQUIRE(t.box2d_60hz_found);
        CHECK(t.box2d_60hz == 1);
    }
    SECTION("the 60 Hz point failed") {
        SweepPoint failed = box2d_60hz(0.0, 0.0);
        failed.ok = false;
        const SweepResult r = result_of({
            impulse_at(1.0 / 60.0, 1e-5, 1e-15),
            failed,
            box2d_at(1.0 / 120.0, 1, 8, 3, 1e-4, 1e-2),
        });
        const SweepTargets t = evaluate_targets(r);
        CHECK(t.measured);
        CHECK(t.box2d_60hz_found);
        CHECK(t.box2d_60hz == 1);
        CHECK_FALSE(t.error_target_measured);
        CHECK_FALSE(t.error_target_met);
        CHECK(t.box2d_front_size == 1); // the failed point is on no front
    }
    SECTION("no Box2D point succeeded, or none at all") {
        SweepPoint failed = box2d_60hz(0.0, 0.0);
        failed.ok = false;
        for (const SweepResult& r : {result_of({impulse_at(1.0 / 60.0, 1e-5, 1e-15)}),
                                     result_of({impulse_at(1.0 / 60.0, 1e-5, 1e-15), failed})}) {
            const SweepTargets t = evaluate_targets(r);
            CHECK_FALSE(t.measured);
            CHECK_FALSE(t.error_target_met);
            CHECK(t.box2d_front_size == 0);
            CHECK_FALSE(t.front_target_met);
        }
    }
}

TEST_CASE("An impulse error of 0 is taken at the error floor", "[sweep]") {
    // 2e-3 / 1e-9 = 2e6: met, though only as a lower bound.
    SweepTargets t = evaluate_targets(result_of({
        impulse_at(1.0 / 30.0, 1e-4, 0.0),
        box2d_60hz(1e-3, 2e-3),
    }));
    REQUIRE(t.impulse_found);
    CHECK(t.impulse_error_zero);
    CHECK(std::isfinite(t.error_ratio));
    CHECK(t.error_ratio == Approx(2e-3 / sweep_error_floor));
    CHECK(t.cost_margin == Approx(10.0));
    CHECK(t.error_target_met);
    // 5e-4 / 1e-9 = 5e5: an exact run cannot show more than the floor allows.
    t = evaluate_targets(result_of({
        impulse_at(1.0 / 30.0, 1e-4, 0.0),
        box2d_60hz(1e-3, 5e-4),
    }));
    CHECK(t.impulse_error_zero);
    CHECK(t.error_ratio == Approx(5e5));
    CHECK_FALSE(t.error_target_met);
}

TEST_CASE("Target 2 names the cheapest Box2D front point no impulse point dominates", "[sweep]") {
    const SweepResult r = result_of({
        impulse_at(1.0 / 30.0, 5e-5, 1e-2),           // 0: dominates point 3 only
        impulse_at(1.0 / 960.0, 5e-3, 1e-12),         // 1: dearer than every Box2D point
        box2d_at(1.0 / 960.0, 4, 30, 10, 4e-3, 1e-4), // 2: front, undominated
        box2d_60hz(1e-4, 1e-1),                       // 3: front, dominated by 0
        box2d_at(1.0 / 240.0, 1, 8, 3, 1e-3, 1e-3),   // 4: front, undominated, cheaper than 2
        box2d_at(1.0 / 240.0, 4, 8, 3, 2e-3, 5e-3),   // 5: behind 4: not on Box2D's front
    });
    const SweepTargets t = evaluate_targets(r);
    CHECK(t.box2d_front_size == 3);
    CHECK(t.box2d_front_dominated == 1);
    REQUIRE(t.undominated_found);
    CHECK(t.first_undominated == 4);
    CHECK_FALSE(t.front_target_met);
    // Target 1 on the same points: 1e-1 / 1e-2.
    CHECK(t.best_impulse == 0);
    CHECK(t.error_ratio == Approx(10.0));
    CHECK_FALSE(t.error_target_met);
}

TEST_CASE("Ties: equal cost and equal error is not domination", "[sweep]") {
    SECTION("an impulse point equal to Box2D's") {
        const SweepTargets t = evaluate_targets(result_of({
            impulse_at(1.0 / 60.0, 1e-3, 1e-2),
            box2d_60hz(1e-3, 1e-2),
        }));
        CHECK(t.box2d_front_size == 1);
        CHECK(t.box2d_front_dominated == 0);
        CHECK(t.undominated_found);
        CHECK(t.first_undominated == 1);
        CHECK_FALSE(t.front_target_met);
        // Equal cost is affordable for target 1; equal error is a ratio of 1.
        REQUIRE(t.impulse_found);
        CHECK(t.best_impulse == 0);
        CHECK(t.error_ratio == 1.0);
        CHECK(t.cost_margin == 1.0);
        CHECK_FALSE(t.error_target_met);
    }
    SECTION("equal in one, strictly smaller in the other, dominates") {
        for (const SweepPoint& better : {impulse_at(1.0 / 60.0, 1e-3, 1e-3),    // equal cost
                                         impulse_at(1.0 / 30.0, 5e-4, 1e-2)}) { // equal error
            const SweepTargets t = evaluate_targets(result_of({better, box2d_60hz(1e-3, 1e-2)}));
            CHECK(t.box2d_front_dominated == 1);
            CHECK(t.front_target_met);
        }
    }
    SECTION("equal errors: the cheaper impulse point is the best") {
        const SweepTargets t = evaluate_targets(result_of({
            impulse_at(1.0 / 60.0, 2e-4, 1e-9),
            impulse_at(1.0 / 30.0, 1e-4, 1e-9),
            box2d_60hz(4e-4, 1e-2),
        }));
        CHECK(t.best_impulse == 1);
        CHECK(t.cost_margin == Approx(4.0));
    }
}
