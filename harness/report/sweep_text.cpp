// The sweep as text (impulse sweep's table): every point, the counts, each
// reference's verdict and the two targets against Box2D 2.4.1, in sentences the
// JSON output repeats. Kept apart from the verb as its CSV and plot are.
#include "sweep_text.h"

#include "number_format.h"
#include "sweep_verdict.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace impulse::harness {

namespace {

std::string sci(double value, int digits = 2) {
    if (std::isinf(value)) {
        return "inf";
    }
    if (std::isnan(value)) {
        return "-";
    }
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*e", digits, value);
    return buffer;
}

std::string settings_of(const SweepPoint& p) {
    if (!p.reference.empty()) {
        return p.substeps > 0 ? "sub " + std::to_string(p.substeps) : "its own";
    }
    if (p.box2d) {
        return "sub " + std::to_string(p.substeps) + ", it " +
               std::to_string(p.velocity_iterations) + "/" + std::to_string(p.position_iterations);
    }
    return "tol " + sci(p.toi_tolerance, 0);
}

std::string dt_text(double dt) {
    const double hz = 1.0 / dt;
    if (std::abs(hz - std::round(hz)) < 1e-9 * hz) {
        return "1/" + fixed_text(std::round(hz), 0);
    }
    return format_double(dt);
}

// "Box2D 1/60 sub 1, it 8/3", "verlet/secant 1/30 tol 1e-12",
// "verlet/secant+ccd 1/30 tol 1e-12", "my-engine verlet 1/30 tol 1e-12".
std::string point_name(const SweepPoint& p) {
    const bool own = p.kind == EngineSpec::Kind::impulse;
    const std::string method = p.box2d                ? std::string("Box2D")
                               : !p.reference.empty() ? p.family
                               : !own                 ? p.family
                                      : std::string(integrator_name(p.integrator)) + "/" +
                                            toi_method_name(p.toi) + (p.ccd ? "+ccd" : "");
    return method + " " + dt_text(p.dt) + " " + settings_of(p);
}

// The cost's unit: a pile's is per body-step (SweepResult::cost_unit).
const char* cost_unit_of(const SweepResult& r) {
    return r.pile ? " s/body-step" : " s/s";
}

std::string error_and_cost(const SweepResult& r, const SweepPoint& p) {
    return "error " + sci(p.error) + " at " + sci(p.cost_median) + cost_unit_of(r);
}

// Few digits where noise could matter (near 1x), none where it cannot.
std::string times(double ratio) {
    if (!std::isfinite(ratio) || ratio >= 1e4) {
        return sci(ratio, 1) + "x";
    }
    return fixed_text(ratio, ratio < 10.0 ? 1 : 0) + "x";
}

} // namespace

// Why no target was measured, or empty when they were.

std::string sweep_targets_not_measured(const SweepResult& r, const SweepTargets& t) {
    if (t.measured) {
        return "";
    }
    const bool any_box2d =
        std::any_of(r.points.begin(), r.points.end(), [](const SweepPoint& p) { return p.box2d; });
    return any_box2d ? "not measured (every Box2D point failed)" : "not measured (no Box2D points)";
}

// Target 1 in one sentence.
std::string sweep_error_target_text(const SweepResult& r, const SweepTargets& t) {
    std::string text = "error at Box2D's 60 Hz cost: ";
    if (!t.box2d_60hz_found) {
        return text + "not measured (the grid has no Box2D point at dt 1/60, " +
               std::to_string(target_box2d_substeps) + " sub-step, " +
               std::to_string(target_box2d_velocity_iterations) + "/" +
               std::to_string(target_box2d_position_iterations) + " iterations)";
    }
    const SweepPoint& b = r.points[t.box2d_60hz];
    if (!t.error_target_measured) {
        return text + "not measured (" + point_name(b) + " failed: " + b.failure + ")";
    }
    text += point_name(b) + ": " + error_and_cost(r, b) + "; ";
    const std::string target = " (target >= " + sci(target_error_ratio, 0) + ")";
    if (!t.impulse_found) {
        return text + "no " + r.engine + " point costs that little: not met" + target;
    }
    const SweepPoint& p = r.points[t.best_impulse];
    text += "best " + r.engine + " at <= that cost: " + point_name(p) + ", ";
    if (t.impulse_error_zero) {
        text += "error 0 (below the floor " + sci(sweep_error_floor, 0) + ", taken as it) at " +
                sci(p.cost_median) + cost_unit_of(r);
    } else {
        text += error_and_cost(r, p);
    }
    text += " (" + times(t.cost_margin) +
            " cheaper): " + (t.impulse_error_zero ? "at least " : "") + sci(t.error_ratio, 1) +
            " times smaller: " + (t.error_target_met ? "met" : "not met") + target;
    return text;
}

// Target 2 in one sentence.
std::string sweep_front_target_text(const SweepResult& r, const SweepTargets& t) {
    std::string text = "Pareto front: " + r.engine + "'s front dominates ";
    if (t.front_target_met) {
        return text +
               (t.box2d_front_size == 1
                    ? std::string("Box2D's only front point")
                    : "all " + std::to_string(t.box2d_front_size) + " of Box2D's front points") +
               ": met";
    }
    const SweepPoint& b = r.points[t.first_undominated];
    return text + std::to_string(t.box2d_front_dominated) + " of Box2D's " +
           std::to_string(t.box2d_front_size) + " front point" +
           (t.box2d_front_size == 1 ? "" : "s") + "; not " + point_name(b) + " (" +
           error_and_cost(r, b) + "): not met";
}

// The axes a verdict is given on: a pile's two, otherwise the error.
std::vector<SweepAxis> sweep_verdict_axes(const SweepResult& r) {
    return r.pile ? std::vector<SweepAxis>{SweepAxis::error, SweepAxis::energy}
                  : std::vector<SweepAxis>{SweepAxis::error};
}

namespace {

// One sentence per reference (and per axis on a pile).

void write_verdicts(const SweepResult& r, std::ostream& out) {
    if (r.references.empty()) {
        return;
    }
    out << "verdicts (each reference's point nearest 60 Hz against the most accurate " << r.engine
        << " point that costs no more):\n";
    for (const SweepAxis axis : sweep_verdict_axes(r)) {
        for (const ReferenceVerdict& v : reference_verdicts(r, axis)) {
            out << "  " << verdict_sentence(r, v, axis) << "\n";
        }
    }
}

void write_targets(const SweepResult& r, std::ostream& out) {
    write_verdicts(r, out);
    const SweepTargets t = evaluate_targets(r);
    if (!t.measured) {
        out << "targets: " << sweep_targets_not_measured(r, t) << "\n";
        return;
    }
    out << "targets (wall-clock costs of this run; noisy):\n";
    out << "  " << sweep_error_target_text(r, t) << "\n";
    out << "  " << sweep_front_target_text(r, t) << "\n";
}

// How many points were measured, failed and skipped; each reason for a skip
// once, with how many points it skipped.
void write_counts(const SweepResult& r, std::ostream& out) {
    std::size_t failed = 0;
    std::vector<std::pair<std::string, std::size_t>> skips; // in the order first met
    for (const SweepPoint& p : r.points) {
        failed += p.ok || p.skipped ? 0 : 1;
        if (p.skipped) {
            const auto same = std::find_if(skips.begin(), skips.end(),
                                           [&](const auto& s) { return s.first == p.failure; });
            if (same == skips.end()) {
                skips.emplace_back(p.failure, 1);
            } else {
                ++same->second;
            }
        }
    }
    std::size_t skipped = 0;
    for (const auto& [reason, n] : skips) {
        skipped += n;
    }
    out << "\n"
        << plural(r.points.size() - failed - skipped, "point", "points") << " measured, " << failed
        << " failed" << (skipped > 0 ? ", " + std::to_string(skipped) + " skipped" : "") << "\n";
    for (const auto& [reason, n] : skips) {
        out << "skipped " << plural(n, "point", "points") << ": " << reason << "\n";
    }
    out << "\n";
}

} // namespace

void write_sweep_table(const SweepResult& r, std::ostream& out) {
    out << "sweep: " << r.scene << ", " << r.points.size() << " grid points, " << r.repeats
        << " repeats each, " << format_double(r.simulated_duration) << " s simulated\n";
    out << "error " << r.error_reference << "\n";
    if (r.pile) {
        out << r.energy_reference << "\n";
        out << "cost: " << r.cost_unit
            << " of wall time (median +- spread); * on its family's Pareto front in "
               "(cost, deepest overlap)\n\n";
    } else if (r.cost_source.empty()) {
        out << "cost: seconds of wall time per simulated second (median +- spread); * on its "
               "family's Pareto front\n\n";
    } else {
        // Box2D's points are timed in process whatever the engine's cost is.
        const bool any_box2d = std::any_of(r.points.begin(), r.points.end(),
                                           [](const SweepPoint& p) { return p.box2d; });
        out << r.cost_source << ", in seconds per simulated second (median +- spread)"
            << (any_box2d ? "; Box2D's points: wall time in process" : "")
            << "; * on its family's Pareto front\n\n";
    }
    // As wide as the longest family ("+ccd" can take one past the usual 36).
    std::size_t method_width = 36;
    for (const SweepPoint& p : r.points) {
        method_width = std::max(method_width, p.family.size() + 2);
    }
    out << padded("method", method_width) << padded("dt", 7) << padded("settings", 17)
        << padded(r.pile ? "overlap" : "error", 10, true)
        << (r.pile ? padded("energy", 10, true) : std::string()) << padded("cost", 11, true)
        << padded("+-", 10, true) << padded("steps", 9, true) << padded("narrow", 10, true)
        << padded("toi_it", 9, true) << "\n";
    for (const SweepPoint& p : r.points) {
        out << padded(p.family, method_width) << padded(dt_text(p.dt), 7)
            << padded(settings_of(p), 17);
        if (!p.ok) {
            out << (p.skipped ? std::string("  skipped") : "  FAILED: " + p.failure) << "\n";
            continue;
        }
        out << padded(sci(p.error), 10, true)
            << (r.pile ? padded(sci(p.energy_error), 10, true) : std::string())
            << padded(sci(p.cost_median), 11, true) << padded(sci(p.cost_spread, 1), 10, true)
            << padded(p.work_counted ? std::to_string(p.work.steps) : "-", 9, true);
        if (p.box2d || p.kind != EngineSpec::Kind::impulse) {
            out << padded("-", 10, true) << padded("-", 9, true);
        } else {
            out << padded(std::to_string(p.work.narrow_phase_queries), 10, true)
                << padded(std::to_string(p.work.toi_iterations), 9, true);
        }
        out << (p.on_front ? " *" : "") << (p.work_identical ? "" : " (work varied!)") << "\n";
    }
    write_counts(r, out);
    write_targets(r, out);
}

} // namespace impulse::harness
