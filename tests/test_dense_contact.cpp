// Dense contact by time-stepping (solver.resting_method = time_stepping;
// docs/physics.md, "Dense contact: time-stepping", Eqs. 10-16): the answers
// the method gives exactly, derived there and computed here from the bodies
// each test builds. A stack and a heavy pair rest with every contact impulse
// the weight above times h; a box slides down a frictionless slope with
// exactly g sin(theta) per step; a box wedged between a ramp and a wall rests
// in the closed-form pose with the closed-form forces; a drop converges at
// first order; world and local stepping give the same bits.
#include "contact_candidates.h"
#include "manifold.h"
#include "support.h"
#include "support/random_piles.h"
#include "world.h"

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <vector>

using namespace impulse;
using impulse::test::dynamic_body;
using impulse::test::static_body;
using impulse::test::time_stepping;
using impulse::test::piles::check_pile_settles;
using impulse::test::piles::PileCase;
using impulse::test::piles::random_pile;
using impulse::test::piles::sweep_cases;

namespace {

constexpr double g = 9.81;
constexpr double h60 = 1.0 / 60.0;

double mass_of(const Body& body) {
    return 1.0 / body.inv_mass;
}

// Newton's second law for bodies first..last over one step (Eq. 13): their
// momentum changes by gravity's h m g plus the impulses from outside the set;
// impulses between them cancel. So for a column whose contact normals are
// vertical, the impulse through the contact under body `first` is the
// column's vertical momentum change minus gravity's share.
double impulse_under(const World& before, const World& after, std::size_t first, std::size_t last) {
    double momentum_change = 0.0;
    double weight_impulse = 0.0;
    for (std::size_t j = first; j <= last; ++j) {
        const double m = mass_of(after.bodies[j]);
        momentum_change +=
            m * (after.bodies[j].state.velocity.y - before.bodies[j].state.velocity.y);
        weight_impulse += m * g * h60;
    }
    return momentum_change + weight_impulse;
}

} // namespace

// With 20 points the island goes to the iterative solver. Projected
// Gauss-Seidel stopped at its 200-sweep cap with the impulses 20% off; MPRGP
// (conjugate gradients on the free set) ends a 20-unknown problem in at most
// 20 products to rounding, so the pivoting solver's 1e-12 holds here too.
TEST_CASE(
    "each step the impulse under box k of a stack of ten is h g times the mass at and above k",
    "[dense-contact]") {
    // Eq. 15: at rest v = 0, so phase 2's holding LCP gives each contact the
    // impulse that cancels gravity's kick on everything it carries.
    std::vector<Body> bodies{static_body(make_box(5.0, 0.5), {0.0, -0.5})};
    for (int i = 0; i < 10; ++i) {
        bodies.push_back(dynamic_body(make_box(0.5, 0.25), 1.0 + 0.1 * i, {0.0, 0.25 + 0.5 * i}));
    }
    const std::vector<Body> initial = bodies;
    World world = make_world(std::move(bodies), {0.0, -g}, 0.5, time_stepping());
    const double d = world.solver.contact_tolerance;
    std::vector<CollisionEvent> events;
    double worst = 0.0;
    for (int k = 0; k < 600; ++k) {
        const World before = world;
        REQUIRE_FALSE(step(world, k * h60, h60, events));
        for (std::size_t first = 1; first <= 10; ++first) {
            double carried = 0.0;
            for (std::size_t j = first; j <= 10; ++j) {
                carried += mass_of(world.bodies[j]);
            }
            const double exact = h60 * g * carried;
            const double measured = impulse_under(before, world, first, 10);
            worst = std::max(worst, std::abs(measured - exact) / exact);
        }
    }
    CHECK(worst <= 1e-12);
    CHECK(events.empty()); // holding is no impact
    CHECK(world.work.time_stepping_steps == 600);
    for (std::size_t i = 1; i < initial.size(); ++i) {
        INFO("box " << i);
        const BodyState& s = world.bodies[i].state;
        CHECK(std::abs(s.position.y - initial[i].state.position.y) <= d);
        CHECK(std::abs(s.position.x - initial[i].state.position.x) <= d);
        CHECK(std::abs(s.angle) <= d);
    }
}

TEST_CASE("a 1:1000 mass pair rests with impulses m_top g h and (m_top + m_bottom) g h to "
          "rounding",
          "[dense-contact]") {
    for (const double top_mass : {1000.0, 0.001}) {
        INFO("top mass " << top_mass << " kg on 1 kg");
        std::vector<Body> bodies{static_body(make_box(5.0, 0.5), {0.0, -0.5}),
                                 dynamic_body(make_box(0.5, 0.25), 1.0, {0.0, 0.25}),
                                 dynamic_body(make_box(0.5, 0.25), top_mass, {0.0, 0.75})};
        World world = make_world(std::move(bodies), {0.0, -g}, 0.5, time_stepping());
        std::vector<CollisionEvent> events;
        double worst_between = 0.0;
        double worst_under = 0.0;
        for (int k = 0; k < 600; ++k) {
            const World before = world;
            REQUIRE_FALSE(step(world, k * h60, h60, events));
            const double between = h60 * g * top_mass;
            const double under = h60 * g * (top_mass + 1.0);
            worst_between = std::max(
                worst_between, std::abs(impulse_under(before, world, 2, 2) - between) / between);
            worst_under =
                std::max(worst_under, std::abs(impulse_under(before, world, 1, 2) - under) / under);
        }
        // Rounding, grown by the Delassus matrix's condition, which is about
        // the mass ratio: 64 epsilon x 1000 (1.4e-11).
        const double rounding = 64.0 * std::numeric_limits<double>::epsilon() * 1000.0;
        INFO("worst relative errors " << worst_between << " between, " << worst_under << " under");
        CHECK(worst_between <= rounding);
        CHECK(worst_under <= rounding);
        CHECK(events.empty());
        CHECK(std::abs(world.bodies[2].state.position.y - 0.75) <= world.solver.contact_tolerance);
    }
}

TEST_CASE("on a frictionless slope a box gains exactly h g sin(theta) along it every step",
          "[dense-contact]") {
    // Eq. 12 with the normal impulse perpendicular to the slope: the velocity
    // along the slope after n steps is n h g sin(theta) whatever the
    // integrator (contact islands move semi-implicitly), and the distance
    // slid is h^2 g sin(theta) n (n + 1) / 2.
    const double theta = 0.5235987755982988; // 30 degrees
    const Rotation q = rotation_of(theta);
    const Vec2 downhill{-q.c, -q.s};
    const Vec2 normal{-q.s, q.c};
    const double half_height = 0.2;
    const Vec2 touch = 0.5 * normal; // on the slope's top face
    const int n = 120;
    for (const Integrator integrator :
         {Integrator::euler, Integrator::symplectic_euler, Integrator::verlet, Integrator::rk4}) {
        INFO("integrator " << static_cast<int>(integrator));
        std::vector<Body> bodies{
            static_body(make_box(20.0, 0.5), {0.0, 0.0}, theta),
            dynamic_body(make_box(0.3, half_height), 2.0, touch + half_height * normal, theta)};
        World world = make_world(std::move(bodies), {0.0, -g}, 0.5, time_stepping(integrator));
        const Vec2 start = world.bodies[1].state.position;
        std::vector<CollisionEvent> events;
        for (int k = 0; k < n; ++k) {
            REQUIRE_FALSE(step(world, k * h60, h60, events));
            const double along = dot(world.bodies[1].state.velocity, downhill);
            const double exact = (k + 1) * h60 * g * q.s;
            REQUIRE(std::abs(along - exact) <= 1e-12 * exact);
        }
        CHECK(events.empty());
        const Vec2 moved = world.bodies[1].state.position - start;
        const double slid = h60 * h60 * g * q.s * n * (n + 1) / 2.0;
        CHECK(std::abs(dot(moved, downhill) - slid) <= 1e-9 * slid);
        CHECK(std::abs(dot(moved, normal)) <= world.solver.contact_tolerance);
        CHECK(std::abs(world.bodies[1].state.angle - theta) <= 1e-12);
    }
}

TEST_CASE("a box wedged between a ramp and a wall rests in the closed-form pose with the "
          "closed-form forces",
          "[dense-contact]") {
    // The ramp descends toward +x at theta; its top face runs through the
    // origin along t = (cos, -sin), normal n = (sin, cos). The wall's face is
    // x = 0. A box of half extents a x b slides down from rest, its top-front
    // corner meets the wall at e = 0, and it rests (docs/physics.md, "Exact
    // answers for checking", the ramp wedge): centre s* t + b n with
    // s* = -(a + 2 b tan), angle -theta, wall force m g tan, back-bottom
    // N2 = m g (a cos + b sin) / (2 a), front-bottom N1 = m g / cos - N2.
    const double theta = 0.5235987755982988;
    const double a = 0.5;
    const double b = 0.25;
    const double m = 2.0;
    const double c = std::cos(theta);
    const double s = std::sin(theta);
    const Vec2 t{c, -s};
    const Vec2 n{s, c};
    const double s_rest = -(a + 2.0 * b * (s / c));
    std::vector<Body> bodies{static_body(make_box(3.0, 0.5), -2.5 * t - 0.5 * n, -theta),
                             static_body(make_box(0.5, 3.0), {0.5, 1.0}),
                             dynamic_body(make_box(a, b), m, (s_rest - 1.0) * t + b * n, -theta)};
    World world = make_world(std::move(bodies), {0.0, -g}, 0.0, time_stepping());
    std::vector<CollisionEvent> events;
    const int steps = 180;
    World before = world;
    for (int k = 0; k < steps; ++k) {
        before = world;
        REQUIRE_FALSE(step(world, k * h60, h60, events));
    }
    REQUIRE_FALSE(events.empty()); // the corner's arrival at the wall is an impact
    const BodyState& rest = world.bodies[2].state;
    const Vec2 centre = s_rest * t + b * n;
    const double d = world.solver.contact_tolerance;
    CHECK(std::abs(rest.position.x - centre.x) <= 4.0 * d);
    CHECK(std::abs(rest.position.y - centre.y) <= 4.0 * d);
    CHECK(std::abs(rest.angle + theta) <= 4.0 * d);
    CHECK(length(rest.velocity) <= d);
    // The last step's impulses, read from the box's change of momentum (Eq.
    // 13) through the three contacts of the closed-form pose: the two bottom
    // corners push along n, the wall along (-1, 0) at the top-front corner.
    const BodyState& was = before.bodies[2].state;
    const Vec2 push = m * (rest.velocity - was.velocity) - m * h60 * world.gravity;
    const double inertia = m * (4.0 * a * a + 4.0 * b * b) / 12.0;
    const double spin = inertia * (rest.angular_velocity - was.angular_velocity);
    const double sum_bottom = push.y / c; // (l1 + l2) n + lw (-1, 0) = push
    const double wall = sum_bottom * s - push.x;
    const double difference = (spin - wall * (b * c - a * s)) / a; // torques a l1 - a l2 + ...
    const double front = 0.5 * (sum_bottom + difference);
    const double back = 0.5 * (sum_bottom - difference);
    const double w_exact = m * g * s / c;
    const double back_exact = m * g * (a * c + b * s) / (2.0 * a);
    const double front_exact = m * g / c - back_exact;
    CHECK(std::abs(wall / h60 - w_exact) <= 1e-9 * w_exact);
    CHECK(std::abs(back / h60 - back_exact) <= 1e-9 * back_exact);
    CHECK(std::abs(front / h60 - front_exact) <= 1e-9 * front_exact);
}

namespace {

struct DropErrors {
    double time = 0.0;  // largest |t_event - t1|
    double speed = 0.0; // largest |vn_after - e v1|
};

// A disc dropped onto a floor from the gap that puts its first impact at each
// t1 given, run until that impact under time-stepping: the worst errors of
// the impact's time and rebound speed against "Drop" (docs/physics.md).
DropErrors first_impact_errors(const std::vector<double>& impact_times, double e, double h) {
    DropErrors worst;
    for (const double t1 : impact_times) {
        const double h0 = 0.5 * g * t1 * t1;
        const double r = 0.25;
        std::vector<Body> bodies{static_body(make_box(5.0, 0.5), {0.0, -0.5}),
                                 dynamic_body(make_circle(r), 1.0, {0.0, r + h0})};
        World world = make_world(std::move(bodies), {0.0, -g}, e, time_stepping());
        std::vector<CollisionEvent> events;
        for (int k = 0; events.empty() && k * h < 2.0 * t1; ++k) {
            REQUIRE_FALSE(step(world, k * h, h, events));
        }
        REQUIRE_FALSE(events.empty());
        const double v1 = g * t1;
        const CollisionEvent& first = events.front();
        INFO("t1 " << t1 << ", h " << h);
        // Eq. 16: the impact acts at a step's start within h of t1 (plus the
        // prediction's h^2 / (2 t1)), the rebound speed within |g| h.
        CHECK(std::abs(first.time - t1) <= h * (1.0 + h / t1));
        CHECK(std::abs(first.vn_after - e * v1) <= g * h);
        worst.time = std::max(worst.time, std::abs(first.time - t1));
        worst.speed = std::max(worst.speed, std::abs(first.vn_after - e * v1));
    }
    return worst;
}

} // namespace

TEST_CASE("the drop under time-stepping converges at first order", "[dense-contact]") {
    // The error depends on where t1 falls within its step, so each h takes the
    // worst over 32 drops whose t1 are spread over a step by the golden ratio
    // (no two alike at any of the three steps): about e g h and h, halving
    // with h.
    std::vector<double> impact_times;
    const double golden = 0.6180339887498949;
    for (int j = 0; j < 32; ++j) {
        const double phase = j * golden - std::floor(j * golden);
        impact_times.push_back(0.5 + phase * h60);
    }
    const double e = 0.5;
    const DropErrors coarse = first_impact_errors(impact_times, e, h60);
    const DropErrors middle = first_impact_errors(impact_times, e, h60 / 2.0);
    const DropErrors fine = first_impact_errors(impact_times, e, h60 / 4.0);
    INFO("time errors " << coarse.time << " " << middle.time << " " << fine.time);
    INFO("speed errors " << coarse.speed << " " << middle.speed << " " << fine.speed);
    for (const double ratio : {coarse.time / middle.time, middle.time / fine.time,
                               coarse.speed / middle.speed, middle.speed / fine.speed}) {
        CHECK(ratio >= 1.6);
        CHECK(ratio <= 2.5);
    }
}

TEST_CASE("world and local stepping give the same bits under time-stepping", "[dense-contact]") {
    PileCase pile;
    pile.seed = 7;
    pile.count = 20;
    pile.e = 0.5;
    World world = random_pile(pile);
    pile.stepping = Stepping::local;
    World local = random_pile(pile);
    std::vector<CollisionEvent> world_events;
    std::vector<CollisionEvent> local_events;
    for (int k = 0; k < 180; ++k) {
        REQUIRE_FALSE(step(world, k * h60, h60, world_events));
        REQUIRE_FALSE(step(local, k * h60, h60, local_events));
        for (std::size_t i = 0; i < world.bodies.size(); ++i) {
            INFO("step " << k << ", body " << i);
            REQUIRE(std::memcmp(&world.bodies[i].state, &local.bodies[i].state,
                                sizeof(BodyState)) == 0);
        }
    }
    REQUIRE(world_events.size() == local_events.size());
    CHECK_FALSE(world_events.empty());
    for (std::size_t i = 0; i < world_events.size(); ++i) {
        INFO("event " << i);
        CHECK(std::memcmp(&world_events[i], &local_events[i], sizeof(CollisionEvent)) == 0);
    }
}

TEST_CASE("seeded random piles keep every invariant: every integrator, both steppings",
          "[dense-contact]") {
    // Every integrator twice, each stepping four times, every e in {0, 0.3,
    // 0.6, 0.9}, in a few seconds; [dense-contact-sweep] runs 48.
    for (const PileCase& pile : sweep_cases(8, 1)) {
        check_pile_settles(pile, 0.0);
    }
}
