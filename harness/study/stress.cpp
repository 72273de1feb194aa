// The stress matrix (stress.h): running a case, up-front refusal included.
// The invariants are measured by stress_monitor.cpp, the cases built by
// stress_cases.cpp.
#include "stress.h"

#include "input_error.h"
#include "progress.h"
#include "simulator.h"

#include <algorithm>
#include <chrono>
#include <memory>

namespace impulse::harness {

bool StressResult::passed() const {
    if (expected_refusal) {
        return refused_as_expected;
    }
    return refusal.empty() && stopped.empty() &&
           std::all_of(rows.begin(), rows.end(), [](const StressRow& r) { return r.passed; });
}

namespace {

// An InputError's text without the "FILE: " it starts with: a case is named
// by its row already.
std::string without_file(const std::string& message, const std::string& file) {
    const std::string prefix = file + ": ";
    return message.compare(0, prefix.size(), prefix) == 0 ? message.substr(prefix.size()) : message;
}

} // namespace

StressResult run_stress_case(const StressCase& stress_case) {
    const auto started = std::chrono::steady_clock::now();
    const Scene& scene = stress_case.scene;
    StressResult result;
    result.name = stress_case.name;
    result.description = stress_case.description;
    result.expected_refusal = !stress_case.expected_refusal.empty();
    const auto finish = [&] {
        result.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        return result;
    };

    const auto refuse = [&](const std::string& refusal) {
        result.refusal = refusal;
        result.refused_as_expected =
            result.expected_refusal &&
            result.refusal.find(stress_case.expected_refusal) != std::string::npos;
        return finish();
    };
    if (const std::optional<TunnellingRefusal> r = tunnelling_refusal(scene)) {
        return refuse(r->path + ": " + r->message);
    }
    std::unique_ptr<Simulator> simulator;
    try {
        simulator = make_impulse_simulator(scene);
    } catch (const InputError& error) {
        return refuse(without_file(error.what(), scene.file));
    }

    StressMonitor monitor(scene, stress_case.checks);
    std::vector<BodyState> states(scene.bodies.size());
    const auto read_states = [&] {
        for (std::size_t i = 0; i < states.size(); ++i) {
            states[i] = simulator->state(static_cast<int>(i));
        }
    };
    read_states();
    monitor.observe(0.0, states);
    const long long steps = step_count(scene);
    try {
        for (long long k = 0; k < steps; ++k) {
            simulator->step(static_cast<double>(k) * scene.dt, scene.dt);
            for (const TrajectoryEvent& event : simulator->take_events()) {
                monitor.observe(event);
                ++result.collisions;
            }
            read_states();
            monitor.observe(static_cast<double>(k + 1) * scene.dt, states);
            note_simulated_time(static_cast<double>(k + 1) * scene.dt, scene.duration);
            ++result.steps;
        }
    } catch (const InputError& error) {
        result.stopped = without_file(error.what(), scene.file);
    }
    result.rows = monitor.rows();
    return finish();
}

} // namespace impulse::harness
