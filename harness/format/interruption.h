// What an interrupted harness leaves behind: nothing. An engine runs in its
// own process group (so its misbehaviour cannot signal the harness), which
// also means a Ctrl-C or a CI cancel (SIGINT, SIGTERM, SIGHUP) reaches the
// harness alone. While an engine runs or a file is being written, those
// signals first kill every live engine group, remove every private scene
// folder and every half-written temporary file, then end the harness as the
// signal would have (exit status 128 + the signal's number in a shell). The
// handler is installed only over the default action: a program that links
// this library and handles these signals itself keeps its handler.
#pragma once

#include <csignal>
#include <string>
#include <sys/types.h>

namespace impulse::harness {

// An engine's process group, killed if the harness is interrupted while it
// lives. Register it right after the spawn; the destructor forgets it (the
// group is reaped by then).
class InterruptibleGroup {
  public:
    explicit InterruptibleGroup(pid_t group);
    ~InterruptibleGroup();
    InterruptibleGroup(const InterruptibleGroup&) = delete;
    InterruptibleGroup& operator=(const InterruptibleGroup&) = delete;

  private:
    int slot_;
};

// INT, TERM and HUP held back on this thread while it lives, then delivered:
// around a spawn and its registration, so that no signal finds an engine
// started and not yet registered.
class HeldInterrupts {
  public:
    HeldInterrupts();
    ~HeldInterrupts();
    HeldInterrupts(const HeldInterrupts&) = delete;
    HeldInterrupts& operator=(const HeldInterrupts&) = delete;

  private:
    sigset_t before_;
};

// A private folder holding one file, both removed if the harness is
// interrupted while it lives (the owner removes them otherwise).
class InterruptibleFolder {
  public:
    InterruptibleFolder(const std::string& folder, const std::string& file);
    ~InterruptibleFolder();
    InterruptibleFolder(const InterruptibleFolder&) = delete;
    InterruptibleFolder& operator=(const InterruptibleFolder&) = delete;

  private:
    int slot_;
};

// A temporary file being written beside its target (write_file_atomically),
// removed if the harness is interrupted while it lives: an outside review
// found `NAME.tmp-XXXXXX` of up to 69 MB left by a SIGTERM during the write,
// in the goldens folder when bless was writing.
class InterruptibleFile {
  public:
    explicit InterruptibleFile(const std::string& file);
    ~InterruptibleFile();
    InterruptibleFile(const InterruptibleFile&) = delete;
    InterruptibleFile& operator=(const InterruptibleFile&) = delete;

  private:
    int slot_;
};

} // namespace impulse::harness
