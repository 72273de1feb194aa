#include "atomic_file.h"

#include "file_kind.h"
#include "input_error.h"
#include "interruption.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <optional>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace impulse::harness {

namespace {
std::string reason() {
    return std::strerror(errno);
}

// "No such file or directory" reads better mid-sentence as "no such ...".
std::string lower_first(std::string text) {
    if (!text.empty() && text[0] >= 'A' && text[0] <= 'Z') {
        text[0] = static_cast<char>(text[0] - 'A' + 'a');
    }
    return text;
}

// Closed on every way out, so a refusal never leaks the descriptor.
struct Descriptor {
    int fd = -1;
    ~Descriptor() {
        if (fd >= 0) {
            ::close(fd);
        }
    }
};

[[noreturn]] void refuse_to_read(const std::string& path, FileKind kind) {
    if (kind == FileKind::directory) {
        throw InputError(path, "", "cannot be read (it is a directory)");
    }
    throw InputError(path, "",
                     std::string("cannot be read (it is ") + kind_words(kind) +
                         "; impulse reads only regular files)");
}
} // namespace

void require_regular_or_missing(const std::string& path) {
    const FileKind kind = kind_at(path);
    if (kind != FileKind::missing && kind != FileKind::regular) {
        throw InputError(path, "",
                         std::string("cannot be written (it is ") + kind_words(kind) +
                             "; impulse writes only regular files)");
    }
}

void write_file_atomically(const std::string& path, const std::string& content) {
    require_regular_or_missing(path);
    // Same directory as the target, so rename() cannot cross file systems;
    // mkstemp creates it with O_EXCL, so it is never something already there.
    std::string temp = path + ".tmp-XXXXXX";
    std::optional<InterruptibleFile> removed_if_interrupted;
    int fd = -1;
    {
        const HeldInterrupts held; // no interrupt between making it and registering it
        fd = mkstemp(temp.data());
        if (fd >= 0) {
            removed_if_interrupted.emplace(temp);
        }
    }
    if (fd < 0) {
        throw InputError(path, "", "cannot be written (" + reason() + ")");
    }
    const char* data = content.data();
    std::size_t left = content.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, data, left);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            const std::string why = reason();
            ::close(fd);
            std::remove(temp.c_str());
            throw InputError(path, "", "cannot be written (" + why + ")");
        }
        data += n;
        left -= static_cast<std::size_t>(n);
    }
    // mkstemp creates 0600. A file replaced keeps its permissions (a golden
    // the team made group-writable stays so); a new one gets the usual ones.
    struct stat old {};
    if (::stat(path.c_str(), &old) == 0 && S_ISREG(old.st_mode)) {
        ::fchmod(fd, old.st_mode & 07777);
    } else {
        const mode_t mask = ::umask(0);
        ::umask(mask);
        ::fchmod(fd, 0666 & ~mask);
    }
    if (::fsync(fd) != 0 || ::close(fd) != 0) {
        const std::string why = reason();
        std::remove(temp.c_str());
        throw InputError(path, "", "cannot be written (" + why + ")");
    }
    // Something may have appeared at the path while the file was written.
    try {
        require_regular_or_missing(path);
    } catch (const InputError&) {
        std::remove(temp.c_str());
        throw;
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        const std::string why = reason();
        std::remove(temp.c_str());
        throw InputError(path, "", "cannot be written (" + why + ")");
    }
}

std::string read_file(const std::string& path, std::size_t limit_bytes, const std::string& what) {
    // Looked at before opening: opening a FIFO could block and opening a
    // device could do anything.
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) {
        throw InputError(path, "", "cannot be read (" + lower_first(reason()) + ")");
    }
    if (!S_ISREG(info.st_mode)) {
        refuse_to_read(path, kind_of_mode(info.st_mode));
    }
    // Non-blocking and checked again on the descriptor: the path may have
    // been replaced by a FIFO since it was looked at.
    Descriptor file;
    file.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (file.fd < 0) {
        throw InputError(path, "", "cannot be read (" + lower_first(reason()) + ")");
    }
    if (::fstat(file.fd, &info) != 0) {
        throw InputError(path, "", "cannot be read (" + lower_first(reason()) + ")");
    }
    if (!S_ISREG(info.st_mode)) {
        refuse_to_read(path, kind_of_mode(info.st_mode));
    }
    // Read at most one byte past the limit, so a huge file is refused without reading it all.
    std::string text;
    // Reserved once: a string that doubles as it grows holds up to three
    // times the file for a moment (docs/memory.md).
    const auto size = static_cast<std::uintmax_t>(info.st_size);
    text.reserve(static_cast<std::size_t>(std::min<std::uintmax_t>(size, limit_bytes) + 1));
    char buffer[65536];
    while (text.size() <= limit_bytes) {
        const ssize_t n = ::read(file.fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n < 0) {
            throw InputError(path, "",
                             "cannot be read (an I/O error occurred while reading: " +
                                 lower_first(reason()) + ")");
        }
        if (n == 0) {
            break;
        }
        text.append(buffer, static_cast<std::size_t>(n));
    }
    if (text.size() > limit_bytes) {
        throw InputError(path, "",
                         "is too large: more than " + std::to_string(limit_bytes / (1024 * 1024)) +
                             " MiB; " + what);
    }
    return text;
}

} // namespace impulse::harness
