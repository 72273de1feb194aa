// An engine that did not do its part: it would not start, exited with an
// error, ran out of time, or wrote output that is not a trajectory of the
// scene. Bad input to the harness like any other (exit 2, one sentence), but
// the engine's rather than the scene's, so a report can tell a CI user which
// of the two to look at (JUnit's type "engine error", not "input error").
#pragma once

#include "input_error.h"

namespace impulse::harness {

class EngineFailure : public InputError {
  public:
    using InputError::InputError;
    // The same sentence, found while reading the engine's output.
    explicit EngineFailure(const InputError& cause) : InputError(cause) {}

    // Exit status 1: by the protocol, the engine's model cannot go on with
    // this scene (a cascade it cannot end), not a broken engine. A sweep
    // marks that one grid point failed and goes on, as for impulse's stops.
    bool model_stopped = false;
};

} // namespace impulse::harness
