// Files that are either wholly old or wholly new: written to a temporary file
// beside the target, flushed, then renamed over it.
#pragma once

#include <cstddef>
#include <string>

namespace impulse::harness {

// Throws InputError naming the path unless it is missing or a regular file:
// impulse never replaces a symbolic link, FIFO, device, socket or directory.
void require_regular_or_missing(const std::string& path);

// Throws InputError naming the path when the file cannot be written, or when
// something other than a regular file is there (checked before the temporary
// file is made and again right before it is renamed over the path).
void write_file_atomically(const std::string& path, const std::string& content);

// The whole file, refusing one larger than limit_bytes (`what` completes the
// sentence, e.g. "a scene is a few kilobytes"). Throws InputError naming the
// path when it cannot be read, and anything that is not a regular file after
// symbolic links are followed (a FIFO is refused, never waited on).
std::string read_file(const std::string& path, std::size_t limit_bytes, const std::string& what);

} // namespace impulse::harness
