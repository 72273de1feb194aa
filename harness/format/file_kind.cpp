#include "file_kind.h"

#include <sys/stat.h>

namespace impulse::harness {

FileKind kind_of_mode(mode_t mode) {
    if (S_ISREG(mode)) {
        return FileKind::regular;
    }
    if (S_ISDIR(mode)) {
        return FileKind::directory;
    }
    if (S_ISLNK(mode)) {
        return FileKind::symbolic_link;
    }
    if (S_ISFIFO(mode)) {
        return FileKind::fifo;
    }
    if (S_ISCHR(mode)) {
        return FileKind::character_device;
    }
    if (S_ISBLK(mode)) {
        return FileKind::block_device;
    }
    if (S_ISSOCK(mode)) {
        return FileKind::socket;
    }
    return FileKind::other;
}

FileKind kind_at(const std::string& path) {
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0) {
        return FileKind::missing;
    }
    return kind_of_mode(info.st_mode);
}

const char* kind_words(FileKind kind) {
    switch (kind) {
    case FileKind::missing:
        return "missing";
    case FileKind::regular:
        return "a regular file";
    case FileKind::directory:
        return "a directory";
    case FileKind::symbolic_link:
        return "a symbolic link";
    case FileKind::fifo:
        return "a FIFO";
    case FileKind::character_device:
        return "a character device";
    case FileKind::block_device:
        return "a block device";
    case FileKind::socket:
        return "a socket";
    case FileKind::other:
        break;
    }
    return "a special file";
}

} // namespace impulse::harness
