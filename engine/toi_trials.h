// What a time-of-impact search evaluates at a trial time t seconds into the
// step. The world search (the seed's) integrates every body from the step's
// start and asks whether any pair interpenetrates; local stepping integrates
// one pair on its bodies' clocks and measures its separation. Each search
// method is one loop templated on these two (toi_bisection.cpp,
// toi_secant.cpp), so with one pair and both offsets 0 the two make the same
// trials and the same tests, and give the same bits.
#pragma once

#include "integrator.h"
#include "narrow_phase_query.h"
#include "time_of_impact.h"

namespace impulse {

// What one trial found, for the secant search.
struct SecantTrial {
    enum class Outcome {
        free,    // nothing interpenetrates: t becomes lo
        hit,     // the offending pair interpenetrates: t becomes hi
        new_pair // another pair interpenetrates, so it collides first
    } outcome = Outcome::free;
    double s = 0.0;    // the (new) offending pair's separation at t
    double s_lo = 0.0; // new_pair: the new pair's separation at lo
};

// The world's trials: the configuration at lo is kept in `at_lo`.
class WorldTrials {
  public:
    WorldTrials(World& world, const Configuration& start, int pair_at_h, Configuration& at_lo)
        : world_(world), start_(start), pair_(pair_at_h), at_lo_(at_lo) {
        at_lo_ = start;
    }

    // The offending pair: the one interpenetrating at hi.
    int pair() const { return pair_; }

    double separation_at_lo() { return pair_separation(world_, at_lo_, world_.pairs[pair_]); }

    // The seed's trial: is any pair interpenetrating at t? Like the seed, every
    // trial is integrated from the step's start.
    bool interpenetrates_at(double t) {
        advance_all(world_, start_, t, trial_);
        const int pair = first_interpenetrating_pair(world_, trial_);
        if (pair >= 0) {
            pair_ = pair;
            return true;
        }
        at_lo_.swap(trial_);
        return false;
    }

    SecantTrial secant_trial(double t) {
        const int offending = pair_;
        if (!interpenetrates_at(t)) {
            return {SecantTrial::Outcome::free, separation_at_lo(), 0.0};
        }
        const double s = pair_separation(world_, trial_, world_.pairs[pair_]);
        if (pair_ == offending) {
            return {SecantTrial::Outcome::hit, s, 0.0};
        }
        return {SecantTrial::Outcome::new_pair, s, separation_at_lo()};
    }

  private:
    World& world_;
    const Configuration& start_;
    int pair_;
    Configuration& at_lo_;
    Configuration trial_;
};

// One pair's trials (local stepping): the states at lo are kept in at_a and
// at_b. No other pair is looked at, so the offending pair never changes.
class PairTrials {
  public:
    PairTrials(World& world, const PairMotion& motion, BodyState& at_a, BodyState& at_b)
        : world_(world), motion_(motion), at_a_(at_a), at_b_(at_b) {
        state_at(0.0, at_a_, at_b_);
        s_lo_ = pair_separation(world_, motion_.pair, at_a_, at_b_);
    }

    int pair() const { return -1; }

    double separation_at_lo() const { return s_lo_; }

    bool interpenetrates_at(double t) {
        return secant_trial(t).outcome != SecantTrial::Outcome::free;
    }

    SecantTrial secant_trial(double t) {
        state_at(t, trial_a_, trial_b_);
        const double s = pair_separation(world_, motion_.pair, trial_a_, trial_b_);
        if (s < 0.0) {
            return {SecantTrial::Outcome::hit, s, 0.0};
        }
        s_lo_ = s;
        at_a_ = trial_a_;
        at_b_ = trial_b_;
        return {SecantTrial::Outcome::free, s, 0.0};
    }

  private:
    // The pair's states u seconds into the search (one body advance per
    // dynamic body; time_of_impact.h, PairMotion).
    void state_at(double u, BodyState& a, BodyState& b) {
        const auto at = [&](int index, const BodyState& from, double offset) {
            const Body& body = world_.bodies[static_cast<std::size_t>(index)];
            // Not integrated over zero time either: that could turn a -0.0 into +0.0.
            if (body.is_static() || offset + u == 0.0) {
                return from;
            }
            ++world_.work.body_advances;
            return advance(world_.solver.integrator, from, world_.gravity, body.rotates(),
                           offset + u);
        };
        a = at(motion_.pair.a, motion_.from_a, motion_.offset_a);
        b = at(motion_.pair.b, motion_.from_b, motion_.offset_b);
    }

    World& world_;
    const PairMotion& motion_;
    BodyState& at_a_;
    BodyState& at_b_;
    BodyState trial_a_;
    BodyState trial_b_;
    double s_lo_ = 0.0;
};

} // namespace impulse
