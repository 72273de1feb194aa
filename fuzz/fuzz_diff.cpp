// Fuzz target: the trajectory diff, compare() (and describe()).
//
// The input is GOLDEN, NUL, NEW, optionally NUL and tolerance options: lines
// "--atol TEXT", "--rtol TEXT" or "--ulp TEXT", each given to
// parse_tolerance_option as `impulse check --tolerance` does. Without a NUL the
// whole input is the golden and is compared with itself only. Each trajectory
// is read as the trajectory target reads it (digest made to match).
//
// Invariants checked: a trajectory is identical to itself, and passes against
// itself within any tolerances; compare(a, b) and compare(b, a) agree on
// "identical"; in exact mode "passed" is "identical"; describe() never throws.
// Bad tolerance options (std::invalid_argument, the documented answer) and
// tolerances that leave a channel uncovered (the callers' check before
// compare) skip tolerance mode.
#include "compare.h"
#include "fuzz_support.h"

#include <cstddef>
#include <cstdint>
#include <stdexcept>

namespace {

using impulse::fuzz::finding;
using impulse::harness::Comparison;
using impulse::harness::Tolerances;
using impulse::harness::Trajectory;

// The tolerance options, or nullopt when there are none or one is refused.
std::optional<Tolerances> tolerances_from(const std::string& options) {
    if (options.empty()) {
        return std::nullopt;
    }
    Tolerances tolerances;
    std::size_t start = 0;
    while (start < options.size()) {
        std::size_t end = options.find('\n', start);
        if (end == std::string::npos) {
            end = options.size();
        }
        const std::string line = options.substr(start, end - start);
        start = end + 1;
        if (line.empty()) {
            continue;
        }
        const std::size_t space = line.find(' ');
        if (space == std::string::npos) {
            return std::nullopt;
        }
        const std::string option = line.substr(0, space);
        if (option != "--atol" && option != "--rtol" && option != "--ulp") {
            return std::nullopt;
        }
        try {
            tolerances = impulse::harness::parse_tolerance_option(option, line.substr(space + 1),
                                                                  tolerances);
        } catch (const std::invalid_argument&) {
            return std::nullopt;
        }
    }
    return tolerances;
}

// compare(), but only with tolerances that cover every channel `gold` needs,
// as `impulse check --tolerance` and `impulse diff` check first.
std::optional<Comparison> compare_if_covered(const Trajectory& gold, const Trajectory& value,
                                             const std::optional<Tolerances>& tolerances) {
    if (tolerances && !impulse::harness::channels_without_tolerance(gold, *tolerances).empty()) {
        return std::nullopt;
    }
    Comparison comparison = impulse::harness::compare(gold, value, tolerances);
    (void)impulse::harness::describe(comparison);
    if (!tolerances && comparison.passed != comparison.identical) {
        finding("compare: in exact mode 'passed' differs from 'identical'");
    }
    return comparison;
}

void check_against_itself(const Trajectory& trajectory,
                          const std::optional<Tolerances>& tolerances) {
    const std::optional<Comparison> exact =
        compare_if_covered(trajectory, trajectory, std::nullopt);
    if (!exact->identical || !exact->passed || !exact->structural.empty() ||
        !exact->first_divergences.empty()) {
        finding("compare: a trajectory is not identical to itself:\n" +
                impulse::harness::describe(*exact));
    }
    const std::optional<Comparison> within = compare_if_covered(trajectory, trajectory, tolerances);
    if (within && !within->passed) {
        finding("compare: a trajectory is not within tolerance of itself:\n" +
                impulse::harness::describe(*within));
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string input = impulse::fuzz::text_of(data, size);
    const std::size_t first_nul = input.find('\0');
    const std::string gold_text = input.substr(0, first_nul);
    std::string new_text;
    std::string options;
    if (first_nul != std::string::npos) {
        const std::size_t second_nul = input.find('\0', first_nul + 1);
        new_text = input.substr(first_nul + 1, second_nul == std::string::npos
                                                   ? std::string::npos
                                                   : second_nul - first_nul - 1);
        if (second_nul != std::string::npos) {
            options = input.substr(second_nul + 1);
        }
    }
    const std::optional<Tolerances> tolerances = tolerances_from(options);

    const std::optional<Trajectory> gold = impulse::fuzz::read_trajectory_fixing_digest(gold_text);
    if (gold) {
        check_against_itself(*gold, tolerances);
    }
    if (first_nul == std::string::npos) {
        return 0;
    }
    const std::optional<Trajectory> value = impulse::fuzz::read_trajectory_fixing_digest(new_text);
    if (!gold || !value) {
        return 0;
    }
    const std::optional<Comparison> forward = compare_if_covered(*gold, *value, std::nullopt);
    const std::optional<Comparison> backward = compare_if_covered(*value, *gold, std::nullopt);
    if (forward->identical != backward->identical) {
        finding("compare: compare(a, b) and compare(b, a) disagree on 'identical'");
    }
    // "identical" looks at the scene name, columns, frames and events, not at
    // scene_sha256, engine or solver: with those copied over, it is equality.
    Trajectory same_header = *value;
    same_header.scene_sha256 = gold->scene_sha256;
    same_header.engine = gold->engine;
    same_header.solver = gold->solver;
    if (forward->identical != impulse::fuzz::same_trajectory(*gold, same_header)) {
        finding(forward->identical ? "compare: 'identical' for trajectories whose values differ"
                                   : "compare: not 'identical' for equal trajectories");
    }
    (void)compare_if_covered(*gold, *value, tolerances);
    return 0;
}
