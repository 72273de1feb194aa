// What is at a path, told without opening it: the harness reads and writes
// only regular files, and a message names anything else for what it is.
#pragma once

#include <string>
#include <sys/types.h>

namespace impulse::harness {

enum class FileKind {
    missing, // nothing there, or nothing that can be looked at
    regular,
    directory,
    symbolic_link,
    fifo,
    character_device,
    block_device,
    socket,
    other
};

// The kind a stat() mode says.
FileKind kind_of_mode(mode_t mode);

// What is at `path` itself (lstat: a final symbolic link is not followed).
// Any failure to look is `missing`: the write or read that follows reports it.
FileKind kind_at(const std::string& path);

// "a FIFO", "a symbolic link", ... for a sentence.
const char* kind_words(FileKind kind);

} // namespace impulse::harness
