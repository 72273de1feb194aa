// One place for the protocol's exit codes and streams, so that every C++
// engine gets them right: nothing but the trajectory on standard output, and
// at most one sentence on standard error.
#include "engine_main.h"

#include "input_error.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>

namespace impulse::protocol {

namespace {

int say(const std::string& sentence, int code) {
    std::cerr << sentence << '\n' << std::flush;
    return code;
}

// The whole text, or false when standard output fails (a closed pipe, a full
// disk): the harness must not mistake a cut trajectory for a finished one.
bool write_stdout(const std::string& text) {
    return std::fwrite(text.data(), 1, text.size(), stdout) == text.size() &&
           std::fflush(stdout) == 0;
}

} // namespace

void refuse(const std::string& sentence) {
    say(sentence, exit_unsupported);
    std::exit(exit_unsupported);
}

int engine_main(int argc, const char* const* argv, const std::string& engine,
                const Simulation& simulate) {
    if (argc != 2) {
        const std::string program = argc > 0 ? argv[0] : engine;
        return say("usage: " + program + " SCENE.json (an impulse engine: docs/engine-protocol.md)",
                   exit_bad_input);
    }
    harness::Scene scene;
    try {
        scene = harness::load_scene(argv[1]);
    } catch (const harness::InputError& error) {
        return say(error.what(), exit_bad_input);
    } catch (const std::exception& error) {
        return say(engine + ": " + error.what(), exit_failed);
    }
    std::string text;
    try {
        TrajectoryWriter writer(scene, engine);
        simulate(scene, writer);
        text = writer.text();
    } catch (const Unsupported& refusal) {
        return say(refusal.what(), exit_unsupported);
    } catch (const std::exception& error) {
        return say(engine + ": " + error.what(), exit_failed);
    }
    if (!write_stdout(text)) {
        return say(engine + ": could not write the trajectory to standard output", exit_failed);
    }
    return 0;
}

} // namespace impulse::protocol
