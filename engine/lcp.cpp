// Principal pivoting with Murty's least-index rule for the LCP of lcp.h, the
// linear solves by Eigen; every active set as a fallback for small problems.
//
// Eigen's SIMD kernels would break determinism: on aarch64 they use fused
// multiply-adds (NEON vfmaq) whatever -ffp-contract says, and on x86-64-v3
// their 4-wide AVX packets sum in another order than SSE2's 2-wide ones. With
// them off, what remains is scalar + - * / and sqrt, which -ffp-contract=off
// and -mno-fma keep the same on every build. The switch must hold for every
// file that includes Eigen (their template instances are merged at link time),
// so it belongs on the engine target; this is the fallback while it is not.
#ifndef EIGEN_DONT_VECTORIZE
#define EIGEN_DONT_VECTORIZE
#endif

#include "lcp.h"

#include "impulse_unit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>

namespace impulse {

namespace {

using Eigen::Index;
using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;
using RowMajorMap =
    Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;

// x with M x = rhs, M a principal block of A (the active points, where w = 0).
Vector solve_block(const Matrix& M, const Vector& rhs, double singular_threshold) {
    const Index k = M.rows();
    if (k == 0) {
        return Vector();
    }
    if (k == 1 && M(0, 0) > 0.0) {
        // With q = (1 + e) vn this is Eq. 9's j = -(1 + e) vn / k operation for
        // operation, so a problem of one point gives single contact's bits.
        Vector x(1);
        x(0) = rhs(0) / M(0, 0);
        return x;
    }
    if (k == 2) {
        const Eigen::Matrix2d m = M;
        const double det = m.determinant();
        const double scale = std::max(std::abs(m(0, 0) * m(1, 1)), std::abs(m(0, 1) * m(1, 0)));
        if (std::abs(det) > singular_threshold * scale) {
            // Eigen's 2 x 2 inverse is the cofactor formula (d, -b; -c, a) / (ad - cb),
            // which maps to itself, bit for bit, when the two points swap places;
            // with the products summed in this order, a problem symmetric under the
            // swap (a box landing flat) gets bitwise equal impulses at both points.
            const Eigen::Matrix2d inv = m.inverse();
            Vector x(2);
            x(0) = inv(0, 0) * rhs(0) + inv(0, 1) * rhs(1);
            x(1) = inv(1, 0) * rhs(0) + inv(1, 1) * rhs(1);
            return x;
        }
    }
    // Three or more points, or a singular block (redundant points: more points
    // than the bodies have freedoms): rank-revealing, and for a singular but
    // consistent block the minimum-norm impulses (redundant points share).
    Eigen::CompleteOrthogonalDecomposition<Matrix> cod(k, k);
    cod.setThreshold(singular_threshold);
    cod.compute(M);
    return cod.solve(rhs);
}

struct Trial {
    Vector lambda; // 0 outside the active set
    Vector w;      // A lambda + q; on the active set, the residual of the solve
};

class Problem {
  public:
    Problem(const std::vector<double>& A, const std::vector<double>& q, const LcpSettings& settings)
        : n_(static_cast<Index>(q.size())), A_(A.data(), n_, n_),
          q_(Eigen::Map<const Vector>(q.data(), n_)), settings_(settings) {
        const double largest = n_ == 0 ? 0.0 : q_.cwiseAbs().maxCoeff();
        tau_ = settings.tolerance * largest;
    }

    Index size() const { return n_; }

    Trial trial(const std::vector<bool>& active) const {
        std::vector<Index> set;
        for (Index i = 0; i < n_; ++i) {
            if (active[static_cast<std::size_t>(i)]) {
                set.push_back(i);
            }
        }
        Trial t;
        t.lambda = Vector::Zero(n_);
        if (!set.empty()) {
            const Matrix block = A_(set, set);
            const Vector rhs = -q_(set);
            const Vector x = solve_block(block, rhs, settings_.singular_threshold);
            for (std::size_t k = 0; k < set.size(); ++k) {
                t.lambda(set[k]) = x(static_cast<Index>(k));
            }
        }
        t.w = A_ * t.lambda + q_;
        return t;
    }

    // Murty's rule: the least index whose status is wrong, an active point
    // pulling (lambda_i < 0) or an inactive one approaching (w_i < 0); -1 if none.
    Index least_infeasible(const Trial& t, const std::vector<bool>& active) const {
        for (Index i = 0; i < n_; ++i) {
            const bool wrong = active[static_cast<std::size_t>(i)] ? t.lambda(i) * A_(i, i) < -tau_
                                                                   : t.w(i) < -tau_;
            if (wrong) {
                return i;
            }
        }
        return -1;
    }

    // Sets impulses within the tolerance of 0 to 0, then checks every
    // condition; a singular block solved in the least-squares sense fails here
    // when its residual is not rounding.
    bool accept(Trial& t) const {
        bool clamped = false;
        for (Index i = 0; i < n_; ++i) {
            if (t.lambda(i) < 0.0) {
                if (t.lambda(i) * A_(i, i) < -tau_) {
                    return false;
                }
                t.lambda(i) = 0.0;
                clamped = true;
            }
        }
        if (clamped) {
            t.w = A_ * t.lambda + q_;
        }
        for (Index i = 0; i < n_; ++i) {
            const bool both_positive = t.lambda(i) * A_(i, i) > tau_ && t.w(i) > tau_;
            if (t.w(i) < -tau_ || both_positive) {
                return false;
            }
        }
        return true;
    }

  private:
    Index n_;
    RowMajorMap A_;
    Vector q_;
    LcpSettings settings_;
    double tau_ = 0.0;
};

LcpSolution solution_of(const Trial& t) {
    LcpSolution s;
    s.solved = true;
    s.lambda.assign(t.lambda.data(), t.lambda.data() + t.lambda.size());
    s.w.assign(t.w.data(), t.w.data() + t.w.size());
    return s;
}

int popcount(unsigned long long mask) {
    int count = 0;
    for (; mask != 0; mask &= mask - 1) {
        ++count;
    }
    return count;
}

// impulse_unit.h's delassus_unit for A: scaled by a power of two, A lambda
// is unchanged and lambda scales exactly (in a pile of density 1e200, A's
// entries near 1e-200 made a 2 x 2 block's products underflow to 0, a
// "singular" block, and no solution was found).
double unit_of(const std::vector<double>& A, std::size_t n) {
    double largest = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        largest = std::max(largest, A[i * n + i]);
    }
    return delassus_unit(largest);
}
LcpSolution solve_unit_lcp(const std::vector<double>& A, const std::vector<double>& q,
                           const LcpSettings& settings, const std::vector<double>& warm);

} // namespace

LcpSolution solve_lcp(const std::vector<double>& A, const std::vector<double>& q,
                      const LcpSettings& settings, const std::vector<double>& warm) {
    const double unit = unit_of(A, q.size());
    if (unit == 1.0) {
        return solve_unit_lcp(A, q, settings, warm);
    }
    std::vector<double> scaled(A.size());
    for (std::size_t i = 0; i < A.size(); ++i) {
        scaled[i] = unit * A[i];
    }
    LcpSolution solution = solve_unit_lcp(scaled, q, settings, warm);
    for (double& lambda : solution.lambda) {
        lambda *= unit; // (unit A) (lambda / unit) = A lambda
    }
    return solution;
}

namespace {

LcpSolution solve_unit_lcp(const std::vector<double>& A, const std::vector<double>& q,
                           const LcpSettings& settings, const std::vector<double>& warm) {
    const Problem problem(A, q, settings);
    const Index n = problem.size();
    const auto count = static_cast<std::size_t>(n);

    // Principal pivoting from the points with q_i < 0 (for contacts: the
    // approaching ones), which is the answer when the points do not interact,
    // and those a warm guess has pushing (a resting contact's set barely
    // changes from step to step). For a P-matrix (A positive definite:
    // independent points) Murty's least-index rule reaches the unique
    // solution in finitely many pivots from any starting set.
    std::vector<bool> active(count);
    for (std::size_t i = 0; i < count; ++i) {
        active[i] = warm.empty() ? q[i] < 0.0 : (warm[i] > 0.0 || q[i] < 0.0);
    }
    const int max_pivots =
        settings.max_pivots > 0 ? settings.max_pivots : std::max(64, 8 * static_cast<int>(n));
    int pivots = 0;
    for (;;) {
        Trial t = problem.trial(active);
        const Index flip = problem.least_infeasible(t, active);
        if (flip < 0) {
            if (problem.accept(t)) {
                LcpSolution s = solution_of(t);
                s.pivots = pivots;
                return s;
            }
            break; // a singular block without a consistent solution: no pivot helps
        }
        if (pivots == max_pivots) {
            break;
        }
        active[static_cast<std::size_t>(flip)] = !active[static_cast<std::size_t>(flip)];
        ++pivots;
    }

    // With A only semidefinite the rule may stall or cycle. A solution, when
    // one exists, has an active set with a non-singular block (a basic
    // solution), so trying every set finds it: fewest active points first,
    // then in the order of the set's bits.
    LcpSolution failed;
    failed.pivots = pivots;
    if (n > settings.max_enumerated || n >= 63) {
        return failed;
    }
    const unsigned long long sets = 1ULL << static_cast<unsigned>(n);
    for (int size = 0; size <= static_cast<int>(n); ++size) {
        for (unsigned long long mask = 0; mask < sets; ++mask) {
            if (popcount(mask) != size) {
                continue;
            }
            for (std::size_t i = 0; i < count; ++i) {
                active[i] = ((mask >> i) & 1ULL) != 0;
            }
            ++failed.enumerated;
            Trial t = problem.trial(active);
            if (problem.least_infeasible(t, active) < 0 && problem.accept(t)) {
                LcpSolution s = solution_of(t);
                s.pivots = pivots;
                s.enumerated = failed.enumerated;
                return s;
            }
        }
    }
    return failed;
}

} // namespace

} // namespace impulse
