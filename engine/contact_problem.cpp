#include "contact_problem.h"

namespace impulse {

ContactPoint contact_point(const World& world, int pair, const Contact& contact, double vn) {
    const Pair& p = world.pairs[static_cast<std::size_t>(pair)];
    const Body& a = world.bodies[static_cast<std::size_t>(p.a)];
    const Body& b = world.bodies[static_cast<std::size_t>(p.b)];
    return {pair,
            p.a,
            p.b,
            contact,
            dot(perp(contact.point - a.state.position), contact.normal),
            dot(perp(contact.point - b.state.position), contact.normal),
            vn};
}

// A_ij: the change of v_AB . n at point i per unit impulse at point j, i.e.
// J M^-1 J^T where point j's row of J is (n, perp(r_AP) . n) on its body A and
// minus (n, perp(r_BP) . n) on its body B (Eqs. 8a, 8b). On the diagonal this
// is Eq. 9's denominator, in impulse_magnitude()'s order of operations; every
// product is written so that A_ij and A_ji are the same bits.
double delassus(const World& world, const ContactPoint& i, const ContactPoint& j) {
    const Vec2 ni = i.contact.normal;
    const Vec2 nj = j.contact.normal;
    if (i.pair == j.pair) {
        const Body& a = world.bodies[static_cast<std::size_t>(i.a)];
        const Body& b = world.bodies[static_cast<std::size_t>(i.b)];
        double k = dot(ni, nj) * (a.inv_mass + b.inv_mass); // Eq. 9
        if (a.rotates() || b.rotates()) {
            k += i.rn_a * j.rn_a * a.inv_inertia + i.rn_b * j.rn_b * b.inv_inertia;
        }
        return k;
    }
    // Two different pairs share at most one body. Its sign in each row is +
    // where it is that point's A and - where it is B.
    int shared = -1;
    double rn_i = 0.0;
    double rn_j = 0.0;
    double sign = 1.0;
    if (i.a == j.a) {
        shared = i.a;
        rn_i = i.rn_a;
        rn_j = j.rn_a;
    } else if (i.a == j.b) {
        shared = i.a;
        rn_i = i.rn_a;
        rn_j = j.rn_b;
        sign = -1.0;
    } else if (i.b == j.a) {
        shared = i.b;
        rn_i = i.rn_b;
        rn_j = j.rn_a;
        sign = -1.0;
    } else if (i.b == j.b) {
        shared = i.b;
        rn_i = i.rn_b;
        rn_j = j.rn_b;
    }
    if (shared < 0 || world.bodies[static_cast<std::size_t>(shared)].is_static()) {
        return 0.0;
    }
    const Body& s = world.bodies[static_cast<std::size_t>(shared)];
    double k = dot(ni, nj) * s.inv_mass;
    if (s.rotates()) {
        k += rn_i * rn_j * s.inv_inertia;
    }
    return sign * k;
}

std::vector<double> delassus_matrix(const World& world, const std::vector<ContactPoint>& points) {
    const std::size_t n = points.size();
    std::vector<double> A(n * n);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i; j < n; ++j) {
            A[i * n + j] = delassus(world, points[i], points[j]);
            A[j * n + i] = A[i * n + j];
        }
    }
    return A;
}

} // namespace impulse
