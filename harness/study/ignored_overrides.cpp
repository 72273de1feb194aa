#include "ignored_overrides.h"

#include "number_format.h"

#include <string>

namespace impulse::harness {

namespace {

// Whether, for every value of the other setting, the digests along one
// setting are all equal and all measured. `at(i, j)` is the digest of the
// setting's value i with the other's value j.
template <typename At> bool all_alike(std::size_t values, std::size_t others, const At& at) {
    if (values < 2) {
        return false;
    }
    for (std::size_t j = 0; j < others; ++j) {
        for (std::size_t i = 0; i < values; ++i) {
            if (at(i, j) == 0 || at(i, j) != at(0, j)) {
                return false;
            }
        }
    }
    return true;
}

} // namespace

IgnoredOverrides ignored_overrides(const FirstStepRuns& runs) {
    const std::size_t nt = runs.tolerances;
    IgnoredOverrides ignored;
    if (runs.digests.size() != runs.integrators * nt) {
        return ignored;
    }
    ignored.integrator = all_alike(runs.integrators, nt, [&](std::size_t i, std::size_t j) {
        return runs.digests[i * nt + j];
    });
    ignored.toi_tolerance = all_alike(nt, runs.integrators, [&](std::size_t i, std::size_t j) {
        return runs.digests[j * nt + i];
    });
    return ignored;
}

void skip_repeated_points(std::vector<SweepPoint>& points, const SweepConfig& config,
                          const IgnoredOverrides& ignored) {
    const std::string first_dt = format_double(config.dts.front());
    const std::string integrator_reason =
        config.engine.name + " gave the same trajectory under every integrator at dt " + first_dt +
        " (it ignores solver.integrator, or it changes nothing here), so only " +
        integrator_name(config.integrators.front()) + " is run";
    const std::string tolerance_reason =
        config.engine.name + " gave the same trajectory under every toi_tolerance at dt " +
        first_dt + " (it ignores solver.toi_tolerance, or it changes nothing here), so only " +
        format_double(config.toi_tolerances.front()) + " is run";
    for (SweepPoint& p : points) {
        if (p.box2d || !p.reference.empty() || p.kind == EngineSpec::Kind::impulse) {
            continue;
        }
        const bool other_integrator = p.integrator != config.integrators.front();
        const bool other_tolerance = p.toi_tolerance != config.toi_tolerances.front();
        if ((ignored.integrator && other_integrator) ||
            (ignored.toi_tolerance && other_tolerance)) {
            p.skipped = true;
            p.ok = false;
            p.failure =
                ignored.integrator && other_integrator ? integrator_reason : tolerance_reason;
        }
    }
}

} // namespace impulse::harness
