// The sweep's Pareto fronts and its two targets against Box2D (sweep.h):
// pure functions of measured points, apart from running the grid.
#include "sweep.h"
#include "sweep_verdict.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace impulse::harness {

std::vector<std::size_t> pareto_front(const std::vector<std::pair<double, double>>& cost_error) {
    std::vector<std::size_t> order(cost_error.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        order[i] = i;
    }
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return cost_error[a] != cost_error[b] ? cost_error[a] < cost_error[b] : a < b;
    });
    std::vector<std::size_t> front;
    for (const std::size_t i : order) {
        const auto [cost, error] = cost_error[i];
        if (std::isnan(cost) || std::isnan(error)) {
            continue;
        }
        bool dominated = false;
        for (std::size_t j = 0; j < cost_error.size() && !dominated; ++j) {
            const auto [c, e] = cost_error[j];
            dominated = c <= cost && e <= error && (c < cost || e < error);
        }
        if (!dominated) {
            front.push_back(i);
        }
    }
    return front;
}

void mark_fronts(std::vector<SweepPoint>& points) {
    std::map<std::string, std::vector<std::size_t>> families;
    for (std::size_t i = 0; i < points.size(); ++i) {
        points[i].on_front = false;
        if (points[i].ok && !std::isnan(points[i].error)) {
            families[points[i].family].push_back(i);
        }
    }
    for (const auto& [family, members] : families) {
        std::vector<std::pair<double, double>> cost_error;
        for (const std::size_t i : members) {
            cost_error.emplace_back(points[i].cost_median, points[i].error);
        }
        for (const std::size_t k : pareto_front(cost_error)) {
            points[members[k]].on_front = true;
        }
    }
}

namespace {

// A point a front can use: it ran and its error means something.
bool measured_point(const SweepPoint& p) {
    return p.ok && !std::isnan(p.error) && !std::isnan(p.cost_median);
}

bool is_box2d_60hz(const SweepPoint& p) {
    return p.box2d && p.substeps == target_box2d_substeps &&
           p.velocity_iterations == target_box2d_velocity_iterations &&
           p.position_iterations == target_box2d_position_iterations &&
           std::abs(p.dt - target_box2d_dt) <= 1e-12 * target_box2d_dt;
}

} // namespace

SweepTargets evaluate_targets(const SweepResult& result) {
    SweepTargets t;
    const std::vector<SweepPoint>& points = result.points;
    for (const SweepPoint& p : points) {
        t.measured = t.measured || (p.box2d && measured_point(p));
    }
    if (!t.measured) {
        return t;
    }

    // Target 1. A --dt list typed in decimal lands within rounding of 1/60,
    // not on it: the closest such dt is the 60 Hz point.
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (is_box2d_60hz(points[i]) &&
            (!t.box2d_60hz_found || std::abs(points[i].dt - target_box2d_dt) <
                                        std::abs(points[t.box2d_60hz].dt - target_box2d_dt))) {
            t.box2d_60hz_found = true;
            t.box2d_60hz = i;
        }
    }
    t.error_target_measured = t.box2d_60hz_found && measured_point(points[t.box2d_60hz]);
    if (t.error_target_measured) {
        const SweepPoint& b = points[t.box2d_60hz];
        for (std::size_t i = 0; i < points.size(); ++i) {
            const SweepPoint& p = points[i];
            if (is_reference_point(p) || !measured_point(p) || p.cost_median > b.cost_median) {
                continue;
            }
            const SweepPoint* best = t.impulse_found ? &points[t.best_impulse] : nullptr;
            if (best == nullptr || p.error < best->error ||
                (p.error == best->error && p.cost_median < best->cost_median)) {
                t.impulse_found = true;
                t.best_impulse = i;
            }
        }
        if (t.impulse_found) {
            const SweepPoint& p = points[t.best_impulse];
            // An error of exactly 0 says only that it is below what the
            // measurement resolves: the floor gives a ratio it is at least.
            t.impulse_error_zero = p.error == 0.0;
            t.error_ratio = b.error / (t.impulse_error_zero ? sweep_error_floor : p.error);
            t.cost_margin = b.cost_median / p.cost_median;
            t.error_target_met = t.error_ratio >= target_error_ratio;
        }
    }

    // Target 2. An impulse point that dominates a Box2D point is dominated by
    // or equal to one on the impulse front, so checking every impulse point
    // checks the front.
    std::vector<std::size_t> box2d;
    std::vector<std::pair<double, double>> cost_error;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (points[i].box2d && measured_point(points[i])) {
            box2d.push_back(i);
            cost_error.emplace_back(points[i].cost_median, points[i].error);
        }
    }
    for (const std::size_t k : pareto_front(cost_error)) {
        const SweepPoint& b = points[box2d[k]];
        ++t.box2d_front_size;
        const bool dominated = std::any_of(points.begin(), points.end(), [&](const SweepPoint& p) {
            return !is_reference_point(p) && measured_point(p) && dominates(p, b, SweepAxis::error);
        });
        if (dominated) {
            ++t.box2d_front_dominated;
        } else if (!t.undominated_found) {
            t.undominated_found = true;
            t.first_undominated = box2d[k];
        }
    }
    t.front_target_met = t.box2d_front_size > 0 && !t.undominated_found;
    return t;
}

} // namespace impulse::harness
