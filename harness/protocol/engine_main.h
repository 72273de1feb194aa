// The rest of the engine protocol (docs/engine-protocol.md) for a C++ engine:
// the scene from the command line, the refusal of what the engine does not
// model (exit 3), and the exit codes, so that an engine's main() is one call.
#pragma once

#include "scene.h"
#include "trajectory_writer.h"

#include <functional>
#include <stdexcept>
#include <string>

namespace impulse::protocol {

// The protocol's exit code for "the scene asks for something this engine
// does not model": a skip for the harness, neither a pass nor a failure.
inline constexpr int exit_unsupported = 3;
// Anything else the engine could not do (the harness reports it as a failure).
inline constexpr int exit_failed = 1;
// The command line or the scene file was wrong.
inline constexpr int exit_bad_input = 2;

// Thrown by an engine's simulation for what it does not model; the message is
// one sentence saying what ("cpp-minimal moves circles only; 'box' is a polygon").
class Unsupported : public std::runtime_error {
  public:
    explicit Unsupported(const std::string& sentence) : std::runtime_error(sentence) {}
};

// Writes `sentence` as one line on standard error and exits with code 3.
[[noreturn]] void refuse(const std::string& sentence);

// What an engine does with a scene: fill the writer (every frame, each
// event, optionally settings and cost); throw Unsupported to refuse.
using Simulation = std::function<void(const harness::Scene&, TrajectoryWriter&)>;

// An engine's whole main(): reads the scene (argv[1], with the harness's own
// loader, harness::load_scene), runs `simulate`, writes the
// trajectory to standard output and returns the exit code: 0; 3 with the
// Unsupported sentence on standard error; 2 for a bad command line or scene;
// 1 for any other exception (its message on standard error) or a failed write.
int engine_main(int argc, const char* const* argv, const std::string& engine,
                const Simulation& simulate);

} // namespace impulse::protocol
