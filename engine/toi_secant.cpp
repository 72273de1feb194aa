// The time of collision by a safeguarded secant search (docs/engine.md, "The
// secant search"). It finds what the seed's bisection finds, the latest
// instant free of interpenetration to within toi_tolerance, but puts each trial
// where the chord through the bracket's ends crosses zero, on the signed
// separation s(t) of the offending pair, instead of at the midpoint.
#include "toi_trials.h"

namespace impulse {

namespace {

// How many past bracket widths the halving safeguard looks back over.
constexpr int halving_window = 3;

// The search's state. s(t) is positive before the collision, negative after.
struct Bracket {
    double lo = 0.0;   // nothing interpenetrates at lo
    double hi = 0.0;   // the offending pair interpenetrates at hi
    double s_lo = 0.0; // s(lo) >= 0
    double s_hi = 0.0; // s(hi) < 0
    // The values the chord uses in place of s(lo) and s(hi): an end that stays
    // put while the other moves twice is scaled down (Anderson-Bjorck), so the
    // chord swings past the root and the stale end moves too.
    double weight_lo = 0.0;
    double weight_hi = 0.0;
    int last_moved = 0;   // -1: lo, +1: hi, 0: neither since the pair was chosen
    int stepped_past = 0; // the last trial was step_past from an end: -1 lo, +1 hi
    // s = 0 at lo and step_past beyond it: touching without approaching (a
    // resting body), where the chord carries no information. Halve from then on.
    bool flat = false;
    double widths[halving_window] = {}; // widths[k]: the width k + 1 iterations ago
};

Bracket bracket_for_pair(double lo, double hi, double s_lo, double s_hi) {
    Bracket b;
    b.lo = lo;
    b.hi = hi;
    b.s_lo = s_lo;
    b.s_hi = s_hi;
    b.weight_lo = s_lo;
    b.weight_hi = s_hi;
    for (double& width : b.widths) {
        width = 2.0 * (hi - lo); // no halving owed yet
    }
    return b;
}

// The halvings the bisection would still need to bring `width` to `tolerance`
// (at most about 2100 from the largest double to the smallest).
int halvings_needed(double width, double tolerance) {
    int n = 0;
    for (; width > tolerance && n < 2100; ++n) {
        width *= 0.5;
    }
    return n;
}

// Regula falsi: the zero of the chord through (lo, w_lo) and (hi, w_hi),
// t = hi - w_hi (hi - lo) / (w_hi - w_lo). With w_lo >= 0 > w_hi it lies in
// [lo, hi); the midpoint stands in if the weights do not straddle zero.
double chord_zero(const Bracket& b) {
    if (!(b.weight_lo >= 0.0 && b.weight_hi < 0.0)) {
        return b.lo + 0.5 * (b.hi - b.lo);
    }
    return b.hi - b.weight_hi * (b.hi - b.lo) / (b.weight_hi - b.weight_lo);
}

// The next trial time: the chord's zero, or the midpoint when the chord
// cannot be trusted to shrink the bracket.
double next_trial(Bracket& b, double tolerance, int iterations_left) {
    const double width = b.hi - b.lo;
    const double mid = b.lo + 0.5 * width;
    b.stepped_past = 0;
    // Halve when only the contact tolerance is still unmet (as the seed does),
    // when s is flat at lo, when the bracket did not halve over the last
    // halving_window iterations (so every halving_window + 1 iterations at
    // least halve it), and when only enough iterations are left for the
    // bisection to finish (so this search converges whenever the bisection
    // would within max_search_iterations).
    if (width <= tolerance || b.flat || width > 0.5 * b.widths[halving_window - 1] ||
        iterations_left <= halvings_needed(width, tolerance)) {
        return mid;
    }
    // Keep step_past inside each end. Once the chord's zero is accurate it
    // lands within step_past of the end that moved last; stepping past it
    // puts the trial on the root's other side and closes the bracket to
    // step_past < toi_tolerance, instead of creeping up on the root from one
    // side.
    const double step_past = 0.5 * tolerance;
    double t = chord_zero(b);
    if (t < b.lo + step_past) {
        b.stepped_past = -1;
        t = b.lo + step_past;
    } else if (t > b.hi - step_past) {
        b.stepped_past = +1;
        t = b.hi - step_past;
    }
    // step_past below the spacing of doubles at this time: leave it to halving.
    if (!(b.lo < t && t < b.hi)) {
        b.stepped_past = 0;
        return mid;
    }
    return t;
}

void remember_width(Bracket& b) {
    for (int k = halving_window - 1; k > 0; --k) {
        b.widths[k] = b.widths[k - 1];
    }
    b.widths[0] = b.hi - b.lo;
}

// Anderson-Bjorck: when the same end moves twice in a row, the stale end's
// weight is scaled by m = 1 - s_new / s_old (how much the moving end's value
// fell), or by 1/2 when that is not in (0, 1) (Illinois).
double stale_scale(double s_new, double s_old) {
    const double m = s_old != 0.0 ? 1.0 - s_new / s_old : 0.5;
    return m > 0.0 && m < 1.0 ? m : 0.5;
}

// Nothing interpenetrates at t: it becomes lo.
void move_lo(Bracket& b, double t, double s_t) {
    remember_width(b);
    if (b.last_moved < 0) {
        b.weight_hi *= stale_scale(s_t, b.s_lo);
    }
    if (b.stepped_past < 0 && s_t <= 0.0) {
        b.flat = true;
    }
    b.lo = t;
    b.s_lo = s_t;
    b.weight_lo = s_t;
    b.last_moved = -1;
}

// The offending pair still interpenetrates at t: it becomes hi.
void move_hi(Bracket& b, double t, double s_t) {
    remember_width(b);
    if (b.last_moved > 0) {
        b.weight_lo *= stale_scale(s_t, b.s_hi);
    }
    b.hi = t;
    b.s_hi = s_t;
    b.weight_hi = s_t;
    b.last_moved = +1;
}

// Another pair interpenetrates at t, so it collides first: s(t) is now that
// pair's separation and the chord starts afresh on it.
void change_pair(Bracket& b, double t, double s_lo, double s_t) {
    remember_width(b);
    Bracket fresh = bracket_for_pair(b.lo, t, s_lo, s_t);
    for (int k = 0; k < halving_window; ++k) {
        fresh.widths[k] = b.widths[k];
    }
    b = fresh;
}

// One loop for the world's trials and one pair's (toi_trials.h).
template <class Trials>
TimeOfImpact secant_search(World& world, Trials& trials, double h, double s_h) {
    const SolverSettings& solver = world.solver;
    TimeOfImpact toi;
    Bracket b = bracket_for_pair(0.0, h, trials.separation_at_lo(), s_h);
    for (;;) {
        if (b.hi - b.lo <= solver.toi_tolerance && b.s_lo <= solver.contact_tolerance) {
            toi.converged = true;
            break;
        }
        const double t =
            next_trial(b, solver.toi_tolerance, solver.max_search_iterations - toi.iterations);
        // A bracket that no longer shrinks means the tolerance is below the
        // spacing of doubles at this time: stop rather than loop forever.
        if (toi.iterations == solver.max_search_iterations || t <= b.lo || t >= b.hi) {
            break;
        }
        ++toi.iterations;
        ++world.work.toi_iterations;
        const SecantTrial trial = trials.secant_trial(t);
        switch (trial.outcome) {
        case SecantTrial::Outcome::free:
            move_lo(b, t, trial.s);
            break;
        case SecantTrial::Outcome::hit:
            move_hi(b, t, trial.s);
            break;
        case SecantTrial::Outcome::new_pair:
            change_pair(b, t, trial.s_lo, trial.s);
            break;
        }
    }
    toi.time = b.lo;
    toi.pair = trials.pair();
    return toi;
}

} // namespace

TimeOfImpact secant_time_of_impact(World& world, const Configuration& start, double h,
                                   const Configuration& at_h, int pair_at_h,
                                   Configuration& at_impact) {
    WorldTrials trials(world, start, pair_at_h, at_impact);
    // s(h): the bisection never needs it.
    const double s_h = pair_separation(world, at_h, world.pairs[pair_at_h]);
    return secant_search(world, trials, h, s_h);
}

TimeOfImpact secant_pair_time_of_impact(World& world, const PairMotion& motion, double h,
                                        double s_h, BodyState& at_a, BodyState& at_b) {
    PairTrials trials(world, motion, at_a, at_b);
    return secant_search(world, trials, h, s_h);
}

} // namespace impulse
