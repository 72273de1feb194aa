// --engine-command 'PROGRAM ARGS' as words, the way a POSIX shell splits a
// simple command, with nothing expanded: the one reading of that string for
// every verb and for init (docs/engine-protocol.md, "The command").
#pragma once

#include <string>
#include <vector>

namespace impulse::harness::cli {

// Words separated by unquoted blanks (space, tab, newline). Inside '...'
// every character is kept as it is; inside "..." a backslash keeps a
// following '"', '\', '$' or '`' and is kept itself before any other
// character; outside quotes a backslash keeps the character after it (a
// backslash-newline joins lines). Quotes make a word even when empty ('').
// No variables, globs, '~' or operators: '$HOME', '*', '|' and ';' are
// characters of words. Throws UsageError naming --engine-command for an
// unclosed quote, a trailing backslash, or no word at all.
std::vector<std::string> command_words(const std::string& command);

} // namespace impulse::harness::cli
