// `impulse diff A B`: compare two trajectory files with the rules of `check`.
#include "cli.h"
#include "compare.h"
#include "diff_json.h"
#include "first_divergence.h"
#include "trajectory.h"

#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace impulse::harness::cli {

namespace {

constexpr const char* diff_help =
    R"(usage: impulse diff A B [--tolerance] [--atol SPEC] [--rtol SPEC] [--ulp SPEC] [--json]

Compares two impulse/trajectory@1 files with the rules of 'impulse check': A is
the reference (the golden), B the new trajectory. Frames are matched by index,
columns by name, collision events by order and bodies.

By default every double must be bit-identical (-0.0 and +0.0 told apart).
With --tolerance a value passes when |B - A| <= atol + rtol * |A|, or when the
two are at most ulp units in the last place apart (ULPs counted at the
channel's scale, its largest |value| in A: docs/gate-rules.md). Tolerances are
per channel: position, angle, velocity, angular_velocity, impulse, event_time
(event times and the frames' t). There are no defaults: every channel A has
values for needs a tolerance from these options; a field not given is 0.

  --tolerance     compare within tolerances instead of exactly
  --atol SPEC     absolute tolerance: one number for every channel (1e-9) or
                  channel=number pairs (position=1e-9,velocity=1e-6)
  --rtol SPEC     relative tolerance, in the same forms
  --ulp SPEC      units in the last place, whole numbers, in the same forms
  --json          print the comparison as JSON (impulse/diff@1, docs/formats.md)
                  instead of the text: the verdict, the first divergence (the
                  same one the text prints), each column's first divergent
                  value and the per-channel statistics; the exit codes are the same

Prints "identical" or "within tolerance" and exits 0; or prints the first
divergence (the earliest value over frames and events) with its cause, where
the trajectories first part per body and channel, and per channel how many
values differ and by how much, and exits 1. A different scene_sha256 is noted but is
no failure by itself. Exits 2 when a file cannot be read or is not a valid
trajectory, or for a bad option.
)";

Trajectory load_trajectory(const std::string& path) {
    return read_trajectory_file(path, "a trajectory");
}

// Without a scene, tolerances come only from the command line.
Tolerances command_line_tolerances(const Arguments& a) {
    Tolerances tolerances;
    for (const char* option : {"--atol", "--rtol", "--ulp"}) {
        if (const auto spec = a.option(option)) {
            try {
                tolerances = parse_tolerance_option(option, *spec, tolerances);
            } catch (const std::invalid_argument& e) {
                throw UsageError(e.what());
            }
        }
    }
    return tolerances;
}

void require_every_channel(const Trajectory& gold, const std::string& gold_file,
                           const Tolerances& tolerances) {
    const std::vector<Channel> missing = channels_without_tolerance(gold, tolerances);
    if (missing.empty()) {
        return;
    }
    std::string names;
    for (const Channel channel : missing) {
        names += (names.empty() ? "" : ", ") +
                 std::string(channel_names[static_cast<std::size_t>(channel)]);
    }
    throw UsageError("tolerance mode has no tolerance for " + names + ", which " + gold_file +
                     " has values for; give one with --atol, --rtol or --ulp");
}

} // namespace

int diff_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream&) {
    const Arguments a =
        parse_arguments(args, {"--atol", "--rtol", "--ulp"}, {"--help", "--tolerance", "--json"});
    if (a.has_flag("--help")) {
        out << diff_help;
        return exit_ok;
    }
    if (a.positional.size() != 2) {
        throw UsageError("needs two trajectory files A and B, got " +
                         std::to_string(a.positional.size()));
    }
    const bool tolerance_mode = a.has_flag("--tolerance");
    if (!tolerance_mode && (a.option("--atol") || a.option("--rtol") || a.option("--ulp"))) {
        throw UsageError("--atol, --rtol and --ulp apply in tolerance mode: add --tolerance");
    }
    std::optional<Tolerances> tolerances;
    if (tolerance_mode) {
        tolerances = command_line_tolerances(a); // bad specs before reading large files
    }
    const std::string& gold_file = a.positional[0];
    const std::string& value_file = a.positional[1];
    const Trajectory gold = load_trajectory(gold_file);
    const Trajectory value = load_trajectory(value_file);
    if (tolerances) {
        require_every_channel(gold, gold_file, *tolerances);
    }

    const Comparison comparison = compare(gold, value, tolerances);
    if (a.has_flag("--json")) {
        out << diff_json(
            {gold_file, value_file, tolerance_mode, gold.scene_sha256 == value.scene_sha256},
            comparison);
        return comparison.passed ? exit_ok : exit_failed;
    }
    if (gold.scene_sha256 != value.scene_sha256) {
        out << "note: " << gold_file << " and " << value_file
            << " were recorded from different scene files (scene_sha256 differs)\n";
    }
    if (comparison.identical) {
        out << "identical\n";
        return exit_ok;
    }
    if (comparison.passed) {
        // How close it came is worth seeing: the per-channel maxima.
        out << "within tolerance\n" << describe(comparison);
        return exit_ok;
    }
    out << value_file << " differs from " << gold_file << ":\n"
        << first_divergence_line(comparison) << "\n"
        << describe(comparison);
    return exit_failed;
}

} // namespace impulse::harness::cli
