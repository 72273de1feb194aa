#include "atomic_file.h"

#include "input_error.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

namespace impulse::harness {

namespace {
std::string reason() {
    return std::strerror(errno);
}
} // namespace

void write_file_atomically(const std::string& path, const std::string& content) {
    // Same directory as the target, so rename() cannot cross file systems.
    std::string temp = path + ".tmp-XXXXXX";
    const int fd = mkstemp(temp.data());
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
    // mkstemp creates 0600; give the file the usual permissions.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
    if (::fsync(fd) != 0 || ::close(fd) != 0 || std::rename(temp.c_str(), path.c_str()) != 0) {
        const std::string why = reason();
        std::remove(temp.c_str());
        throw InputError(path, "", "cannot be written (" + why + ")");
    }
}

// "No such file or directory" reads better mid-sentence as "no such ...".
std::string lower_first(std::string text) {
    if (!text.empty() && text[0] >= 'A' && text[0] <= 'Z') {
        text[0] = static_cast<char>(text[0] - 'A' + 'a');
    }
    return text;
}

std::string read_file(const std::string& path, std::size_t limit_bytes, const std::string& what) {
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (error) {
        throw InputError(path, "", "cannot be read (" + lower_first(error.message()) + ")");
    }
    if (fs::is_directory(status)) {
        throw InputError(path, "", "cannot be read (it is a directory)");
    }
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        // libstdc++ and libc++ open through the C library, which sets errno.
        const std::string why =
            errno != 0 ? std::generic_category().message(errno) : "it could not be opened";
        throw InputError(path, "", "cannot be read (" + lower_first(why) + ")");
    }
    // Read at most one byte past the limit, so a huge file is refused without reading it all.
    std::string text;
    // Reserved once: a string that doubles as it grows holds up to three
    // times the file for a moment (docs/memory.md).
    std::error_code size_error;
    const std::uintmax_t size = fs::file_size(path, size_error);
    if (!size_error) {
        text.reserve(static_cast<std::size_t>(std::min<std::uintmax_t>(size, limit_bytes) + 1));
    }
    char buffer[65536];
    while (in && text.size() <= limit_bytes) {
        in.read(buffer, sizeof buffer);
        text.append(buffer, static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) {
        throw InputError(path, "", "cannot be read (an I/O error occurred while reading)");
    }
    if (text.size() > limit_bytes) {
        throw InputError(path, "",
                         "is too large: more than " + std::to_string(limit_bytes / (1024 * 1024)) +
                             " MiB; " + what);
    }
    return text;
}

} // namespace impulse::harness
