// The conservation expectations: momentum, angular momentum and energy
// conserved in free space, and energy that never increases with e < 1.
#include "expectation_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace impulse::harness {

namespace {

// A conserved quantity as scalar components (momentum has two) and the scale
// of its terms.
std::vector<double> components_of(const Totals& t, const std::string& quantity) {
    if (quantity == "momentum") {
        return {t.momentum.x, t.momentum.y};
    }
    return {quantity == "angular_momentum" ? t.angular_momentum : t.energy};
}

double scale_of(const Totals& t, const std::string& quantity) {
    if (quantity == "momentum") {
        return t.momentum_scale;
    }
    return quantity == "angular_momentum" ? t.angular_momentum_scale : t.energy_scale;
}

// What explicit Euler adds to the energy over a step of h: sum m |g|^2 h^2 / 2
// (docs/physics.md, "Integrators"; it moves a body by its velocity at the
// step's start). A contact only takes from it: the velocities it leaves are a
// projection, in the mass metric, of those free flight would give. The other
// integrators gain nothing, so this is their 0.
double integrator_gain_per_h2(const Scene& scene, const std::vector<Mass>& masses) {
    if (scene.solver.integrator != Integrator::euler) {
        return 0.0;
    }
    const double g2 = dot(scene.gravity, scene.gravity);
    double sum = 0.0;
    for (const Mass& m : masses) {
        sum += m.body->mass * g2 / 2.0;
    }
    return sum;
}

} // namespace

// docs/physics.md: frictionless contact in free space conserves momentum and
// angular momentum; with e = 1, energy. Every frame is compared with frame 0
// and the frame where the quantity strays furthest is reported.
void check_conserved(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const std::optional<std::vector<Mass>> masses = masses_of(scene, trajectory, checks);
    if (!masses) {
        return;
    }
    std::vector<Totals> totals;
    totals.reserve(trajectory.frames.size());
    for (const std::vector<double>& frame : trajectory.frames) {
        totals.push_back(totals_in(frame, *masses, scene.gravity));
    }
    const Expectation& x = checks.expectation();
    for (const std::string& quantity : x.quantities) {
        const std::vector<double> initial = components_of(totals.front(), quantity);
        // The largest scale of frames 0 to k: frame k's numbers carry the
        // rounding of every frame before it (a ball at rest at y = 0 passes
        // y = 0 again after a bounce with terms of 72 J behind it).
        double scale = 0.0;
        double worst_scale = 0.0;
        std::size_t worst_frame = 0;
        std::size_t worst_component = 0;
        double largest = -std::numeric_limits<double>::infinity(); // off minus allowed
        for (std::size_t k = 0; k < totals.size(); ++k) {
            const std::vector<double> now = components_of(totals[k], quantity);
            scale = std::max(scale, scale_of(totals[k], quantity));
            for (std::size_t c = 0; c < now.size(); ++c) {
                const double beyond = std::abs(now[c] - initial[c]) - x.rtol * scale;
                // NaN is the worst of all: it is what a blown-up run leaves.
                if (beyond > largest || (std::isnan(beyond) && !std::isnan(largest))) {
                    largest = beyond;
                    worst_frame = k;
                    worst_component = c;
                    worst_scale = scale;
                }
            }
        }
        std::string name = quantity == "angular_momentum" ? "angular momentum" : quantity;
        if (initial.size() == 2) {
            name += worst_component == 0 ? " (x)" : " (y)";
        }
        const double t = frame_time(trajectory.frames[worst_frame]);
        checks.value("conserved " + name + ", furthest from t = 0 at t = " + sentence_number(t) +
                         " s",
                     {initial[worst_component], worst_scale},
                     components_of(totals[worst_frame], quantity)[worst_component]);
    }
}

// docs/physics.md: "with e < 1 energy never increases". One result: the rise
// from one frame to the next furthest past its allowance, judged against the
// larger of the two frames' energy scales (frame 0's may be 0: a body at rest
// at the origin).
void check_energy_non_increasing(const Scene& scene, const Trajectory& trajectory, Checks& checks) {
    const std::optional<std::vector<Mass>> masses = masses_of(scene, trajectory, checks);
    if (!masses) {
        return;
    }
    const Expectation& x = checks.expectation();
    const Totals initial = totals_in(trajectory.frames.front(), *masses, scene.gravity);
    const double gain_per_h2 = integrator_gain_per_h2(scene, *masses);
    double worst_gain = 0.0;
    std::size_t worst = 0;
    double before = initial.energy;
    double after = initial.energy;
    double scale = initial.energy_scale;
    double largest = -std::numeric_limits<double>::infinity(); // rise minus rtol x scale
    Totals previous = initial;
    for (std::size_t k = 1; k < trajectory.frames.size(); ++k) {
        const Totals now = totals_in(trajectory.frames[k], *masses, scene.gravity);
        const double step_scale = std::max(previous.energy_scale, now.energy_scale);
        const double h = frame_time(trajectory.frames[k]) - frame_time(trajectory.frames[k - 1]);
        const double gain = gain_per_h2 * h * h;
        const double beyond = now.energy - previous.energy - x.rtol * step_scale - gain;
        if (beyond > largest || std::isnan(beyond)) {
            largest = std::isnan(beyond) ? std::numeric_limits<double>::infinity() : beyond;
            worst = k;
            worst_gain = gain;
            before = previous.energy;
            after = now.energy;
            scale = step_scale;
        }
        previous = now;
    }
    const double t = frame_time(trajectory.frames[worst]);
    // E(k) <= E(k-1) + atol + rtol * scale: one-sided, a fall is always fine.
    // An allowance past the largest double (atol or rtol near 1e308) allows
    // any rise, as the scene asked: it is held at that double, not at inf,
    // which every judgement refuses (an outside review was told its finite
    // energies were "too large").
    const double allowed =
        std::min(x.atol + x.rtol * scale + worst_gain, std::numeric_limits<double>::max());
    const std::string what =
        "energy non-increasing, largest rise at t = " + sentence_number(t) + " s";
    // An energy of inf or NaN did not "rise by NaN J": say what it is.
    if (!std::isfinite(before) || !std::isfinite(after)) {
        checks.judged(what, false, before, after,
                      "the energy is " + sentence_number(after) +
                          " J at t = " + sentence_number(t) + " s (" + sentence_number(before) +
                          " J a frame before), beyond double precision: the scene's masses, "
                          "speeds, heights or gravity are too large for m v^2 / 2 + I w^2 / 2 - "
                          "m g . x to be summed, so whether it rose cannot be judged; scale "
                          "them down",
                      allowed);
        return;
    }
    checks.judged(what, after <= before + allowed, before, after,
                  "the energy rose by " + sentence_number(after - before) +
                      " J in the step to t = " + sentence_number(t) + " s, more than the " +
                      sentence_number(allowed) + " allowed (atol " + sentence_number(x.atol) +
                      " + rtol " + sentence_number(x.rtol) + " x " + sentence_number(scale) +
                      (worst_gain > 0.0 ? " + explicit Euler's sum m g^2 h^2 / 2 of " +
                                              sentence_number(worst_gain)
                                        : std::string()) +
                      ")",
                  allowed);
}

} // namespace impulse::harness
