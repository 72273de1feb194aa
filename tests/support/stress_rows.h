// What the stress tests share: a scene's bodies as the monitor's states, and a
// monitor's row by the start of its invariant's name.
#pragma once

#include "stress.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

namespace impulse::test {

inline std::vector<BodyState> states_of(const harness::Scene& scene) {
    std::vector<BodyState> states;
    for (const harness::SceneBody& body : scene.bodies) {
        states.push_back({body.position, body.angle, body.velocity, body.angular_velocity});
    }
    return states;
}

// The row whose invariant starts with `name`; fails the test when there is none.
inline harness::StressRow row_of(const std::vector<harness::StressRow>& rows,
                                 const std::string& name) {
    for (const harness::StressRow& row : rows) {
        if (row.invariant.rfind(name, 0) == 0) {
            return row;
        }
    }
    FAIL("no row '" << name << "'");
    return {};
}

inline bool passes(const harness::StressMonitor& monitor, const std::string& name) {
    return row_of(monitor.rows(), name).passed;
}

} // namespace impulse::test
