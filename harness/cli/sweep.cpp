// `impulse sweep SCENE`: the speed/accuracy trade (harness/study/sweep.h) as a
// table, JSON, CSV and an SVG plot of error against cost.
#include "sweep.h"

#include "cli.h"
#include "engine_option.h"
#include "gate.h"
#include "input_error.h"
#include "markup.h"
#include "number_format.h"
#include "output_path.h"
#include "progress.h"
#include "project_options.h"
#include "reference_option.h"
#include "render.h"
#include "sweep_csv.h"
#include "sweep_plot.h"
#include "sweep_text.h"
#include "sweep_verdict.h"
#include "text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace impulse::harness::cli {

namespace {

constexpr const char* sweep_help =
    R"(usage: impulse sweep SCENE [options]

The speed/accuracy trade on one scene: runs a grid of impulse settings (time
step x integrator x time-of-impact method x toi_tolerance x ccd) and of Box2D
settings (time step x sub-steps x iterations) and measures each point's

  error  against the exact answers the scene declares (drop, corner-impact,
         head-on: the largest |actual - expected| / max(|expected|, 1e-9));
         where it declares none, against a reference run at the finest
         settings (impulse rk4, the finest dt / 4, secant, toi_tolerance 1e-14,
         ccd on when the scene or any grid point uses it): the largest
         relative difference of the final frame's state
  cost   wall time (steady clock) per simulated second, median of the repeats
         and its spread (max - min), plus deterministic work counters: steps,
         narrow-phase queries (with ccd, its sampling too), time-of-impact
         iterations

and marks each method family's Pareto front (impulse per integrator/toi
method, "+ccd" a family of its own, Box2D 2.4.1, and every other reference
engine on this machine: Box2D v3, Chipmunk2D, Rapier2D, each over the grid's
time steps and, for Box2D v3 and Rapier, --reference-substeps). A grid point the engine
refuses (a Zeno cascade, a resting contact) is reported as failed with its
reason. SCENE is a path or the name of a canonical scene under
ROOT/harness/scenes/.

After the table (and under "targets" in --json), the two targets against
Box2D, judged on this run's wall-clock costs: at the cost of Box2D at dt 1/60,
1 sub-step, 8/3 iterations or less, an impulse error at least 1e6 times smaller
(with how many times cheaper the chosen impulse point is, to show how near
noise is to flipping it); and the impulse points' Pareto front (all families
together) dominating every point of Box2D's. Then one verdict per reference:
"impulse at Box2D 2.4.1's cost: N orders of magnitude more accurate", comparing
the reference's point nearest 60 Hz (at its default settings) with the most
accurate impulse point that costs no more, and whether impulse's front
dominates the reference's.

On a pile (a scene without exact answers whose expectations include
max-overlap, at-rest or energy-non-increasing) the error is the deepest
overlap of any pair in any frame (metres), a second axis is the largest
energy gained over the run (relative to the energy's scale at t = 0), and
the cost is wall-clock seconds per body-step at the scene's dt.

  --dt LIST                 time steps in seconds (default 1/30,1/60,...,1/960)
  --integrator LIST         euler,symplectic-euler,verlet,rk4 (default all)
  --toi LIST                bisection,secant (default both)
  --toi-tolerance LIST      seconds (default 1e-6,1e-9,1e-12)
  --ccd LIST                off,on: solver.ccd, catching tunnelling (default: the
                            scene's own setting); not with "stepping": "local"
  --box2d-substeps LIST     Box2D steps per scene step (default 1,4)
  --box2d-iterations LIST   velocity/position iterations (default 8/3,30/10)
  --no-box2d                impulse points only: no reference at all, unless --with
                            names some (then every one named but Box2D 2.4.1)
  --with LIST               the references, comma-separated (box2d-2.4, box2d-3,
                            chipmunk, rapier), or none (default: every one on this
                            machine; the others are listed as skipped with the
                            command that installs them)
  --no-references           impulse points only (the same as --with none)
  --reference-substeps LIST Box2D v3's sub-steps and Rapier's solver iterations
                            (--substeps N of their programs; default 1,4)
  --engine NAME             the engine under study (default: the project's first, impulse
                            without a project file); for an engine
                            other than impulse the grid is --dt x --integrator x
                            --toi-tolerance, which reach it as a modified scene
                            (docs/engine-protocol.md); points it refuses (exit 3) are
                            skipped and listed; its cost is what it reports, or the
                            process's wall time, and the output says which
  --repeats N               timed runs per grid point (default 5)
  --json                    the sweep as JSON on standard output
  --csv                     the sweep as CSV on standard output
  --svg FILE                an SVG plot of error against cost (log axes) with the fronts;
                            - is standard output (the table then goes to standard error)
  --progress                a line per point on standard error, even when it is not a
                            terminal
  --quiet                   no progress bar (drawn on standard error only when that is a
                            terminal, after about a second of work)
  --root DIR                the project's folder (default: the first impulse.json found
                            from the current folder upwards; without one, the scenes
                            are in ./harness/scenes/)

A LIST is comma-separated, e.g. --dt 0.01,0.005. Exit 0, or 2 for bad input.
)";

int whole_number(const std::string& option, const std::string& text) {
    int value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || value < 1 || value > 1000) {
        throw UsageError(option + " takes whole numbers from 1 to 1000, got '" + text + "'");
    }
    return value;
}

// The toi method and ccd are the impulse engine's own grid dimensions: they
// do not reach another engine as overrides (docs/engine-protocol.md).
void refuse_impulse_only_options(const Arguments& a, const EngineSpec& engine) {
    if (engine.kind == EngineSpec::Kind::impulse) {
        return;
    }
    for (const char* option : {"--toi", "--ccd"}) {
        if (a.option(option)) {
            throw UsageError(std::string(option) + " varies the impulse engine's own settings; " +
                             "the grid of " + engine.name +
                             " is --dt, --integrator and --toi-tolerance");
        }
    }
}

SweepConfig config_from(const Arguments& a, const Scene& scene, const Project& project) {
    SweepConfig config = default_sweep_config(scene);
    config.engine = chosen_engine(project, a);
    refuse_impulse_only_options(a, config.engine);
    if (const auto list = a.option("--dt")) {
        config.dts.clear();
        for (const std::string& item : comma_list(*list)) {
            config.dts.push_back(positive_seconds("--dt", item));
        }
    }
    if (const auto list = a.option("--integrator")) {
        config.integrators.clear();
        for (const std::string& item : comma_list(*list)) {
            Integrator integrator{};
            if (!integrator_from_name(item, integrator)) {
                throw UsageError(
                    "--integrator takes euler, symplectic-euler, verlet or rk4, got '" + item +
                    "'");
            }
            config.integrators.push_back(integrator);
        }
    }
    if (const auto list = a.option("--toi")) {
        config.toi_methods.clear();
        for (const std::string& item : comma_list(*list)) {
            TimeOfImpactMethod method{};
            if (!toi_method_from_name(item, method)) {
                throw UsageError("--toi takes bisection or secant, got '" + item + "'");
            }
            config.toi_methods.push_back(method);
        }
    }
    if (const auto list = a.option("--toi-tolerance")) {
        config.toi_tolerances.clear();
        for (const std::string& item : comma_list(*list)) {
            config.toi_tolerances.push_back(positive_seconds("--toi-tolerance", item));
        }
    }
    if (const auto list = a.option("--ccd")) {
        config.ccd.clear();
        for (const std::string& item : comma_list(*list)) {
            if (item != "off" && item != "on") {
                throw UsageError("--ccd takes off or on, got '" + item + "'");
            }
            config.ccd.push_back(item == "on");
        }
    }
    if (const auto list = a.option("--box2d-substeps")) {
        config.box2d_substeps.clear();
        for (const std::string& item : comma_list(*list)) {
            config.box2d_substeps.push_back(whole_number("--box2d-substeps", item));
        }
    }
    if (const auto list = a.option("--box2d-iterations")) {
        config.box2d_iterations.clear();
        for (const std::string& item : comma_list(*list)) {
            const std::size_t slash = item.find('/');
            if (slash == std::string::npos) {
                throw UsageError("--box2d-iterations takes VELOCITY/POSITION, e.g. 8/3, got '" +
                                 item + "'");
            }
            config.box2d_iterations.emplace_back(
                whole_number("--box2d-iterations", item.substr(0, slash)),
                whole_number("--box2d-iterations", item.substr(slash + 1)));
        }
    }
    if (a.has_flag("--no-box2d")) {
        config.box2d = false;
    }

    if (const auto n = a.option("--repeats")) {
        config.repeats = whole_number("--repeats", *n);
    }
    return config;
}

// The Node references' --substeps grid (Box2D v3's sub-steps, Rapier's
// solver iterations): 1 and Box2D v3's default 4 unless given.
std::vector<int> reference_substeps(const Arguments& a) {
    std::vector<int> substeps{1, 4};
    if (const auto list = a.option("--reference-substeps")) {
        substeps.clear();
        for (const std::string& item : comma_list(*list)) {
            substeps.push_back(whole_number("--reference-substeps", item));
        }
    }
    return substeps;
}

// The references beside the engine under study (reference_option.h): Box2D
// 2.4.1 keeps its in-process grid (--box2d-substeps, --box2d-iterations),
// every other one gets its own front. False: a requested reference is not on
// this machine (said on err).
bool choose_references(const Arguments& a, SweepConfig& config, std::ostream& err) {
    if (a.has_flag("--no-references")) {
        if (a.option(with_option)) {
            throw UsageError("--with and --no-references contradict each other: give one");
        }
        config.box2d = false;
        return true;
    }
    // --no-box2d alone has always meant impulse's points only.
    if (a.has_flag("--no-box2d") && !a.option(with_option)) {
        config.box2d = false;
        return true;
    }
    const std::optional<ReferenceChoice> chosen =
        chosen_references(a.option(with_option), "", "sweep", err);
    if (!chosen) {
        return false;
    }
    for (const std::string& note : chosen->notes) {
        err << "sweep: " << note << "\n";
    }
    for (const ReferenceEngine& r : chosen->skipped) {
        err << "sweep: skipped " << unavailable_sentence(r) << "\n";
    }
    bool box2d = false;
    for (const ReferenceEngine& r : chosen->used) {
        if (r.spec.kind == EngineSpec::Kind::box2d) {
            box2d = true;
            continue;
        }
        SweepReference reference;
        reference.name = r.name;
        reference.title = r.title.substr(0, r.title.find(" ("));
        reference.spec = r.spec;
        if (r.spec.kind == EngineSpec::Kind::external) {
            reference.substeps = reference_substeps(a);
        }
        config.references.push_back(reference);
    }
    config.box2d = config.box2d && box2d;
    return true;
}

nlohmann::json number_or_null(double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json index_or_null(bool found, std::size_t index) {
    return found ? nlohmann::json(index) : nlohmann::json(nullptr);
}

// The targets, with indices into "points" and the table's sentences.
nlohmann::json targets_json(const SweepResult& r) {
    const SweepTargets t = evaluate_targets(r);
    if (!t.measured) {
        return {{"measured", false}, {"verdict", sweep_targets_not_measured(r, t)}};
    }
    const bool have_impulse = t.error_target_measured && t.impulse_found;
    nlohmann::json error_target = {
        {"measured", t.error_target_measured},
        {"box2d_point", index_or_null(t.box2d_60hz_found, t.box2d_60hz)},
        {"impulse_point", index_or_null(have_impulse, t.best_impulse)},
        {"impulse_error_zero", t.impulse_error_zero},
        {"error_ratio", have_impulse ? number_or_null(t.error_ratio) : nullptr},
        {"cost_margin", have_impulse ? number_or_null(t.cost_margin) : nullptr},
        {"required_ratio", target_error_ratio},
        {"met", t.error_target_met},
        {"verdict", sweep_error_target_text(r, t)}};
    nlohmann::json front_target = {
        {"box2d_front_points", t.box2d_front_size},
        {"dominated", t.box2d_front_dominated},
        {"first_undominated", index_or_null(t.undominated_found, t.first_undominated)},
        {"met", t.front_target_met},
        {"verdict", sweep_front_target_text(r, t)}};
    return {{"measured", true},
            {"costs", "wall-clock medians of this run; noisy"},
            {"error_at_box2d_60hz_cost", std::move(error_target)},
            {"pareto_front", std::move(front_target)}};
}

// Every reference's verdict, with indices into "points".
nlohmann::json verdicts_json(const SweepResult& r) {
    nlohmann::json all = nlohmann::json::array();
    for (const SweepAxis axis : sweep_verdict_axes(r)) {
        for (const ReferenceVerdict& v : reference_verdicts(r, axis)) {
            all.push_back({{"reference", v.family},
                           {"title", v.title},
                           {"axis", axis == SweepAxis::energy ? "energy"
                                    : r.pile                  ? "overlap"
                                                              : "error"},
                           {"reference_point", index_or_null(v.measured, v.reference_point)},
                           {"impulse_point", index_or_null(v.found, v.impulse_point)},
                           {"orders_of_magnitude", v.found ? number_or_null(v.orders) : nullptr},
                           {"front_points", v.front_size},
                           {"front_points_dominated", v.front_dominated},
                           {"front_dominates", v.dominates()},
                           {"headline", verdict_headline(r, v, axis)},
                           {"verdict", verdict_sentence(r, v, axis)}});
        }
    }
    return all;
}

nlohmann::json to_json(const SweepResult& r) {
    const bool other_engine = !r.cost_source.empty();
    nlohmann::json points = nlohmann::json::array();
    for (const SweepPoint& p : r.points) {
        nlohmann::json j;
        j["engine"] = p.box2d ? "box2d" : p.engine;
        j["family"] = p.family;
        j["dt"] = p.dt;
        if (!p.reference.empty()) {
            j["engine"] = p.reference;
            j["substeps"] = p.substeps > 0 ? nlohmann::json(p.substeps) : nlohmann::json(nullptr);
        } else if (p.box2d) {
            j["substeps"] = p.substeps;
            j["velocity_iterations"] = p.velocity_iterations;
            j["position_iterations"] = p.position_iterations;
        } else if (p.kind != EngineSpec::Kind::impulse) {
            j["integrator"] = integrator_name(p.integrator);
            j["toi_tolerance"] = p.toi_tolerance;
        } else {
            j["integrator"] = integrator_name(p.integrator);
            j["toi"] = toi_method_name(p.toi);
            j["toi_tolerance"] = p.toi_tolerance;
            j["ccd"] = p.ccd;
        }
        j["ok"] = p.ok;
        if (other_engine || !p.reference.empty()) {
            j["skipped"] = p.skipped;
            j["cost_source"] = p.ok ? nlohmann::json(sweep_cost_name(p.cost_source)) : nullptr;
        }
        if (!p.ok) {
            j["failure"] = p.failure;
        }
        j["error"] = p.ok ? number_or_null(p.error) : nullptr;
        if (r.pile) {
            j["energy_error"] = p.ok ? number_or_null(p.energy_error) : nullptr;
        }
        j["cost_median"] = p.ok ? number_or_null(p.cost_median) : nullptr;
        j["cost_spread"] = p.ok ? number_or_null(p.cost_spread) : nullptr;
        j["work"] = {{"steps", p.work.steps},
                     {"narrow_phase_queries", p.work.narrow_phase_queries},
                     {"toi_iterations", p.work.toi_iterations},
                     {"collisions", p.work.collisions}};
        if (!p.work_counted) {
            j["work"] = nullptr;
        }
        j["work_identical"] = p.work_identical;
        j["on_front"] = p.on_front;
        points.push_back(std::move(j));
    }
    nlohmann::json document = {{"scene", r.scene},
                               {"error_reference", r.error_reference},
                               {"against_exact", r.against_exact},
                               {"simulated_duration", r.simulated_duration},
                               {"repeats", r.repeats},
                               {"cost_unit", r.cost_unit},
                               {"pile", r.pile},
                               {"verdicts", verdicts_json(r)},
                               {"points", std::move(points)},
                               {"targets", targets_json(r)}};
    if (other_engine) {
        document["engine"] = r.engine;
        document["cost_source"] = r.cost_source;
    }
    return document;
}

} // namespace

int sweep_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    const Arguments a = parse_arguments(
        args,
        {"--dt", "--integrator", "--toi", "--toi-tolerance", "--box2d-substeps",
         "--box2d-iterations", "--ccd", "--repeats", "--svg", "--root", "--reference-substeps",
         with_option, engine_option, engine_command_option},
        {"--help", "--json", "--csv", "--no-box2d", "--no-references", "--progress", "--quiet"});
    if (a.has_flag("--help")) {
        out << sweep_help;
        return exit_ok;
    }
    if (a.positional.size() != 1) {
        throw UsageError("needs exactly one SCENE, got " + std::to_string(a.positional.size()));
    }
    const std::optional<std::string> svg = a.option("--svg");
    if (a.has_flag("--json") + a.has_flag("--csv") + (svg && is_standard_output(*svg)) > 1) {
        throw UsageError("--json, --csv and --svg - all write to standard output: give one");
    }
    const Project project = find_project(a.option("--root"));
    if (svg) {
        check_output_file("--svg", *svg, protected_folders(project));
    }
    const Scene scene = load_scene(scene_argument(project, a.positional.front()));
    for (const std::string& warning : scene.warnings) {
        err << "warning: " << warning << "\n";
    }
    SweepConfig config = config_from(a, scene, project);
    if (!choose_references(a, config, err)) {
        return exit_bad_input;
    }
    for (const std::string& warning : tunnelling_warnings(scene, config)) {
        err << "warning: " << warning << "\n";
    }
#ifndef IMPULSE_WITH_BOX2D
    if (config.box2d && !a.has_flag("--no-box2d")) {
        err << "sweep: this tool was built without Box2D; impulse points only\n";
    }
#endif
    // --progress: a line per point (for logs); on a terminal, the bar, erased
    // before anything is written.
    const SweepResult result = [&] {
        Progress bar("sweep " + scene.name,
                     !a.has_flag("--progress") && progress_wanted(a.has_flag("--quiet")));
        SweepProgress progress = [&bar](std::size_t, std::size_t total, const SweepPoint&) {
            bar.set_total(total, "points");
            bar.advance();
        };
        if (a.has_flag("--progress")) {
            progress = [&err](std::size_t done, std::size_t total, const SweepPoint& p) {
                err << "sweep: " << done << "/" << total << " " << p.family << " dt "
                    << format_double(p.dt) << (p.ok ? "" : " (failed)") << "\n";
            };
        }
        return run_sweep(scene, config, progress);
    }();
    if (svg) {
        write_output_file("--svg", *svg, sweep_svg(result), protected_folders(project), out);
    }
    if (a.has_flag("--json")) {
        out << to_json(result).dump(2) << "\n";
    } else if (a.has_flag("--csv")) {
        out << sweep_csv(result);
    } else {
        write_sweep_table(result, svg && is_standard_output(*svg) ? err : out);
    }
    return exit_ok;
}

} // namespace impulse::harness::cli
