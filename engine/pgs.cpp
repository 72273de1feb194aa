#include "pgs.h"

#include "index.h"

#include <algorithm>
#include <cstddef>

namespace impulse {

namespace {

// w_i = J_i dv + q_i.
double velocity_of(const PgsRow& r, double q, const PgsScratch& s) {
    const std::size_t a = at(r.slot_a);
    const std::size_t b = at(r.slot_b);
    const double ja = r.nx * s.dv_x[a] + r.ny * s.dv_y[a] + r.rn_a * s.dw[a];
    const double jb = r.nx * s.dv_x[b] + r.ny * s.dv_y[b] + r.rn_b * s.dw[b];
    return (ja - jb) + q;
}

void apply(const PgsRow& r, double delta, PgsScratch& s) {
    const std::size_t a = at(r.slot_a);
    const std::size_t b = at(r.slot_b);
    s.dv_x[a] += delta * r.ka_x;
    s.dv_y[a] += delta * r.ka_y;
    s.dw[a] += delta * r.ra;
    s.dv_x[b] += delta * r.kb_x;
    s.dv_y[b] += delta * r.kb_y;
    s.dw[b] += delta * r.rb;
}

// The residual of one point: how far (w_i, lambda_i) is from the LCP's
// conditions, as a velocity: -w_i where w_i < 0 (still approaching), else
// min(A_ii lambda_i, w_i) (pushing while separating).
double residual_of(double w, double lambda, double diagonal) {
    return std::max(-w, std::min(diagonal * lambda, w));
}

// Sets up rows, diagonals and dv = M^-1 J^T lambda for the warm start.
void prepare(const World& world, const std::vector<ContactPoint>& points,
             std::vector<double>& lambda, PgsScratch& s) {
    if (s.local_of_body.size() < world.bodies.size()) {
        s.local_of_body.resize(world.bodies.size(), -1);
    }
    s.bodies.clear();
    s.rows.resize(points.size());
    s.diagonal.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        s.rows[i] = row_of(world, points[i], s.local_of_body, s.bodies);
        s.diagonal[i] = delassus(world, points[i], points[i]); // A_ii, as solve_lcp sees it
    }
    const std::size_t slots = s.bodies.size() + 1;
    s.dv_x.assign(slots, 0.0);
    s.dv_y.assign(slots, 0.0);
    s.dw.assign(slots, 0.0);
    if (lambda.size() != points.size()) {
        lambda.assign(points.size(), 0.0);
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
        lambda[i] = std::max(0.0, lambda[i]); // a warm start is a solution's guess: never < 0
        if (lambda[i] != 0.0) {
            apply(s.rows[i], lambda[i], s);
        }
    }
}

// One projected Gauss-Seidel update of point i.
void relax(std::size_t i, const std::vector<double>& q, std::vector<double>& lambda,
           PgsScratch& s) {
    const double d = s.diagonal[i];
    if (d <= 0.0) { // a point between two static bodies moves nothing
        return;
    }
    const PgsRow& r = s.rows[i];
    const double w = velocity_of(r, q[i], s);
    const double updated = std::max(0.0, lambda[i] - w / d);
    const double delta = updated - lambda[i];
    lambda[i] = updated;
    if (delta != 0.0) {
        apply(r, delta, s);
    }
}

void sweep(bool forward, const std::vector<double>& q, std::vector<double>& lambda, PgsScratch& s) {
    const std::size_t n = lambda.size();
    for (std::size_t k = 0; k < n; ++k) {
        relax(forward ? k : n - 1 - k, q, lambda, s);
    }
}

// The residual of lambda as it stands: one pass computing every w_i.
double exact_residual(const std::vector<double>& q, const std::vector<double>& lambda,
                      const PgsScratch& s) {
    double worst = 0.0;
    for (std::size_t i = 0; i < lambda.size(); ++i) {
        const double w = velocity_of(s.rows[i], q[i], s);
        worst = std::max(worst, residual_of(w, lambda[i], s.diagonal[i]));
    }
    return worst;
}

} // namespace

PgsResult solve_pgs(const World& world, const std::vector<ContactPoint>& points,
                    const std::vector<double>& q, std::vector<double>& lambda,
                    const PgsSettings& settings, PgsScratch& scratch) {
    prepare(world, points, lambda, scratch);
    PgsResult result;
    // The residual is measured in an extra pass after every sweep, on the
    // final lambda (about half a sweep's work): a residual taken during the
    // sweep sees each point before its own update and misses what later
    // updates do to it, so it would neither bound the answer nor stop a warm
    // start or a single point after its one sweep.
    // A warm start is swept once even when it already meets the tolerance.
    result.residual = settings.max_sweeps > 0 ? 0.0 : exact_residual(q, lambda, scratch);
    while (result.sweeps < settings.max_sweeps) {
        sweep(result.sweeps % 2 == 0, q, lambda, scratch);
        ++result.sweeps;
        result.residual = exact_residual(q, lambda, scratch);
        if (result.residual <= settings.tolerance) {
            break;
        }
    }
    result.converged = result.residual <= settings.tolerance;
    for (const int body : scratch.bodies) {
        scratch.local_of_body[at(body)] = -1; // reset only what this call touched
    }
    scratch.bodies.clear();
    return result;
}

} // namespace impulse
