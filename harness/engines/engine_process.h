// Running an engine's command as the protocol says (docs/engine-protocol.md,
// "One run"): in its own process group, standard input empty, standard output
// and error read without ever blocking on a pipe, within a time limit and a
// size limit, and nothing left behind: the process is reaped and whatever it
// left running in its group is killed.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness {

struct ProcessRequest {
    std::vector<std::string> command; // program (looked up in PATH without a '/') and arguments
    std::string working_directory = ".";
    double time_limit = 60.0;     // seconds of wall time before the group is killed
    std::size_t output_limit = 0; // bytes of standard output before the group is killed
};

// Standard error is kept to its last this many bytes.
inline constexpr std::size_t kept_error_bytes = 64 * 1024;

struct ProcessResult {
    // Set when the command could not be started at all ("cannot start
    // 'engine/run': No such file or directory"); nothing else is then set.
    std::optional<std::string> not_started;
    std::optional<int> exit_code; // when it exited by itself
    std::optional<int> signal;    // when a signal ended it (not the harness's kill)
    bool timed_out = false;       // the time limit passed; the group was killed
    bool overflowed = false;      // it wrote more than output_limit; the group was killed
    std::string output;           // standard output (at most output_limit bytes)
    std::string error_tail;       // the last kept_error_bytes of standard error
    double seconds = 0.0;         // wall time from start to reaping
};

// Runs request.command; never throws for what the process does, only for a
// failure of this process's own (pipes, memory).
ProcessResult run_process(const ProcessRequest& request);

// Why `command` could not start in `working_directory`, found the way
// run_process's posix_spawnp finds it (a word with a '/' is a path from that
// folder, a bare word is looked up in PATH), without running it: the same
// text as ProcessResult::not_started, or nothing when a program is there to
// run. A program that is there but fails as it starts (a missing
// interpreter) passes here and is caught when it runs.
std::optional<std::string> start_problem(const std::vector<std::string>& command,
                                         const std::string& working_directory);

// The last non-empty line of `text` that is not a runtime's trailer to an
// uncaught exception (indented "at ..." stack frames, Node's "Node.js vN"
// line; the last non-empty line when every line is one), control characters
// replaced by '?' and cut to `max_chars` characters (with "..." when cut): an
// engine's message.
std::string last_line(const std::string& text, std::size_t max_chars);

} // namespace impulse::harness
