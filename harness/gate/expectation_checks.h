// The expectations' shared parts (expectations.cpp and one file per family
// of kinds): the checks of one expectation, the readers of a trajectory they
// use, and each family's check.
#pragma once

#include "exact_answers.h"
#include "expectations.h"
#include "scene.h"
#include "text.h"
#include "trajectory.h"

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness {

// ---------------------------------------------------------------- judging one value

// The checks of one expectation, with the prefix every line of it shares.
class Checks {
  public:
    Checks(const Expectation& expectation, std::string subject, std::vector<ExpectationResult>& out)
        : expectation_(expectation), subject_(std::move(subject)), out_(out) {}

    // Passes when |actual - expected| <= atol + rtol * scale.
    void value(const std::string& what, Exact expected, double actual) {
        ExpectationResult r = start(what);
        const double allowed = expectation_.atol + expectation_.rtol * expected.scale;
        const double off = std::abs(actual - expected.value);
        r.passed = off <= allowed; // false for NaN
        r.expected = finite_or_zero(expected.value);
        r.actual = finite_or_zero(actual);
        r.allowed = allowed;
        r.numeric = std::isfinite(expected.value) && std::isfinite(actual);
        if (!std::isfinite(expected.value)) {
            r.passed = false;
            r.detail = "the exact formula gives " + sentence_number(expected.value) +
                       " for this scene, so it cannot be checked";
        } else if (!std::isfinite(actual)) {
            r.passed = false;
            r.detail = "the run gave " + sentence_number(actual) + ", which is not finite";
        } else if (!std::isfinite(off) || !std::isfinite(allowed)) {
            // An overflowed difference or tolerance (a scale of inf) would let
            // anything pass: what cannot be computed fails.
            r.passed = false;
            r.detail = "not finite: off by " + sentence_number(off) + ", allowed " +
                       sentence_number(allowed) + " (atol " + sentence_number(expectation_.atol) +
                       " + rtol " + sentence_number(expectation_.rtol) + " x " +
                       sentence_number(expected.scale) + ")";
        } else if (!r.passed) {
            r.detail =
                "off by " + sentence_number(off) + ", more than the " + sentence_number(allowed) +
                " allowed (atol " + sentence_number(expectation_.atol) + " + rtol " +
                sentence_number(expectation_.rtol) + " x " + sentence_number(expected.scale) + ")";
        }
        out_.push_back(std::move(r));
    }

    // A check judged by its caller; `detail` is kept only when it failed.
    // `allowed` is the tolerance the caller judged with. A non-finite
    // expected, actual or allowed value fails whatever the caller found:
    // inf <= inf + inf is true, and must not pass.
    void judged(const std::string& what, bool passed, double expected, double actual,
                const std::string& detail, double allowed = 0.0) {
        ExpectationResult r = start(what);
        const bool finite =
            std::isfinite(expected) && std::isfinite(actual) && std::isfinite(allowed);
        r.passed = passed && finite;
        r.expected = finite_or_zero(expected);
        r.actual = finite_or_zero(actual);
        r.allowed = allowed;
        r.numeric = std::isfinite(expected) && std::isfinite(actual);
        if (!finite) {
            r.detail = "not finite: expected " + sentence_number(expected) + ", got " +
                       sentence_number(actual) + ", allowed " + sentence_number(allowed) + "; " +
                       detail;
        } else if (!passed) {
            r.detail = detail;
        }
        out_.push_back(std::move(r));
    }

    // A check that failed without a number to compare (a missing event or
    // frame): the detail alone is shown, never "expected 0, got 0" beside it.
    void failure(const std::string& what, const std::string& detail) {
        judged(what, false, 0.0, 0.0, detail);
        out_.back().allowed.reset();
        out_.back().numeric = false;
    }
    // One that failed on a count (impacts wanted and found): both are shown.
    void failure(const std::string& what, const std::string& detail, double expected,
                 double actual) {
        judged(what, false, expected, actual, detail);
        out_.back().allowed.reset();
    }

    // Names compared as strings: no tolerance applies.
    void name(const std::string& what, const std::string& expected, const std::string& actual) {
        ExpectationResult r = start(what);
        r.passed = expected == actual;
        if (!r.passed) {
            r.detail = "expected " + single_quoted(expected) + ", got " + single_quoted(actual);
        }
        out_.push_back(std::move(r));
    }

    const Expectation& expectation() const { return expectation_; }

  private:
    static double finite_or_zero(double value) { return std::isfinite(value) ? value : 0.0; }

    ExpectationResult start(const std::string& what) const {
        ExpectationResult r;
        r.path = expectation_.path;
        r.what = subject_.empty() ? what : what.empty() ? subject_ : subject_ + ": " + what;
        return r;
    }

    const Expectation& expectation_;
    std::string subject_;
    std::vector<ExpectationResult>& out_;
};

// ---------------------------------------------------------------- reading the trajectory

// A body's column value (x, y, angle, vx, vy, omega) in a motion; NaN for any
// other name.
double field_of(const Motion& m, const std::string& field);
// An event's value by its key (t, impulse, vn_before, vn_after, point.x ...);
// NaN for any other name.
double field_of(const TrajectoryEvent& e, const std::string& field);

// The first frame recorded after event `index`, when no later event touching
// any of `bodies` happens up to it: only then does the frame show the state
// this collision left (plus the free motion since). Empty otherwise.
const std::vector<double>* frame_after_event(const Trajectory& trajectory, std::size_t index,
                                             const std::vector<std::string>& bodies);

// The scene's body of that name; null when it has none.
const SceneBody* scene_body(const Scene& scene, const std::string& name);

// Every dynamic body with its columns; empty (after a failure) when the
// trajectory lacks a body's columns. The same as exact_answers.h's masses_of,
// with the columns found through an index: a gas of 10,000 bodies has 60,001
// columns, and searching them once per body takes over a second.
std::optional<std::vector<Mass>> masses_of(const Scene& scene, const Trajectory& trajectory,
                                           Checks& checks);

// ---------------------------------------------------------------- each family of kinds

// docs/physics.md's exact answers (exact_answer_expectations.cpp).
void check_drop(const Scene& scene, const Trajectory& trajectory, Checks& checks);
void check_corner_impact(const Scene& scene, const Trajectory& trajectory, Checks& checks);
void check_head_on(const Scene& scene, const Trajectory& trajectory, Checks& checks);

// Conservation and energy (conservation_expectations.cpp).
void check_conserved(const Scene& scene, const Trajectory& trajectory, Checks& checks);
void check_energy_non_increasing(const Scene& scene, const Trajectory& trajectory, Checks& checks);

// A closed room's momentum against its walls' impulses (momentum_balance.cpp).
void check_momentum_balance(const Scene& scene, const Trajectory& trajectory, Checks& checks);

// Values written in the scene (literal_expectations.cpp).
void check_event(const Trajectory& trajectory, Checks& checks);
void check_state(const Scene& scene, const Trajectory& trajectory, Checks& checks);

// What "settled" means for a pile (rest_expectations.cpp).
void check_max_overlap(const Scene& scene, const Trajectory& trajectory, Checks& checks);
void check_at_rest(const Scene& scene, const Trajectory& trajectory, Checks& checks);

} // namespace impulse::harness
