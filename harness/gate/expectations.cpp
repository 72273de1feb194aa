// Checking a run against the answers its scene declares (docs/design.md: "A scene
// may declare expectations that every run checks"): each expectation's kind
// sent to its family's check (expectation_checks.h).
//
// Everything here reads the trajectory only (its NAME.x ... NAME.omega columns
// and its events), never the engine, so the same checks hold any simulator to
// the same physics.
#include "expectations.h"

#include "expectation_checks.h"
#include "text.h"

#include <string>
#include <vector>

namespace impulse::harness {

namespace {

// The first words of every line an expectation reports.
std::string subject_of(const Expectation& x) {
    switch (x.kind) {
    case Expectation::Kind::drop:
        return "drop of " + single_quoted(x.body);
    case Expectation::Kind::corner_impact:
        return "corner impact of " + single_quoted(x.body);
    case Expectation::Kind::head_on:
        return "head-on of " + single_quoted(x.body) + " and " + single_quoted(x.other);
    case Expectation::Kind::conserved:
    case Expectation::Kind::energy_non_increasing:
    case Expectation::Kind::momentum_balance:
    case Expectation::Kind::max_overlap:
    case Expectation::Kind::at_rest:
        return "";
    case Expectation::Kind::event:
        return "event " + std::to_string(x.index);
    case Expectation::Kind::state:
        return "state of " + single_quoted(x.body) + " at t = " + sentence_number(x.t) + " s";
    }
    return "";
}

} // namespace

std::vector<ExpectationResult> evaluate_expectations(const Scene& scene,
                                                     const Trajectory& trajectory) {
    std::vector<ExpectationResult> results;
    for (const Expectation& x : scene.expectations) {
        Checks checks(x, subject_of(x), results);
        switch (x.kind) {
        case Expectation::Kind::drop:
            check_drop(scene, trajectory, checks);
            break;
        case Expectation::Kind::corner_impact:
            check_corner_impact(scene, trajectory, checks);
            break;
        case Expectation::Kind::head_on:
            check_head_on(scene, trajectory, checks);
            break;
        case Expectation::Kind::conserved:
            check_conserved(scene, trajectory, checks);
            break;
        case Expectation::Kind::energy_non_increasing:
            check_energy_non_increasing(scene, trajectory, checks);
            break;
        case Expectation::Kind::momentum_balance:
            check_momentum_balance(scene, trajectory, checks);
            break;
        case Expectation::Kind::event:
            check_event(trajectory, checks);
            break;
        case Expectation::Kind::state:
            check_state(scene, trajectory, checks);
            break;
        case Expectation::Kind::max_overlap:
            check_max_overlap(scene, trajectory, checks);
            break;
        case Expectation::Kind::at_rest:
            check_at_rest(scene, trajectory, checks);
            break;
        }
    }
    return results;
}

} // namespace impulse::harness
