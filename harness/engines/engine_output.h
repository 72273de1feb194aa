// Reading what an external engine wrote on standard output
// (docs/engine-protocol.md, "The trajectory the engine writes"): as strictly
// as a scene is read, and against the scene it was given, so that what comes
// back is a trajectory the gate can trust; then put in canonical form, the
// harness's own names, fingerprint and digest in place of the engine's.
#pragma once

#include "engine.h"
#include "scene.h"
#include "trajectory.h"

#include <optional>
#include <string>

namespace impulse::harness {

struct EngineOutput {
    // scene and scene_sha256 of `scene` (before overrides), engine the
    // engine's own string or the spec's name, solver the engine's block plus
    // the overrides as run_scene records them.
    Trajectory trajectory;
    std::optional<EngineCost> cost;
};

// What the output is checked against and how it is named.
struct OutputContext {
    std::string engine_name; // the spec's name: messages, and the default "engine"
    const Scene* scene;      // as loaded: its name, file and fingerprint
    const Scene* received;   // what the engine was given (overrides applied)
    std::string overrides;   // overrides_list() of the overrides, "" for none
};

// Throws InputError "engine 'NAME' on SCENE-FILE: output PATH: MESSAGE" for
// the first thing wrong, in document order.
EngineOutput read_engine_output(const std::string& text, const OutputContext& context);

// "engine 'NAME' on SCENE-FILE": how a message names one run.
std::string engine_run_label(const std::string& engine_name, const Scene& scene);

} // namespace impulse::harness
