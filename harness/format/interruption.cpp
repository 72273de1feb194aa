#include "interruption.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <mutex>
#include <pthread.h>
#include <sys/wait.h>
#include <unistd.h>

namespace impulse::harness {

namespace {

// Fixed slots, so the handler reads them without allocating or locking (it
// may run on any thread, between any two instructions). `check -j N` runs at
// most N engines at once; a registration with no free slot is simply not
// protected (the normal path still kills and removes everything).
constexpr int slot_count = 64;

std::array<std::atomic<pid_t>, slot_count> groups{};

struct FolderSlot {
    std::atomic<bool> live{false};
    std::array<char, PATH_MAX> folder{};
    std::array<char, PATH_MAX> file{};
};
std::array<FolderSlot, slot_count> folder_slots{};
std::mutex claiming; // registrations only; never taken by the handler

// Async-signal-safe throughout: kill, waitpid, unlink, rmdir, signal, raise.
// Each group is reaped before the harness ends (it is their parent, or their
// subreaper), so no engine process outlives it, not even for a moment.
void on_interrupt(int signal) {
    const int saved_errno = errno;
    for (std::atomic<pid_t>& group : groups) {
        const pid_t g = group.load();
        if (g > 0) {
            ::kill(-g, SIGKILL);
            while (::waitpid(-g, nullptr, 0) > 0 || errno == EINTR) {
            }
        }
    }
    for (FolderSlot& slot : folder_slots) {
        if (slot.live.load()) {
            ::unlink(slot.file.data());
            if (slot.folder[0] != '\0') { // a file alone has no folder of its own
                ::rmdir(slot.folder.data());
            }
        }
    }
    std::signal(signal, SIG_DFL);
    std::raise(signal); // delivered when the handler returns: the harness ends as signalled
    errno = saved_errno;
}

// Installed over a default action at each registration, not once: the
// process (or a child forked from it) may have set a signal back to its
// default since. A harness that ignores the signal (nohup) keeps ignoring
// it, and a program with its own handler keeps that.
void install_over_defaults() {
    for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction before {};
        ::sigaction(signal, nullptr, &before);
        if (before.sa_handler != SIG_DFL) {
            continue;
        }
        struct sigaction action {};
        action.sa_handler = on_interrupt;
        sigemptyset(&action.sa_mask);
        for (const int other : {SIGINT, SIGTERM, SIGHUP}) {
            sigaddset(&action.sa_mask, other); // one cleanup at a time
        }
        ::sigaction(signal, &action, nullptr);
    }
}

bool fits(const std::string& path) {
    return path.size() < PATH_MAX;
}

// A slot holding `file` and its `folder` ("" for a file alone), or -1 when
// none is free or a path is too long (the normal path still removes them).
int claim_folder_slot(const std::string& folder, const std::string& file) {
    install_over_defaults();
    if (!fits(folder) || !fits(file)) {
        return -1;
    }
    const std::lock_guard<std::mutex> lock(claiming);
    for (int i = 0; i < slot_count; ++i) {
        FolderSlot& slot = folder_slots[static_cast<std::size_t>(i)];
        if (!slot.live.load()) {
            std::memcpy(slot.folder.data(), folder.c_str(), folder.size() + 1);
            std::memcpy(slot.file.data(), file.c_str(), file.size() + 1);
            slot.live.store(true); // the paths are complete before the handler may read them
            return i;
        }
    }
    return -1;
}

void release_folder_slot(int slot) {
    if (slot >= 0) {
        folder_slots[static_cast<std::size_t>(slot)].live.store(false);
    }
}

} // namespace

InterruptibleGroup::InterruptibleGroup(pid_t group) : slot_(-1) {
    install_over_defaults();
    const std::lock_guard<std::mutex> lock(claiming);
    for (int i = 0; i < slot_count; ++i) {
        if (groups[static_cast<std::size_t>(i)].load() == 0) {
            groups[static_cast<std::size_t>(i)].store(group);
            slot_ = i;
            return;
        }
    }
}

InterruptibleGroup::~InterruptibleGroup() {
    if (slot_ >= 0) {
        groups[static_cast<std::size_t>(slot_)].store(0);
    }
}

HeldInterrupts::HeldInterrupts() : before_{} {
    install_over_defaults();
    sigset_t interrupts;
    sigemptyset(&interrupts);
    for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
        sigaddset(&interrupts, signal);
    }
    ::pthread_sigmask(SIG_BLOCK, &interrupts, &before_);
}

HeldInterrupts::~HeldInterrupts() {
    ::pthread_sigmask(SIG_SETMASK, &before_, nullptr);
}

InterruptibleFolder::InterruptibleFolder(const std::string& folder, const std::string& file)
    : slot_(claim_folder_slot(folder, file)) {}

InterruptibleFolder::~InterruptibleFolder() {
    release_folder_slot(slot_);
}

InterruptibleFile::InterruptibleFile(const std::string& file)
    : slot_(claim_folder_slot("", file)) {}

InterruptibleFile::~InterruptibleFile() {
    release_folder_slot(slot_);
}

} // namespace impulse::harness
