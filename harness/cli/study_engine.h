// The engine a study verb (box2d, sweep) puts under study, from its command
// line: the one place that turns --engine NAME into an EngineSpec, so the
// project file's engines can be added here once and both verbs know them.
#pragma once

#include "cli.h"
#include "engine.h"

#include <optional>
#include <string>

namespace impulse::harness::cli {

// The options study_engine(const Arguments&) reads, for parse_arguments.
// --engine-command is not in the verbs' help: it stands in for the project
// file's engines (docs/engine-protocol.md) until those are wired in.
inline constexpr const char* engine_option = "--engine";
inline constexpr const char* engine_command_option = "--engine-command";

// An engine this tool knows by name: "impulse" (also when no name is given)
// or "box2d". Throws UsageError naming --engine for any other name.
EngineSpec study_engine(const std::optional<std::string>& name);

// --engine NAME, or --engine-command 'PROGRAM ARGS' (split on spaces, run in
// the current folder through the protocol) named by --engine NAME (letters,
// digits, '.', '_', '-'; "external" by default). Throws UsageError.
EngineSpec study_engine(const Arguments& arguments);

} // namespace impulse::harness::cli
