#include "engine.h"

#include "input_error.h"

#include <chrono>

namespace impulse::harness {

EngineSpec impulse_engine() {
    EngineSpec spec;
    spec.kind = EngineSpec::Kind::impulse;
    spec.name = "impulse";
    return spec;
}

EngineSpec box2d_engine() {
    EngineSpec spec;
    spec.kind = EngineSpec::Kind::box2d;
    spec.name = "box2d";
    return spec;
}

EngineRun run_engine(const EngineSpec& engine, const Scene& scene, const Overrides& overrides) {
    const auto start = std::chrono::steady_clock::now();
    EngineRun result;
    switch (engine.kind) {
    case EngineSpec::Kind::impulse:
        result.trajectory = run_scene(scene, overrides);
        break;
    case EngineSpec::Kind::box2d:
    case EngineSpec::Kind::external:
        // Filled in by the protocol runner (external_engine.cpp).
        throw InputError(scene.file, "", "engine '" + engine.name + "' cannot be run yet");
    }
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

} // namespace impulse::harness
