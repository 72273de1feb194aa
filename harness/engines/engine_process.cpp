// The process side of the engine protocol. Everything here is POSIX (with
// Linux's child subreaper where there is one) and written so that no engine,
// however it misbehaves, can hang the harness or leave a process behind:
// pipes are read with poll(), the engine's exit is noticed while a grandchild
// still holds its pipes open, and the whole process group is killed and
// reaped before the run returns.
#include "engine_process.h"

#include "input_error.h"
#include "interruption.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <optional>
#include <poll.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <system_error>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

extern char** environ; // NOLINT: POSIX declares it nowhere else

namespace impulse::harness {

namespace {

using Clock = std::chrono::steady_clock;

// How often the engine's exit is looked for while its pipes stay open, and
// how long the pipes are drained after its process group is gone (only a
// process that left the group can still hold them).
constexpr int poll_slice_ms = 10;
constexpr int drain_wait_ms = 100;
// However much such a process writes, the drain stops after this long.
constexpr auto longest_drain = std::chrono::seconds(1);
constexpr double max_time_limit = 1e9;

[[noreturn]] void fail_system(const std::string& what) {
    throw std::system_error(errno, std::generic_category(), what);
}

// A pipe's read end, closed when done; `open` until end of file.
struct Reader {
    int fd = -1;
    bool open() const { return fd >= 0; }
    void close() {
        if (fd >= 0) {
            ::close(fd);
            fd = -1;
        }
    }
};

// Orphans of the engine become children of this process instead of init's
// (which, in a container, may never reap them), so the group's leftovers can
// be reaped here and are really gone when the run returns.
void become_subreaper() {
#ifdef __linux__
    static const bool done = ::prctl(PR_SET_CHILD_SUBREAPER, 1) == 0;
    (void)done;
#endif
}

void make_pipe(int ends[2]) {
    if (::pipe2(ends, O_CLOEXEC) != 0) {
        fail_system("cannot create a pipe for the engine");
    }
    ::fcntl(ends[0], F_SETFL, ::fcntl(ends[0], F_GETFL) | O_NONBLOCK);
}

// Why a command word may not start, when the word says: a whole command line
// given as one word ("build/engine --fast"), or a bare name looked up in PATH.
std::string start_hint(const std::string& program, int code) {
    if (code != ENOENT) {
        return "";
    }
    if (program.find_first_of(" \t") != std::string::npos) {
        return "; the word holds a space, and a command is one word per element, as "
               "[\"build/engine\", \"--fast\"]";
    }
    if (program.find('/') == std::string::npos) {
        return "; a word without a '/' is looked up in PATH (write ./" + program +
               " for a file in the working directory)";
    }
    return "";
}

std::string cannot_start(const std::string& program, int code) {
    if (code == EISDIR) {
        return "cannot start '" + printable_path(program) + "': it is a folder, not a program";
    }
    return "cannot start '" + printable_path(program) + "': " + std::strerror(code) +
           start_hint(program, code);
}

// 0 when `path` names a file this process may execute, else the errno execve
// would give, except EISDIR for a folder (execve's EACCES would say
// "Permission denied" of something no permission makes a program).
int execute_error(const std::string& path) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) {
        return errno;
    }
    if (S_ISDIR(info.st_mode)) {
        return EISDIR;
    }
    return ::access(path.c_str(), X_OK) == 0 ? 0 : errno;
}

// posix_spawnp in a new process group, stdin /dev/null, stdout and stderr the
// pipes, in the working directory; the error text when it cannot start.
std::optional<std::string> spawn(const ProcessRequest& request, int out, int err, pid_t& pid) {
    posix_spawn_file_actions_t actions;
    posix_spawnattr_t attributes;
    ::posix_spawn_file_actions_init(&actions);
    ::posix_spawnattr_init(&attributes);
    ::posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    ::posix_spawn_file_actions_adddup2(&actions, out, 1);
    ::posix_spawn_file_actions_adddup2(&actions, err, 2);
    ::posix_spawn_file_actions_addchdir_np(&actions, request.working_directory.c_str());
    ::posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK |
                                                POSIX_SPAWN_SETSIGDEF);
    ::posix_spawnattr_setpgroup(&attributes, 0);
    sigset_t signals;
    sigemptyset(&signals);
    ::posix_spawnattr_setsigmask(&attributes, &signals);
    for (const int signal : {SIGPIPE, SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGCHLD}) {
        sigaddset(&signals, signal);
    }
    ::posix_spawnattr_setsigdefault(&attributes, &signals);
    std::vector<char*> argv;
    for (const std::string& word : request.command) {
        argv.push_back(const_cast<char*>(word.c_str()));
    }
    argv.push_back(nullptr);
    const int code = ::posix_spawnp(&pid, argv[0], &actions, &attributes, argv.data(), environ);
    ::posix_spawn_file_actions_destroy(&actions);
    ::posix_spawnattr_destroy(&attributes);
    if (code == 0) {
        return std::nullopt;
    }
    // posix_spawnp says EACCES of a folder too: the search says what it is.
    if (code == EACCES) {
        if (std::optional<std::string> why =
                start_problem(request.command, request.working_directory)) {
            return why;
        }
    }
    return cannot_start(request.command.front(), code);
}

// Reads what is there without blocking; false at end of file.
bool read_some(Reader& reader, std::string& into) {
    char block[65536];
    for (;;) {
        const ssize_t got = ::read(reader.fd, block, sizeof block);
        if (got > 0) {
            into.append(block, static_cast<std::size_t>(got));
            return true;
        }
        if (got == 0) {
            reader.close();
            return false;
        }
        if (errno == EINTR) {
            continue;
        }
        if (errno == EAGAIN || errno == EWOULDBLOCK) {
            return true;
        }
        reader.close(); // a broken pipe reads as its end
        return false;
    }
}

// The state of one run while its pipes are read.
class Run {
  public:
    Run(const ProcessRequest& request, pid_t pid, int out, int err)
        : request_(request), pid_(pid), out_{out}, err_{err} {
        interruptible_.emplace(pid);
    }

    // Waits for the engine to exit, reading its pipes, killing its group at
    // the time limit or the output limit; then kills and reaps the group.
    ProcessResult finish(Clock::time_point start) {
        // Clamped so that the conversion cannot overflow: a limit of 30 years is none.
        const double limit = std::clamp(request_.time_limit, 0.0, max_time_limit);
        const Clock::time_point deadline =
            start + std::chrono::duration_cast<Clock::duration>(
                        std::chrono::duration<double>(std::isnan(limit) ? 0.0 : limit));
        while (!exited()) {
            const auto left =
                std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
            if (left.count() <= 0) {
                result_.timed_out = true;
                break;
            }
            pump(static_cast<int>(std::min<long long>(left.count(), poll_slice_ms)));
            if (result_.overflowed) {
                break;
            }
        }
        kill_group(); // the leader is a zombie until reaped, so its group id is still its own
        interruptible_.reset(); // before the reap frees the group id for reuse
        const int status = reap_leader();
        reaped_ = true;
        result_.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        reap_group();
        drain();
        record(status);
        return std::move(result_);
    }

    // Should anything above throw before the engine was reaped, it is killed
    // and reaped here all the same: no run leaves a process or a zombie.
    ~Run() {
        if (!reaped_) {
            kill_group();
            interruptible_.reset();
            int status = 0;
            while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
            }
            reap_group();
        }
        out_.close();
        err_.close();
    }

  private:
    // True once the engine has exited, without reaping it.
    bool exited() {
        siginfo_t info{};
        for (;;) {
            if (::waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOHANG | WNOWAIT) == 0) {
                return info.si_pid == pid_;
            }
            if (errno != EINTR) {
                fail_system("cannot wait for the engine");
            }
        }
    }

    // One poll of the open pipes, at most `timeout_ms`.
    void pump(int timeout_ms) {
        pollfd fds[2];
        nfds_t count = 0;
        for (Reader* reader : {&out_, &err_}) {
            if (reader->open()) {
                fds[count++] = pollfd{reader->fd, POLLIN, 0};
            }
        }
        const int ready = ::poll(count == 0 ? nullptr : fds, count, timeout_ms);
        if (ready < 0 && errno != EINTR) {
            fail_system("cannot poll the engine's output");
        }
        if (ready > 0) {
            read_pipes();
        }
    }

    void read_pipes() {
        if (out_.open()) {
            read_some(out_, result_.output);
            if (result_.output.size() > request_.output_limit) {
                result_.overflowed = true;
                result_.output.resize(request_.output_limit);
                out_.close();
            }
        }
        if (err_.open()) {
            read_some(err_, result_.error_tail);
            if (result_.error_tail.size() > 2 * kept_error_bytes) {
                result_.error_tail.erase(0, result_.error_tail.size() - kept_error_bytes);
            }
        }
    }

    void kill_group() const { ::kill(-pid_, SIGKILL); }

    int reap_leader() const {
        int status = 0;
        while (::waitpid(pid_, &status, 0) < 0) {
            if (errno != EINTR) {
                fail_system("cannot reap the engine");
            }
        }
        return status;
    }

    // What the engine left in its group was killed; as this process is their
    // subreaper, they are reaped here (ECHILD: none of ours is left).
    void reap_group() const {
        int status = 0;
        while (::waitpid(-pid_, &status, 0) > 0 || errno == EINTR) {
        }
    }

    // What the pipes still hold; only a process outside the group can keep
    // them open now, and it is not waited for.
    void drain() {
        const Clock::time_point end = Clock::now() + longest_drain;
        while ((out_.open() || err_.open()) && !result_.overflowed && Clock::now() < end) {
            pollfd fds[2];
            nfds_t count = 0;
            for (Reader* reader : {&out_, &err_}) {
                if (reader->open()) {
                    fds[count++] = pollfd{reader->fd, POLLIN, 0};
                }
            }
            const int ready = ::poll(fds, count, drain_wait_ms);
            if (ready == 0) {
                break;
            }
            if (ready > 0) {
                read_pipes();
            }
        }
        if (result_.error_tail.size() > kept_error_bytes) {
            result_.error_tail.erase(0, result_.error_tail.size() - kept_error_bytes);
        }
    }

    void record(int status) {
        if (result_.timed_out || result_.overflowed) {
            return; // the harness's own SIGKILL is not the engine's signal
        }
        if (WIFEXITED(status)) {
            result_.exit_code = WEXITSTATUS(status);
        } else if (WIFSIGNALED(status)) {
            result_.signal = WTERMSIG(status);
        }
    }

    const ProcessRequest& request_;
    pid_t pid_;
    Reader out_;
    Reader err_;
    ProcessResult result_;
    bool reaped_ = false;
    // Killed by the harness's SIGINT, SIGTERM or SIGHUP while registered.
    std::optional<InterruptibleGroup> interruptible_;
};

} // namespace

std::optional<std::string> start_problem(const std::vector<std::string>& command,
                                         const std::string& working_directory) {
    const std::string& program = command.front();
    const auto from_folder = [&](const std::string& path) {
        return !path.empty() && path.front() == '/' ? path : working_directory + "/" + path;
    };
    if (program.empty()) {
        return cannot_start(program, ENOENT);
    }
    if (program.find('/') != std::string::npos) {
        const int code = execute_error(from_folder(program));
        return code == 0 ? std::nullopt : std::optional<std::string>(cannot_start(program, code));
    }
    // execvp's search: each PATH entry in turn (an empty one is the working
    // folder; glibc's default when PATH is unset), EACCES if some candidate
    // was there but not executable and none was.
    const char* path_variable = std::getenv("PATH");
    const std::string search = path_variable != nullptr ? path_variable : "/bin:/usr/bin";
    int code = ENOENT;
    std::size_t begin = 0;
    for (;;) {
        const std::size_t end = search.find(':', begin);
        const std::string folder = search.substr(begin, end - begin);
        const int here =
            execute_error(from_folder((folder.empty() ? "." : folder) + "/" + program));
        if (here == 0) {
            return std::nullopt;
        }
        code = here == EACCES || here == EISDIR ? here : code;
        if (end == std::string::npos) {
            break;
        }
        begin = end + 1;
    }
    return cannot_start(program, code);
}

ProcessResult run_process(const ProcessRequest& request) {
    ProcessResult result;
    if (request.command.empty()) {
        result.not_started = "the command is empty";
        return result;
    }
    struct stat folder {};
    if (::stat(request.working_directory.c_str(), &folder) != 0 || !S_ISDIR(folder.st_mode)) {
        result.not_started = "its working directory '" + printable_path(request.working_directory) +
                             "' is not a folder";
        return result;
    }
    become_subreaper();
    int out[2];
    int err[2];
    make_pipe(out);
    make_pipe(err);
    const Clock::time_point start = Clock::now();
    pid_t pid = 0;
    std::optional<Run> run;
    {
        const HeldInterrupts held; // until the engine's group is registered (Run)
        result.not_started = spawn(request, out[1], err[1], pid);
        ::close(out[1]);
        ::close(err[1]);
        if (result.not_started) {
            ::close(out[0]);
            ::close(err[0]);
            return result;
        }
        run.emplace(request, pid, out[0], err[0]);
    }
    return run->finish(start);
}

namespace {

// What a runtime writes after an uncaught exception's own line: indented
// stack frames ("    at f (engine.js:10:5)", Node's and Java's) and Node's
// closing "Node.js v20.19.2". Found by a helper that wrote a Node engine:
// every crash was reported as "Node.js v20".
bool runtime_trailer(const std::string& raw, const std::string& trimmed) {
    const bool indented = !raw.empty() && (raw[0] == ' ' || raw[0] == '\t');
    if (indented && trimmed.rfind("at ", 0) == 0) {
        return true;
    }
    const std::string banner = "Node.js v";
    return trimmed.rfind(banner, 0) == 0 && trimmed.size() > banner.size() &&
           std::isdigit(static_cast<unsigned char>(trimmed[banner.size()])) != 0 &&
           trimmed.find(' ', banner.size()) == std::string::npos;
}

} // namespace

std::string last_line(const std::string& text, std::size_t max_chars) {
    std::size_t end = text.size();
    std::string line;
    std::string fallback; // the last non-empty line, when every line is a trailer
    while (end > 0 && line.empty()) {
        const std::size_t newline = text.rfind('\n', end - 1);
        const std::size_t begin = newline == std::string::npos ? 0 : newline + 1;
        const std::string raw = text.substr(begin, end - begin);
        line = raw;
        line.erase(line.find_last_not_of(" \t\r\f\v") + 1);
        line.erase(0, std::min(line.size(), line.find_first_not_of(" \t")));
        end = newline == std::string::npos ? 0 : newline;
        if (!line.empty() && runtime_trailer(raw, line)) {
            if (fallback.empty()) {
                fallback = line;
            }
            line.clear();
        }
    }
    if (line.empty()) {
        line = fallback;
    }
    for (char& c : line) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7f) {
            c = '?';
        }
    }
    line = printable_path(line); // broken UTF-8 as \xNN: a message is always valid text
    // Cut at a character boundary: never inside a UTF-8 sequence.
    std::size_t chars = 0;
    for (std::size_t i = 0; i < line.size(); ++i) {
        if ((static_cast<unsigned char>(line[i]) & 0xC0U) != 0x80U && chars++ == max_chars) {
            return line.substr(0, i) + "...";
        }
    }
    return line;
}

} // namespace impulse::harness
