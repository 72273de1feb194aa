// Extremes (numerical stability). A matrix of scenes built here, each at an
// edge of what the engine is asked to do (mass ratios to 1e6, speeds from 0.01
// to 1000 m/s, sizes from 0.05 to 50 m, positions 1e4 m from the origin, dt
// from 1e-4 to 1/30 s, e of 0 and 1, 1e4 simulated seconds, near-parallel
// edges, corner on corner), run with every invariant that applies checked at
// every frame and its worst value kept. `impulse stress` prints the table
// (harness/cli/stress.cpp); CTest runs it (stress.matrix).
//
// Every case is first put to the up-front tunnelling refusal (tunnelling.h),
// and a case that would tunnel must be refused there.
#pragma once

#include "body.h"
#include "exact_answers.h"
#include "scene.h"
#include "trajectory.h"
#include "tunnelling.h"

#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

// ---------------------------------------------------------------- invariants

// How a row's worst value is judged.
enum class Bound {
    at_most, // worst <= bound
    above,   // worst > bound (a margin that must stay positive)
    finite,  // worst (the largest magnitude seen) is finite
};

struct StressRow {
    std::string invariant; // "energy drift (relative)"
    double worst = 0.0;
    double bound = 0.0;
    Bound kind = Bound::at_most;
    bool passed = false;
    std::string detail; // where the worst value happened, or why it failed
};

// Body a's centre stays on the side of body b's centre that axis points to:
// dot(x_a - x_b, axis) > 0 at every frame. A body that passes through another
// (tunnels) ends on the wrong side.
struct SideRule {
    int a = 0;
    int b = 0;
    Vec2 axis;
};

// docs/physics.md's drop of `body`, released at rest above static ground: its
// collisions, exactly `impacts` of them, against the ladder (impact times and
// rebound speeds).
struct DropCheck {
    int body = 0;
    int impacts = 0;
};

// docs/physics.md's 1D head-on collision of bodies a and b along x.
struct HeadOnCheck {
    int a = 0;
    int b = 0;
};

// No dynamic body's centre moves further than `bound` along `axis` from where
// it started (a resting column that holds neither slides nor sinks).
struct DriftCheck {
    Vec2 axis;
    double bound = 0.0;
};

// A pile at rest (formats.md, "at-rest"): from `after` on, the kinetic energy
// stays below `rtol` of the energy the fall released (the kinetic energy at
// t = 0 plus the potential energy lost since).
struct AtRestCheck {
    double after = 0.0;
    double rtol = 0.0;
};

// A column of bodies resting on static ground, listed bottom to top: each
// step, the impulse through the contact under body k (from the momentum the
// bodies from k up gained, less gravity's kick) equals the weight above it
// times the step, |g| h sum_{j >= k} m_j, within `rtol` of it.
struct SupportCheck {
    std::vector<int> column;
    double rtol = 0.0;
};

// Which invariants a case checks. Every case checks that every value stays
// finite and that no pair interpenetrates beyond solver.contact_tolerance (or
// overlap_bound when given).
struct StressChecks {
    std::vector<SideRule> sides;
    bool momentum = false;         // free collisions: no static body, no gravity
    bool angular_momentum = false; // the same, about the origin
    bool energy_gain = true;       // e <= 1: energy never gained
    bool energy_drift = false;     // e = 1: energy conserved
    std::optional<DropCheck> drop;
    std::optional<HeadOnCheck> head_on;
    // How far from the origin the scene sits: rounding of positions there is
    // half an ULP of this per step, and the bounds of quantities made from
    // positions grow by it (0: no such term).
    double offset = 0.0;
    std::optional<double> overlap_bound; // m; issue 14's 1e-6 for the piles
    // The least scale energy changes are relative to (J). A resting pile's
    // totals, measured from where it started, are all but 0, so its rounding
    // would be judged against nothing; a pile row gives the potential energy
    // its bodies hold above the ground, the terms the engine's energy is made of.
    double energy_scale_floor = 0.0;
    std::vector<DriftCheck> drifts;
    std::optional<AtRestCheck> at_rest;
    std::vector<SupportCheck> supports;
};

// The bounds, and why (stress_monitor.cpp and stress_exact_answers.cpp derive each):
// relative slack for energy never gained and momentum conserved;
inline constexpr double stress_relative_slack = 1e-12;
// energy change per collision at e = 1, in units of DBL_EPSILON of the kinetic
// energy: the largest seen over 6 x 10^6 random collisions of rotating and
// non-rotating bodies is 14 (10 in test_stress.cpp's 3 x 10^5), doubled.
inline constexpr double energy_ulps_per_collision = 32.0;

// Watches a run frame by frame and keeps the worst value of each invariant.
// Works on any sequence of states, so each checker can be fed a made-up
// violation.
class StressMonitor {
  public:
    StressMonitor(const Scene& scene, StressChecks checks);

    // Every frame, t = 0 first: the state of every body in scene order.
    void observe(double t, const std::vector<BodyState>& states);
    // Every collision, in order.
    void observe(const TrajectoryEvent& event);

    std::vector<StressRow> rows() const;

  private:
    // Momentum, angular momentum and energy with the scales of their terms
    // (exact_answers.h), here from the engine's states.
    Totals totals_of(const std::vector<BodyState>& states) const;

    // The steps of observe, one invariant each; false: a value is not finite.
    bool observe_finite(double t, const std::vector<BodyState>& states);
    void observe_penetration(double t, const std::vector<BodyState>& states);
    void observe_sides(double t, const std::vector<BodyState>& states);
    void observe_totals(double t, const std::vector<BodyState>& states);
    // The pile rows (DriftCheck, AtRestCheck, SupportCheck); observe_supports
    // compares these states with the last frame's.
    void observe_drifts(double t, const std::vector<BodyState>& states);
    void observe_rest(double t, const std::vector<BodyState>& states);
    void observe_supports(double t, const std::vector<BodyState>& states);

    // The steps of rows: finite, interpenetration and sides; then what
    // rounding far from the origin can move a position by over the run; then
    // momentum and energy, with that budget.
    std::vector<StressRow> geometry_rows() const;
    double position_budget() const;
    void add_conservation_rows(std::vector<StressRow>& rows, double position_budget) const;
    void add_pile_rows(std::vector<StressRow>& rows) const;

    const Scene* scene_;
    StressChecks checks_;
    long long frames_ = 0;
    std::vector<Vec2> start_positions_; // potential energy is measured from here
    std::vector<TrajectoryEvent> events_;
    std::vector<BodyState> last_;
    double last_t_ = 0.0;

    // finite
    double largest_ = 0.0;
    std::string non_finite_; // the first non-finite value, named
    // penetration
    double deepest_ = 0.0;
    std::string deepest_at_;
    // sides
    std::vector<double> margins_;
    std::vector<std::string> margins_at_;
    // penetration's scratch: this frame's poses for the overlap grid
    std::vector<Transform> poses_;
    // pile rows: the worst of each check, and where
    std::vector<double> drift_worst_;
    std::vector<std::string> drift_at_;
    double start_kinetic_ = 0.0;
    double rest_worst_ = 0.0;
    std::string rest_at_;
    std::vector<double> support_worst_;
    std::vector<std::string> support_at_;
    // conservation
    Totals start_;
    double momentum_drift_ = 0.0, angular_momentum_drift_ = 0.0;
    double energy_gain_ = 0.0, energy_drift_ = 0.0;
    double momentum_scale_ = 0.0, angular_momentum_scale_ = 0.0, energy_scale_ = 0.0;
    std::string energy_gain_at_, energy_drift_at_;
};

// ---------------------------------------------------------------- the matrix

struct StressCase {
    std::string name;
    std::string description;
    Scene scene;
    StressChecks checks;
    // The engine or the harness must refuse this one up front; the refusal
    // must contain this text.
    std::string expected_refusal;
    // Seconds or more of wall time (a pile of 1000): `impulse stress` and the
    // stress label run it, the unit tests' pass over the matrix leaves it out.
    bool slow = false;
};

struct StressResult {
    std::string name;
    std::string description;
    bool expected_refusal = false;
    std::string refusal; // the refusal, when the case was refused up front
    bool refused_as_expected = false;
    std::string stopped; // the run stopped on an error after it started
    std::vector<StressRow> rows;
    double seconds = 0.0; // wall time of the case (reported, never judged)
    long long steps = 0;
    long long collisions = 0;

    // Every row passed, or the case was refused as expected.
    bool passed() const;
};

// Every case, in table order.
std::vector<StressCase> stress_cases();

// Refuses the case up front when it could tunnel (tunnelling_refusal), else
// runs it through the impulse simulator (the NaN guard and the engine's own
// refusals included) and checks its invariants.
StressResult run_stress_case(const StressCase& stress_case);

} // namespace impulse::harness
