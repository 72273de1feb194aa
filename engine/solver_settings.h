// How the engine models a scene (DESIGN.md, the solver table). Each variant is
// one enum value and one case where it is used; the seed's value comes first.
#pragma once

namespace impulse {

enum class Integrator { euler, symplectic_euler, verlet, rk4 };
inline constexpr int integrator_count = 4;

enum class TimeOfImpactMethod { bisection };
inline constexpr int time_of_impact_method_count = 1;

enum class ContactMode { single };
inline constexpr int contact_mode_count = 1;

struct SolverSettings {
    Integrator integrator = Integrator::euler;
    TimeOfImpactMethod toi = TimeOfImpactMethod::bisection;
    double toi_tolerance = 1e-12;    // seconds
    double contact_tolerance = 1e-9; // metres
    ContactMode contacts = ContactMode::single;
    bool ccd = false;
    bool resting = false;
    // Work bounds that turn a stall into a clear error instead of a hang.
    int max_halvings = 200; // per time-of-impact search
    int max_collisions_per_step = 4096;
};

} // namespace impulse
