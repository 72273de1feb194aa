// The engine a verb that runs one engine works with (run, render, box2d,
// sweep, conform): the one place that turns --engine and --engine-command
// into an EngineSpec (docs/project-file.md, "Choosing the engine").
#pragma once

#include "cli.h"
#include "engine.h"
#include "project.h"

namespace impulse::harness::cli {

// The options chosen_engine reads, for parse_arguments.
inline constexpr const char* engine_option = "--engine";
inline constexpr const char* engine_command_option = "--engine-command";

// --engine-command 'PROGRAM ARGS' (split into words as a shell would, run through the engine
// protocol in the current folder), named by --engine NAME ("external" when
// not given); else --engine NAME: the project's engine of that name, or the
// built-in impulse, box2d or chipmunk; else the project's first engine. Throws
// UsageError or InputError (an unknown name, listing the known ones; a
// program that is not there to start, require_startable).
EngineSpec chosen_engine(const Project& project, const Arguments& arguments);

} // namespace impulse::harness::cli
