// Files that are either wholly old or wholly new: written to a temporary file
// beside the target, flushed, then renamed over it.
#pragma once

#include <cstddef>
#include <string>

namespace impulse::harness {

// Throws InputError naming the path when the file cannot be written.
void write_file_atomically(const std::string& path, const std::string& content);

// The whole file, refusing one larger than limit_bytes (`what` completes the
// sentence, e.g. "a scene is a few kilobytes"). Throws InputError naming the
// path when it cannot be read.
std::string read_file(const std::string& path, std::size_t limit_bytes, const std::string& what);

} // namespace impulse::harness
