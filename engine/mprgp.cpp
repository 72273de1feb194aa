#include "mprgp.h"

#include "index.h"
#include "mprgp_scaling.h"

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

// What one call's steps need besides the vectors: the expansion step length
// and what the unbounded test (flat_descent) measures against.
struct Limits {
    double alpha = 1.0;     // the expansion step length
    double norm = 0.0;      // B, the bound on ||A^|| (and on || |J| M^-1 |J|^T ||)
    double tolerance = 0.0; // settings.tolerance, a velocity
};

Limits limits_of(double norm, double tolerance) {
    Limits l;
    // 1.9 rather than 2 / ||A^||: the bound is rounded, and the theory's
    // interval (0, 2 / ||A^||] is open to nothing beyond it. An A of zeros
    // (points between static bodies only) needs no particular length.
    l.alpha = norm > 0.0 ? 1.9 / norm : 1.0;
    l.norm = norm;
    l.tolerance = tolerance;
    return l;
}

// The unbounded test (docs/engine.md, "The island solver", derives it). For
// A positive semidefinite a ray y = -p >= 0 with p.Ap = 0 has Ap = 0, and
// with q.y < 0 it is Farkas' proof that no lambda >= 0 gives w >= 0. Flat:
// the computed p.Ap at most kappa eps B |p|^2, the rounding bound of that
// computation (B also bounds || |J| M^-1 |J|^T ||); a line step along a
// direction that flat moves the impulses so far that the gradient's rounding
// there is as large as the slope it removes. Decisive: g.p (sum w_i z_i, z
// the ray in lambda's units) above tolerance sum_i scale_i |p_i| plus its own
// rounding, so that not even an answer to the tolerance exists (a slab
// exactly as thick as its slot is flat but not decisive, and solvable).
bool decisive(double slope, double spread, double magnitude, std::size_t n, double tolerance) {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    return slope > tolerance * spread + static_cast<double>(n) * eps * magnitude;
}

// kappa: a product's entry sums at most n body terms and a 3-term row, a dot
// product n terms.
double kappa_of(std::size_t n) {
    return 2.0 * static_cast<double>(n) + 8.0;
}

// Whether p.Ap (pp = p.p) is more than the rounding of its computation: a
// direction curved so is not flat.
bool curved(std::size_t n, double curvature, double pp, const Limits& limits) {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    return curvature > kappa_of(n) * eps * limits.norm * pp;
}

// pp = p.p, computed by the caller (inner(p, p)).
bool flat_descent(const std::vector<double>& p, double curvature, double pp, const Limits& limits,
                  const MprgpScratch& s) {
    if (curved(p.size(), curvature, pp, limits)) {
        return false;
    }
    double slope = 0.0;
    double spread = 0.0;
    double magnitude = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        slope += s.gradient[i] * p[i];
        spread += s.scale[i] * std::fabs(p[i]);
        magnitude += std::fabs(s.gradient[i] * p[i]);
    }
    return decisive(slope, spread, magnitude, p.size(), limits.tolerance);
}

bool flat_descent(const std::vector<double>& p, double curvature, const Limits& limits,
                  const MprgpScratch& s) {
    return flat_descent(p, curvature, inner(p, p), limits, s);
}

// Candidates: rays that are not flat as they come but may be after
// refine_ray. Only these gates are chosen, not derived: a candidate must
// still pass flat_descent on a product of its own, so a wrong one costs
// products, never an answer. Measured: 1e-6 let a solvable column (75 light
// boxes under 75 heavy) pay 18 products for candidates; 1e-7 none, there or
// in pile-boxes-100 and pile-discs-100/1000.
constexpr double candidate_curvature = 1e-7; // of B |y|^2
constexpr double candidate_share = 1e-2;     // of the largest rising component
constexpr int refine_steps = 16;

// The ray projected onto the null space of A restricted to its own points S:
// conjugate gradients on A_SS y = 0 stay in y + range(A_SS) and converge to
// y's null-space part. A candidate carries some of its own points' curved
// directions (a slab's floor and ceiling impulses a little unequal:
// curvature 1e-7 B |y|^2). Returns the products made.
int refine_ray(const Limits& limits, MprgpScratch& s) {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    const std::size_t n = s.ray.size();
    std::vector<double>& r = s.ray_residual;
    std::vector<double>& d = s.ray_direction;
    std::vector<double>& ad = s.ray_direction_product;
    r.resize(n);
    d.resize(n);
    ad.resize(n);
    s.ray_product.resize(n);
    multiply(s.ray, s.ray_product, s);
    int made = 1;
    for (std::size_t i = 0; i < n; ++i) {
        r[i] = s.ray[i] != 0.0 ? -s.ray_product[i] : 0.0;
        d[i] = r[i];
    }
    double rr = inner(r, r);
    const auto support = static_cast<int>(
        std::count_if(s.ray.begin(), s.ray.end(), [](double y) { return y != 0.0; }));
    for (int step = 0; step < std::min(support, refine_steps); ++step) {
        // ray_product is updated, not recomputed: enough to stop on.
        if (inner(s.ray, s.ray_product) <= kappa_of(n) * eps * limits.norm * inner(s.ray, s.ray)) {
            break;
        }
        multiply(d, ad, s);
        ++made;
        const double curvature = inner(d, ad);
        if (!(curvature > 0.0)) {
            break;
        }
        const double t = rr / curvature;
        for (std::size_t i = 0; i < n; ++i) {
            s.ray_product[i] += t * ad[i];
            if (s.ray[i] != 0.0) {
                s.ray[i] += t * d[i];
                r[i] -= t * ad[i];
            }
        }
        const double next = inner(r, r);
        for (std::size_t i = 0; i < n; ++i) {
            d[i] = r[i] + next / rr * d[i];
        }
        rr = next;
    }
    for (double& y : s.ray) {
        y = std::min(y, 0.0); // p's sign: a ray only raises
    }
    return made;
}

// Whether ray, refined, passes flat_descent on a fresh product. Returns the
// products made.
int flat_ray(const Limits& limits, bool& unbounded, MprgpScratch& s) {
    const int made = refine_ray(limits, s) + 1;
    multiply(s.ray, s.ray_product, s);
    unbounded = flat_descent(s.ray, inner(s.ray, s.ray_product), limits, s);
    return made;
}

// Whether the free step's direction p (curvature p.Ap, its step min(cg,
// bound) about to be taken) proves the problem unbounded. No p_i > 0 (bound
// infinite): flat_descent decides. Else p is a candidate when its falling
// components are small, and it is flat, or nearly (candidate_curvature) with
// a step that at least doubles |mu|. Measured: a flat p with components of
// 2e-11 |p| falling (rounding of the recurrence) whose bound let the step
// take the impulses to 3e10; a slab's ray with 0.2% of |p| from other points
// (curvature 1e-7 to 4e-6), each step multiplying the impulses by 4 to 12.
// So min(p, 0), then p's components within candidate_share of its largest
// rising one, are tried. Returns the products made.
int unbounded_direction(const std::vector<double>& p, double curvature, double pp, double bound,
                        double step, const std::vector<double>& mu, const Limits& limits,
                        bool& unbounded, MprgpScratch& s) {
    if (curvature > candidate_curvature * limits.norm * pp &&
        curved(p.size(), curvature, pp, limits)) {
        return 0; // curved: neither flat nor a candidate (the common step, no pass over p)
    }
    const bool flat = flat_descent(p, curvature, pp, limits, s);
    if (flat && bound == infinite) {
        unbounded = true;
        return 0;
    }
    double largest = 0.0; // the largest rising component, -p_i
    double falling = 0.0; // the largest falling one, p_i
    for (const double v : p) {
        largest = std::max(largest, -v);
        falling = std::max(falling, v);
    }
    if (falling > candidate_share * largest ||
        !(flat || (curvature <= candidate_curvature * limits.norm * pp &&
                   step * std::sqrt(pp) >= std::sqrt(inner(mu, mu))))) {
        return 0;
    }
    int made = 0;
    s.ray.resize(p.size());
    if (flat) {
        for (std::size_t i = 0; i < p.size(); ++i) {
            s.ray[i] = std::min(p[i], 0.0);
        }
        made += flat_ray(limits, unbounded, s);
    }
    if (!unbounded) {
        for (std::size_t i = 0; i < p.size(); ++i) {
            s.ray[i] = p[i] <= -candidate_share * largest ? p[i] : 0.0;
        }
        made += flat_ray(limits, unbounded, s);
    }
    return made;
}

// The growth test: MPRGP on a problem with no solution need not meet a flat
// direction (3 of 200 random problems of tests/test_mprgp_unbounded.cpp
// cycled, one with a period of 5 products, moving the impulses by about the
// same y >= 0 each period, to the cap). The impulses' growth since an anchor
// is then the candidate. Anchors at the products 1, 2, 4, 8, ... (Brent's
// cycle finding): a window holds many periods of any cycle begun before it,
// and there are at most about 11 tests to a cap of 2000. y = mu - mu_anchor
// is tried when it lowers little (|min(y, 0)| within candidate_share |y|),
// descends decisively on q^ (for A y = 0 the slope is q^.y wherever the
// iteration is) and y.(g - g_anchor) = y.A y, no product, is below
// candidate_curvature B |y|^2. Returns the products made.
int growth_along_ray(const std::vector<double>& mu, const Limits& limits, int products,
                     int& anchor_products, bool& unbounded, MprgpScratch& s) {
    if (products < 2 * anchor_products) {
        return 0;
    }
    const std::size_t n = mu.size();
    int made = 0;
    if (anchor_products > 0) {
        double curvature = 0.0;
        double lowered = 0.0;
        double norm = 0.0;
        double slope = 0.0;
        double spread = 0.0;
        double magnitude = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const double y = mu[i] - s.anchor_mu[i];
            curvature += y * (s.gradient[i] - s.anchor_gradient[i]);
            lowered += y < 0.0 ? y * y : 0.0;
            norm += y * y;
            const double up = std::max(y, 0.0);
            slope -= s.scaled_q[i] * up;
            spread += s.scale[i] * up;
            magnitude += std::fabs(s.scaled_q[i] * up);
        }
        if (lowered <= candidate_share * candidate_share * norm &&
            curvature <= candidate_curvature * limits.norm * norm &&
            decisive(slope, spread, magnitude, n, limits.tolerance)) {
            s.ray.resize(n);
            for (std::size_t i = 0; i < n; ++i) {
                s.ray[i] = std::min(s.anchor_mu[i] - mu[i], 0.0); // p's sign: -y
            }
            made = flat_ray(limits, unbounded, s);
        }
    }
    s.anchor_mu = mu;
    s.anchor_gradient = s.gradient;
    anchor_products = std::max(products, 1);
    return made;
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
// active entries, so no bound stops it: along a ray flat_descent accepts
// the iteration stops (`unbounded`) before stepping. Returns the products made.
int proportioning(std::vector<double>& lambda, const Limits& limits, bool& unbounded,
                  MprgpScratch& s) {
    std::vector<double>& d = s.direction;
    for (std::size_t i = 0; i < lambda.size(); ++i) {
        d[i] = lambda[i] > 0.0 ? 0.0 : std::min(s.gradient[i], 0.0);
    }
    multiply(d, s.product, s);
    const double curvature = inner(d, s.product);
    if (flat_descent(d, curvature, limits, s)) {
        unbounded = true;
        return 1;
    }
    // Zero curvature on a ray that descends within the tolerance only: a
    // fixed step keeps the iteration finite.
    const double step = curvature > 0.0 ? inner(d, d) / curvature : limits.alpha;
    for (std::size_t i = 0; i < lambda.size(); ++i) {
        lambda[i] = std::max(0.0, lambda[i] - step * d[i]);
        s.gradient[i] -= step * s.product[i];
    }
    restart_direction(lambda, s);
    return 1;
}

// What a free step reads from its direction p and the product A^ p, in one
// pass: each sum in index order, so the bits are inner()'s.
struct DirectionSums {
    double curvature = 0.0;  // p.A^p
    double slope = 0.0;      // gradient.p
    double length2 = 0.0;    // p.p
    double bound = infinite; // the largest step along -p that keeps lambda >= 0
};

DirectionSums direction_sums(const std::vector<double>& lambda, const MprgpScratch& s) {
    const std::vector<double>& p = s.direction;
    DirectionSums sums;
    for (std::size_t i = 0; i < lambda.size(); ++i) {
        sums.curvature += p[i] * s.product[i];
        sums.slope += s.gradient[i] * p[i];
        sums.length2 += p[i] * p[i];
        if (p[i] > 0.0) {
            sums.bound = std::min(sums.bound, lambda[i] / p[i]);
        }
    }
    return sums;
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
// would cross lambda >= 0; nothing when unbounded_direction finds the ray
// that proves the problem unbounded (`unbounded`). `fresh` says whether the
// gradient was just recomputed rather than updated. Returns the products
// made.
int free_step(const std::vector<double>& q, std::vector<double>& lambda, const Limits& limits,
              bool& fresh, bool& unbounded, MprgpScratch& s) {
    std::vector<double>& p = s.direction;
    multiply(p, s.product, s);
    const DirectionSums sums = direction_sums(lambda, s);
    const double curvature = sums.curvature;
    const double cg = curvature > 0.0 ? sums.slope / curvature : infinite;
    const double bound = sums.bound;
    const int tested = unbounded_direction(p, curvature, sums.length2, bound, std::min(cg, bound),
                                           lambda, limits, unbounded, s);
    if (unbounded) {
        return 1 + tested; // before stepping: lambda and the gradient as they were
    }
    if (cg <= bound && cg < infinite) {
        // p = phi - beta p with beta = phi . A p / p . A p: A-conjugate to p.
        double phi_ap = 0.0;
        for (std::size_t i = 0; i < lambda.size(); ++i) {
            lambda[i] = std::max(0.0, lambda[i] - cg * p[i]);
            s.gradient[i] -= cg * s.product[i];
            phi_ap += lambda[i] > 0.0 ? s.gradient[i] * s.product[i] : 0.0;
        }
        const double beta = phi_ap / curvature;
        for (std::size_t i = 0; i < lambda.size(); ++i) {
            p[i] = (lambda[i] > 0.0 ? s.gradient[i] : 0.0) - beta * p[i];
        }
        fresh = false;
        return 1 + tested;
    }
    // A direction of zero curvature with no bound ahead that flat_descent
    // did not accept is flat (it descends within the tolerance at most): the
    // projected step alone moves. (Stepping infinitely far along it made the
    // impulses infinite.)
    const double half = bound < infinite ? bound : 0.0;
    fresh = true;
    return 1 + tested + expansion(q, lambda, half, limits.alpha, s);
}

} // namespace

MprgpResult solve_mprgp(const World& world, const std::vector<ContactPoint>& points,
                        const std::vector<double>& q, std::vector<double>& lambda,
                        const PgsSettings& settings, MprgpScratch& scratch, MprgpScaling scaling) {
    MprgpScratch& s = scratch;
    const Limits limits =
        limits_of(prepare_scaled_problem(world, points, q, lambda, s, scaling), settings.tolerance);
    std::vector<double>& mu = s.mu;
    const std::vector<double>& q_hat = s.scaled_q;
    MprgpResult result;
    result.sweeps = refresh_gradient(q_hat, mu, s);
    bool fresh = true;
    result.residual = residual(mu, s);
    restart_direction(mu, s);
    const bool warm_enough = result.residual <= settings.tolerance;
    int anchor_products = 0; // none yet
    while (result.residual > settings.tolerance && result.sweeps < settings.max_sweeps &&
           !result.unbounded) {
        if (proportional(mu, limits.alpha, s)) {
            result.sweeps += free_step(q_hat, mu, limits, fresh, result.unbounded, s);
        } else {
            result.sweeps += proportioning(mu, limits, result.unbounded, s);
            if (!result.unbounded) {
                fresh = false; // the step updated the gradient
            }
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
        if (result.residual > settings.tolerance && !result.unbounded) {
            result.sweeps +=
                growth_along_ray(mu, limits, result.sweeps, anchor_products, result.unbounded, s);
        }
    }
    if (!fresh) { // stopped by the cap or a ray: measure what is returned
        result.sweeps += refresh_gradient(q_hat, mu, s);
        result.residual = residual(mu, s);
    }
    result.converged = !result.unbounded && result.residual <= settings.tolerance;
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
