// An engine the harness runs scenes in (docs/engine-protocol.md): this
// engine, Box2D, or any program that speaks the protocol. Everything above
// this layer (the gate, the study, the reports) asks run_engine for a
// trajectory and never names a simulator.
#pragma once

#include "run.h"
#include "scene.h"
#include "trajectory.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

struct EngineSpec {
    // impulse: this engine, in process; box2d: Box2D 2.4.1 with friction off,
    // in process; chipmunk: Chipmunk2D 7.0.3 with friction off, in process
    // (docs/references.md); external: a program run through the protocol.
    enum class Kind { impulse, box2d, chipmunk, external };
    Kind kind = Kind::impulse;
    // Names the engine in messages and rows, and its goldens folder when a
    // project has several engines: letters, digits and -_. (as a scene name).
    std::string name = "impulse";
    // external: the program and its arguments; the scene's path is appended.
    std::vector<std::string> command;
    // external: the folder the command runs in (the project file's folder).
    std::string working_directory = ".";
    // external: seconds one scene may take before the process group is killed.
    double time_limit = 60.0;
    // Where the engine was declared ("impulse.json: engines[1]"), for messages.
    std::string origin;
    // Scenes (by name) this engine is not asked to run: each is unsupported
    // by it, as if it had exited 3 (docs/project-file.md, "skip").
    std::vector<std::string> skip;
};

// An engine's own measure of its work (the trajectory's "cost" block).
struct EngineCost {
    double seconds = 0.0;
    std::optional<long long> steps;
};

struct EngineRun {
    // unsupported: the engine refused the scene's settings (exit 3); a skip.
    enum class Outcome { ran, unsupported };
    Outcome outcome = Outcome::ran;
    // ran: validated against the scene, scene and scene_sha256 the harness's
    // own (of the scene before overrides), overrides in the solver block.
    Trajectory trajectory;
    std::string message;            // unsupported: the engine's sentence
    std::optional<EngineCost> cost; // when the engine reported one
    double seconds = 0.0;           // wall time of the run (the process, for external)
    // box2d: one sentence per body whose speed hits Box2D's per-step clamp.
    std::vector<std::string> warnings;
};

EngineSpec impulse_engine();
EngineSpec box2d_engine();
EngineSpec chipmunk_engine();

// Throws InputError, one sentence naming where the engine was declared
// (impulse.json: engines[i].command[0], or --engine-command), when an outside
// engine's program is not there to start: checked once before any scene
// runs, so a wrong command is one sentence, not one error row per scene.
// Nothing for the engines in process.
void require_startable(const EngineSpec& engine);

// Runs `scene` (with `overrides` applied) in `engine`. Throws InputError with
// one sentence naming the engine, the scene and the engine's own message for
// any failure but a refusal of unsupported settings.
EngineRun run_engine(const EngineSpec& engine, const Scene& scene, const Overrides& overrides = {});

} // namespace impulse::harness
