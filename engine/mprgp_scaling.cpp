// The problem MPRGP iterates on (mprgp.h, "Diagonal scaling"): each point's
// row of J and column of M^-1 J^T, scaled, and the bound on ||A^||.
#include "mprgp_scaling.h"

#include "contact_problem.h"
#include "contact_rows.h"
#include "impulse_unit.h"
#include "index.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace impulse {

namespace {

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

} // namespace

double prepare_scaled_problem(const World& world, const std::vector<ContactPoint>& points,
                              const std::vector<double>& q, std::vector<double>& lambda,
                              MprgpScratch& s, MprgpScaling scaling) {
    if (s.local_of_body.size() < world.bodies.size()) {
        s.local_of_body.resize(world.bodies.size(), -1);
    }
    s.bodies.clear();
    const std::size_t n = points.size();
    const bool scaled = scaling == MprgpScaling::diagonal || n > diagonal_scaling_points;
    s.rows.resize(n);
    s.diagonal.resize(n);
    s.scale.resize(n);
    s.scaled_q.resize(n);
    double largest = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        s.rows[i] = row_of(world, points[i], s.local_of_body, s.bodies);
        s.diagonal[i] = delassus(world, points[i], points[i]); // A_ii, as solve_lcp sees it
        largest = std::max(largest, s.diagonal[i]);
    }
    const double unit = row_unit(largest); // impulse_unit.h
    for (std::size_t i = 0; i < n; ++i) {
        // A point between static bodies only (A_ii = 0) has nothing to scale.
        s.scale[i] = scaled && s.diagonal[i] > 0.0 ? 1.0 / std::sqrt(s.diagonal[i]) : unit;
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
    return norm_bound(world, points, s);
}

} // namespace impulse
