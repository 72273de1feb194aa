#include "mprgp.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace impulse {

namespace {

constexpr double infinite = std::numeric_limits<double>::infinity();

// Dostal's proportioning constant: a proportioning step is taken when the
// active set's chopped gradient outweighs the free set's reduced one; 1 is the
// value his convergence bounds are usually quoted for. Measured to d/h cold
// with the diagonal scaling (tests/test_mprgp.cpp, "[mprgp-measure]"): 1
// takes a column of 50 boxes in 220 products and a 1000-disc packing in 1653;
// 0.5 takes 183 and 3277; 2 takes 285 and 1044. Over the 8 s of
// pile-boxes-100, 0.5 and 1 differ by less than the run-to-run change of the
// trajectory itself; 2 and 4 take 15-60% more.
constexpr double proportion = 1.0;

std::size_t at(int i) {
    return static_cast<std::size_t>(i);
}

// The iteration from here on runs on the scaled problem (mprgp.h): its
// "lambda" is mu, its A is A^, its gradient A^ mu + q^ = D^-1/2 w.

// y = A^ x = J (M^-1 J^T x) on the scaled rows: x scattered into the bodies' dv, then each
// point's relative normal velocity read back. O(points), A never formed.
void multiply(const std::vector<double>& x, std::vector<double>& y, MprgpScratch& s) {
    std::fill(s.dv_x.begin(), s.dv_x.end(), 0.0);
    std::fill(s.dv_y.begin(), s.dv_y.end(), 0.0);
    std::fill(s.dw.begin(), s.dw.end(), 0.0);
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (x[i] == 0.0) {
            continue;
        }
        const PgsRow& r = s.rows[i];
        const std::size_t a = at(r.slot_a);
        const std::size_t b = at(r.slot_b);
        s.dv_x[a] += x[i] * r.ka_x;
        s.dv_y[a] += x[i] * r.ka_y;
        s.dw[a] += x[i] * r.ra;
        s.dv_x[b] += x[i] * r.kb_x;
        s.dv_y[b] += x[i] * r.kb_y;
        s.dw[b] += x[i] * r.rb;
    }
    for (std::size_t i = 0; i < x.size(); ++i) {
        const PgsRow& r = s.rows[i];
        const std::size_t a = at(r.slot_a);
        const std::size_t b = at(r.slot_b);
        const double ja = r.nx * s.dv_x[a] + r.ny * s.dv_y[a] + r.rn_a * s.dw[a];
        const double jb = r.nx * s.dv_x[b] + r.ny * s.dv_y[b] + r.rn_b * s.dw[b];
        y[i] = ja - jb;
    }
}

double inner(const std::vector<double>& u, const std::vector<double>& v) {
    double sum = 0.0;
    for (std::size_t i = 0; i < u.size(); ++i) {
        sum += u[i] * v[i];
    }
    return sum;
}

// The M^-1 norm of a point's row of J on one body, scaled as its row is:
// scale sqrt(n.n / m + rn^2 / I).
double row_norm(const Body& body, const ContactPoint& p, double rn, double scale) {
    const Vec2 n = p.contact.normal;
    return scale * std::sqrt(body.inv_mass * (n.x * n.x + n.y * n.y) + body.inv_inertia * rn * rn);
}

// The bound ||A^|| <= max_i (s_ia S_a + s_ib S_b) of mprgp.h on the scaled
// rows, with the per-slot sums S kept in dv_x for the moment (a product
// clears it before use).
double norm_bound(const World& world, const std::vector<ContactPoint>& points, MprgpScratch& s) {
    std::fill(s.dv_x.begin(), s.dv_x.end(), 0.0);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const ContactPoint& p = points[i];
        s.dv_x[at(s.rows[i].slot_a)] += row_norm(world.bodies[at(p.a)], p, p.rn_a, s.scale[i]);
        s.dv_x[at(s.rows[i].slot_b)] += row_norm(world.bodies[at(p.b)], p, p.rn_b, s.scale[i]);
    }
    double bound = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const ContactPoint& p = points[i];
        const double sa = row_norm(world.bodies[at(p.a)], p, p.rn_a, s.scale[i]);
        const double sb = row_norm(world.bodies[at(p.b)], p, p.rn_b, s.scale[i]);
        bound =
            std::max(bound, sa * s.dv_x[at(s.rows[i].slot_a)] + sb * s.dv_x[at(s.rows[i].slot_b)]);
    }
    return bound;
}

// Point i's row of J and column of M^-1 J^T times scale_i, so that multiply()
// gives A^ x = D^-1/2 A D^-1/2 x.
void scale_row(PgsRow& r, double scale) {
    r.nx *= scale;
    r.ny *= scale;
    r.rn_a *= scale;
    r.rn_b *= scale;
    r.ka_x *= scale;
    r.ka_y *= scale;
    r.ra *= scale;
    r.kb_x *= scale;
    r.kb_y *= scale;
    r.rb *= scale;
}

// Rows, diagonals, scales, slots and vector sizes for this call; the warm
// start projected onto lambda >= 0 and scaled into mu. Returns the expansion
// step length.
double prepare(const World& world, const std::vector<ContactPoint>& points,
               const std::vector<double>& q, std::vector<double>& lambda, MprgpScratch& s) {
    if (s.local_of_body.size() < world.bodies.size()) {
        s.local_of_body.resize(world.bodies.size(), -1);
    }
    s.bodies.clear();
    const std::size_t n = points.size();
    const bool scaled = n > diagonal_scaling_points;
    s.rows.resize(n);
    s.diagonal.resize(n);
    s.scale.resize(n);
    s.scaled_q.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        s.rows[i] = row_of(world, points[i], s.local_of_body, s.bodies);
        s.diagonal[i] = delassus(world, points[i], points[i]); // A_ii, as solve_lcp sees it
        // A point between static bodies only (A_ii = 0) has nothing to scale.
        s.scale[i] = scaled && s.diagonal[i] > 0.0 ? 1.0 / std::sqrt(s.diagonal[i]) : 1.0;
        scale_row(s.rows[i], s.scale[i]);
        s.scaled_q[i] = s.scale[i] * q[i];
    }
    const std::size_t slots = s.bodies.size() + 1;
    s.dv_x.assign(slots, 0.0);
    s.dv_y.assign(slots, 0.0);
    s.dw.assign(slots, 0.0);
    s.gradient.assign(n, 0.0);
    s.direction.assign(n, 0.0);
    s.product.assign(n, 0.0);
    if (lambda.size() != n) {
        lambda.assign(n, 0.0);
    }
    s.mu.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        lambda[i] = std::max(0.0, lambda[i]); // a warm start is a solution's guess: never < 0
        s.mu[i] = lambda[i] / s.scale[i];
    }
    // 1.9 rather than 2 / ||A^||: the bound is rounded, and the theory's
    // interval (0, 2 / ||A^||] is open to nothing beyond it. An A of zeros
    // (points between static bodies only) needs no particular length.
    const double bound = norm_bound(world, points, s);
    return bound > 0.0 ? 1.9 / bound : 1.0;
}

// The LCP residual of one point in the original units, as solve_pgs measures
// it: with w_i = gradient_i / scale_i and A_ii lambda_i = A_ii scale_i mu_i,
// max(-w, min(A_ii lambda, w)). Unscaled (scale 1), the bits it always had.
double residual_of(double gradient, double mu, double diagonal, double scale) {
    const double w = gradient / scale;
    return std::max(-w, std::min(diagonal * scale * mu, w));
}

double residual(const std::vector<double>& mu, const MprgpScratch& s) {
    double worst = 0.0;
    for (std::size_t i = 0; i < mu.size(); ++i) {
        worst = std::max(worst, residual_of(s.gradient[i], mu[i], s.diagonal[i], s.scale[i]));
    }
    return worst;
}

// gradient = A^ mu + q^, fresh (no product for lambda = 0). Returns the
// products made.
int refresh_gradient(const std::vector<double>& q, const std::vector<double>& lambda,
                     MprgpScratch& s) {
    const bool zero = std::all_of(lambda.begin(), lambda.end(), [](double l) { return l == 0.0; });
    if (zero) {
        s.gradient = q;
        return 0;
    }
    multiply(lambda, s.gradient, s);
    for (std::size_t i = 0; i < q.size(); ++i) {
        s.gradient[i] += q[i];
    }
    return 1;
}

// p = the free gradient: w_i where lambda_i > 0, else 0.
void restart_direction(const std::vector<double>& lambda, MprgpScratch& s) {
    for (std::size_t i = 0; i < lambda.size(); ++i) {
        s.direction[i] = lambda[i] > 0.0 ? s.gradient[i] : 0.0;
    }
}

// Dostal's test ||beta||^2 <= Gamma^2 phi~ . phi: the chopped gradient beta
// (min(w_i, 0) on the active set) against the free gradient phi reduced to
// what a step of length alpha can take before lambda_i reaches 0.
bool proportional(const std::vector<double>& lambda, double alpha, const MprgpScratch& s) {
    double chopped = 0.0;
    double reduced = 0.0;
    for (std::size_t i = 0; i < lambda.size(); ++i) {
        const double w = s.gradient[i];
        if (lambda[i] > 0.0) {
            reduced += std::min(lambda[i] / alpha, w) * w;
        } else if (w < 0.0) {
            chopped += w * w;
        }
    }
    return chopped <= proportion * proportion * reduced;
}

// Proportioning: a line search along the chopped gradient, which only raises
// active entries. Returns the products made.
int proportioning(std::vector<double>& lambda, double alpha, MprgpScratch& s) {
    std::vector<double>& d = s.direction;
    for (std::size_t i = 0; i < lambda.size(); ++i) {
        d[i] = lambda[i] > 0.0 ? 0.0 : std::min(s.gradient[i], 0.0);
    }
    multiply(d, s.product, s);
    const double curvature = inner(d, s.product);
    // Zero curvature along a descent direction that only raises lambda means
    // the QP is unbounded (the LCP has no solution): a fixed step keeps the
    // iteration finite and the residual says it did not converge.
    const double step = curvature > 0.0 ? inner(d, d) / curvature : alpha;
    for (std::size_t i = 0; i < lambda.size(); ++i) {
        lambda[i] = std::max(0.0, lambda[i] - step * d[i]);
        s.gradient[i] -= step * s.product[i];
    }
    restart_direction(lambda, s);
    return 1;
}

// The largest step along -p that keeps lambda >= 0.
double feasible_step(const std::vector<double>& lambda, const std::vector<double>& p) {
    double step = infinite;
    for (std::size_t i = 0; i < lambda.size(); ++i) {
        if (p[i] > 0.0) {
            step = std::min(step, lambda[i] / p[i]);
        }
    }
    return step;
}

// Expansion: along -p to the bound (the step cg would overshoot), then a
// projected step of fixed length alpha along the free gradient, which may
// free or fix many entries at once; the gradient is then computed afresh.
int expansion(const std::vector<double>& q, std::vector<double>& lambda, double half, double alpha,
              MprgpScratch& s) {
    for (std::size_t i = 0; i < lambda.size(); ++i) {
        lambda[i] = std::max(0.0, lambda[i] - half * s.direction[i]);
        s.gradient[i] -= half * s.product[i];
    }
    for (std::size_t i = 0; i < lambda.size(); ++i) {
        if (lambda[i] > 0.0) {
            lambda[i] = std::max(0.0, lambda[i] - alpha * s.gradient[i]);
        }
    }
    const int products = refresh_gradient(q, lambda, s);
    restart_direction(lambda, s);
    return products;
}

// A conjugate gradient step on the free set, or an expansion step where it
// would cross lambda >= 0. `fresh` says whether the gradient was just
// recomputed rather than updated. Returns the products made.
int free_step(const std::vector<double>& q, std::vector<double>& lambda, double alpha, bool& fresh,
              MprgpScratch& s) {
    std::vector<double>& p = s.direction;
    multiply(p, s.product, s);
    const double curvature = inner(p, s.product);
    const double cg = curvature > 0.0 ? inner(s.gradient, p) / curvature : infinite;
    const double bound = feasible_step(lambda, p);
    if (cg <= bound) {
        for (std::size_t i = 0; i < lambda.size(); ++i) {
            lambda[i] = std::max(0.0, lambda[i] - cg * p[i]);
            s.gradient[i] -= cg * s.product[i];
        }
        // p = phi - beta p with beta = phi . A p / p . A p: A-conjugate to p.
        double phi_ap = 0.0;
        for (std::size_t i = 0; i < lambda.size(); ++i) {
            phi_ap += lambda[i] > 0.0 ? s.gradient[i] * s.product[i] : 0.0;
        }
        const double beta = phi_ap / curvature;
        for (std::size_t i = 0; i < lambda.size(); ++i) {
            p[i] = (lambda[i] > 0.0 ? s.gradient[i] : 0.0) - beta * p[i];
        }
        fresh = false;
        return 1;
    }
    // A direction of zero curvature with no bound ahead is flat: the
    // projected step alone moves.
    const double half = bound < infinite ? bound : 0.0;
    fresh = true;
    return 1 + expansion(q, lambda, half, alpha, s);
}

} // namespace

PgsResult solve_mprgp(const World& world, const std::vector<ContactPoint>& points,
                      const std::vector<double>& q, std::vector<double>& lambda,
                      const PgsSettings& settings, MprgpScratch& scratch) {
    MprgpScratch& s = scratch;
    const double alpha = prepare(world, points, q, lambda, s);
    std::vector<double>& mu = s.mu;
    const std::vector<double>& q_hat = s.scaled_q;
    PgsResult result;
    result.sweeps = refresh_gradient(q_hat, mu, s);
    bool fresh = true;
    result.residual = residual(mu, s);
    restart_direction(mu, s);
    const bool warm_enough = result.residual <= settings.tolerance;
    while (result.residual > settings.tolerance && result.sweeps < settings.max_sweeps) {
        if (proportional(mu, alpha, s)) {
            result.sweeps += free_step(q_hat, mu, alpha, fresh, s);
        } else {
            result.sweeps += proportioning(mu, alpha, s);
            fresh = false;
        }
        result.residual = residual(mu, s);
        if (result.residual <= settings.tolerance && !fresh) {
            // The running gradient says done: confirm on a fresh one, which
            // also restarts the iteration without its rounding if not.
            result.sweeps += refresh_gradient(q_hat, mu, s);
            fresh = true;
            result.residual = residual(mu, s);
            restart_direction(mu, s);
        }
    }
    if (!fresh) { // stopped by the cap: measure what is returned
        result.sweeps += refresh_gradient(q_hat, mu, s);
        result.residual = residual(mu, s);
    }
    result.converged = result.residual <= settings.tolerance;
    if (!warm_enough) { // a warm start that was good enough is returned as given
        for (std::size_t i = 0; i < mu.size(); ++i) {
            lambda[i] = s.scale[i] * mu[i];
        }
    }
    for (const int body : s.bodies) {
        s.local_of_body[at(body)] = -1; // reset only what this call touched
    }
    s.bodies.clear();
    return result;
}

} // namespace impulse
