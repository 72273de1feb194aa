#include "sweep_verdict.h"

#include "number_format.h"
#include "text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace impulse::harness {

namespace {

bool measured_on(const SweepPoint& p, SweepAxis axis) {
    return p.ok && std::isfinite(p.cost_median) && std::isfinite(axis_value(p, axis));
}

// The settings a reference is known by: Box2D 2.4.1 at 1 sub-step and 8/3
// iterations (its testbed's), a Node reference at its own or at 4 sub-steps
// (Box2D v3's default).
bool default_settings(const SweepPoint& p) {
    if (p.box2d) {
        return p.substeps == 1 && p.velocity_iterations == 8 && p.position_iterations == 3;
    }
    return p.substeps == 0 || p.substeps == 4;
}

// The family's point at the dt nearest verdict_dt (default settings first),
// then the cheapest; false when it has no measured point.
bool pick_reference_point(const std::vector<SweepPoint>& points, const std::string& family,
                          SweepAxis axis, std::size_t& chosen) {
    bool found = false;
    for (const bool want_default : {true, false}) {
        for (std::size_t i = 0; i < points.size(); ++i) {
            const SweepPoint& p = points[i];
            if (p.family != family || !measured_on(p, axis) ||
                (want_default && !default_settings(p))) {
                continue;
            }
            const double off = std::abs(p.dt - verdict_dt);
            const double best = found ? std::abs(points[chosen].dt - verdict_dt) : 0.0;
            if (!found || off < best ||
                (off == best && p.cost_median < points[chosen].cost_median)) {
                found = true;
                chosen = i;
            }
        }
        if (found) {
            return true;
        }
    }
    return false;
}

void judge_front(const std::vector<SweepPoint>& points, SweepAxis axis, ReferenceVerdict& v) {
    std::vector<std::size_t> members;
    std::vector<std::pair<double, double>> cost_error;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (points[i].family == v.family && measured_on(points[i], axis)) {
            members.push_back(i);
            cost_error.emplace_back(points[i].cost_median, axis_value(points[i], axis));
        }
    }
    for (const std::size_t k : pareto_front(cost_error)) {
        const SweepPoint& r = points[members[k]];
        ++v.front_size;
        v.front_dominated += std::any_of(points.begin(), points.end(),
                                         [&](const SweepPoint& p) {
                                             return !is_reference_point(p) &&
                                                    measured_on(p, axis) && dominates(p, r, axis);
                                         })
                                 ? 1
                                 : 0;
    }
}

std::string sci(double value) {
    if (std::isinf(value)) {
        return "inf";
    }
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1e", value);
    return buffer;
}

std::string value_text(const SweepResult& r, const SweepPoint& p, SweepAxis axis) {
    if (!r.pile) {
        return "error " + sci(p.error);
    }
    return axis == SweepAxis::error ? "deepest overlap " + sci(p.error) + " m"
                                    : "energy gained " + sci(p.energy_error);
}

std::string cost_text(const SweepResult& r, const SweepPoint& p) {
    return sci(p.cost_median) + (r.pile ? " s per body-step" : " s/s");
}

std::string title_of(const SweepResult& r, const std::string& family) {
    for (const auto& [f, title] : r.references) {
        if (f == family) {
            return title;
        }
    }
    return family;
}

} // namespace

double axis_value(const SweepPoint& point, SweepAxis axis) {
    return axis == SweepAxis::error ? point.error : point.energy_error;
}

bool dominates(const SweepPoint& a, const SweepPoint& b, SweepAxis axis) {
    const double ea = axis_value(a, axis), eb = axis_value(b, axis);
    return a.cost_median <= b.cost_median && ea <= eb && (a.cost_median < b.cost_median || ea < eb);
}

std::string sweep_dt_label(double dt) {
    const double hz = 1.0 / dt;
    if (std::abs(hz - std::round(hz)) < 1e-9 * hz) {
        return "1/" + fixed_text(std::round(hz), 0);
    }
    return format_double(dt);
}

std::string sweep_point_label(const SweepPoint& p) {
    const std::string dt = sweep_dt_label(p.dt);
    if (p.box2d) {
        return "Box2D " + dt + " sub " + std::to_string(p.substeps) + ", it " +
               std::to_string(p.velocity_iterations) + "/" + std::to_string(p.position_iterations);
    }
    if (!p.reference.empty()) {
        return p.family + " " + dt +
               (p.substeps > 0 ? " sub " + std::to_string(p.substeps) : std::string());
    }
    char tolerance[32];
    std::snprintf(tolerance, sizeof tolerance, "%.0e", p.toi_tolerance);
    return p.family + " " + dt + " tol " + tolerance;
}

std::vector<ReferenceVerdict> reference_verdicts(const SweepResult& r, SweepAxis axis) {
    std::vector<ReferenceVerdict> verdicts;
    for (const auto& [family, title] : r.references) {
        ReferenceVerdict v;
        v.family = family;
        v.title = title;
        v.measured = pick_reference_point(r.points, family, axis, v.reference_point);
        if (v.measured) {
            const SweepPoint& b = r.points[v.reference_point];
            for (std::size_t i = 0; i < r.points.size(); ++i) {
                const SweepPoint& p = r.points[i];
                if (is_reference_point(p) || !measured_on(p, axis) ||
                    p.cost_median > b.cost_median) {
                    continue;
                }
                const SweepPoint* best = v.found ? &r.points[v.impulse_point] : nullptr;
                const double e = axis_value(p, axis);
                if (best == nullptr || e < axis_value(*best, axis) ||
                    (e == axis_value(*best, axis) && p.cost_median < best->cost_median)) {
                    v.found = true;
                    v.impulse_point = i;
                }
            }
            if (v.found) {
                const double re = axis_value(b, axis);
                const double ie = axis_value(r.points[v.impulse_point], axis);
                v.floored = re == 0.0 || ie == 0.0;
                v.orders = std::log10((re == 0.0 ? sweep_error_floor : re) /
                                      (ie == 0.0 ? sweep_error_floor : ie));
            }
        }
        judge_front(r.points, axis, v);
        verdicts.push_back(std::move(v));
    }
    return verdicts;
}

std::string verdict_headline(const SweepResult& r, const ReferenceVerdict& v, SweepAxis axis) {
    const std::string head = r.engine + " at " + v.title + "'s cost: ";
    const std::string in = !r.pile                    ? ""
                           : axis == SweepAxis::error ? " in overlap"
                                                      : " in energy gained";
    if (!v.measured) {
        return head + "not measured (no " + v.title + " point ran)";
    }
    if (!v.found) {
        return head + "no " + r.engine + " point costs that little";
    }
    const double size = std::abs(v.orders);
    if (size < 0.05) {
        return head + "as accurate" + in + " (within 0.1 orders of magnitude)";
    }
    // A floored impulse error says only that it is below what is resolved.
    const bool at_least =
        v.floored && v.orders > 0.0 && axis_value(r.points[v.impulse_point], axis) == 0.0;
    return head + (at_least ? "at least " : "") + fixed_text(size, 1) + " orders of magnitude " +
           (v.orders > 0.0 ? "more" : "less") + " accurate" + in;
}

std::string verdict_sentence(const SweepResult& r, const ReferenceVerdict& v, SweepAxis axis) {
    std::string text = verdict_headline(r, v, axis);
    if (v.measured) {
        const SweepPoint& b = r.points[v.reference_point];
        text +=
            " (" + sweep_point_label(b) + ": " + value_text(r, b, axis) + " at " + cost_text(r, b);
        if (v.found) {
            const SweepPoint& p = r.points[v.impulse_point];
            text += "; " + sweep_point_label(p) + ": " + value_text(r, p, axis) + " at " +
                    cost_text(r, p);
        }
        text += ")";
    }
    if (v.front_size > 0) {
        text += "; " + r.engine + "'s front " +
                (v.dominates() ? std::string("dominates ") : std::string("does not dominate ")) +
                title_of(r, v.family) + "'s (" + std::to_string(v.front_dominated) + " of its " +
                plural(v.front_size, "front point", "front points") + " dominated)";
    }
    return text;
}

} // namespace impulse::harness
