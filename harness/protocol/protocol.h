// Everything a C++ engine needs to speak the engine protocol
// (docs/engine-protocol.md): link impulse::protocol and include this one
// header. docs/install.md shows an engine's main() with it.
#pragma once

#include "engine_main.h"
#include "trajectory_writer.h"
