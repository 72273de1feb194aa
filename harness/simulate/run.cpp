#include "run.h"

#include "contact_band.h"
#include "input_error.h"
#include "number_format.h"
#include "record.h"
#include "simulator.h"
#include "step_travel.h"
#include "tunnelling.h"

namespace impulse::harness {

Scene with_overrides(Scene scene, const Overrides& overrides) {
    if (overrides.dt) {
        // The scene's own dt was validated on load; an override must meet the same rules.
        const std::string given = "--dt " + format_double(*overrides.dt);
        if (*overrides.dt > scene.duration) {
            throw InputError(scene.file, "duration",
                             given + " is longer than the scene's duration of " +
                                 format_double(scene.duration) + " s");
        }
        if (scene.duration / *overrides.dt > static_cast<double>(max_steps)) {
            throw InputError(scene.file, "duration",
                             given + " would take more than " + std::to_string(max_steps) +
                                 " steps");
        }
        scene.dt = *overrides.dt;
    }
    if (overrides.integrator) {
        scene.solver.integrator = *overrides.integrator;
    }
    if (overrides.toi_tolerance) {
        scene.solver.toi_tolerance = *overrides.toi_tolerance;
    }
    return scene;
}

std::string overrides_list(const Overrides& overrides) {
    std::string used;
    for (const auto& [key, given] : {std::pair{"dt", overrides.dt.has_value()},
                                     {"integrator", overrides.integrator.has_value()},
                                     {"toi_tolerance", overrides.toi_tolerance.has_value()}}) {
        if (given) {
            used += std::string(used.empty() ? "" : ", ") + "\"" + key + "\"";
        }
    }
    return used.empty() ? used : "[" + used + "]";
}

Trajectory run_scene(const Scene& scene, const Overrides& overrides) {
    const Scene effective = with_overrides(scene, overrides);
    refuse_tunnelling(effective); // a tunnel would pass unseen: refused, not run
    // Scales the engine cannot resolve: a contact band as wide as a body, and
    // (time-stepping) a per-step fall or initial travel beyond the contact
    // tolerance's reach.
    refuse_contact_band_beyond_bodies(effective);
    refuse_unresolvable_step_fall(effective);
    refuse_unresolvable_step_speed(effective);
    std::unique_ptr<Simulator> simulator = make_impulse_simulator(effective);
    Trajectory trajectory = record(*simulator, effective);
    const std::string used = overrides_list(overrides);
    if (!used.empty()) {
        trajectory.solver.emplace_back("overrides", used);
    }
    return trajectory;
}

} // namespace impulse::harness
