// Progress of long work on a terminal (docs/refusals-and-progress.md): a bar
// on standard error with what is being done, the simulated time (or items
// done of a total), the wall time spent and an estimate of what is left.
//
// Drawn only when standard error is a terminal and --quiet was not given,
// only after about a second of work (IMPULSE_PROGRESS_DELAY_MS overrides the
// delay, for tests), and by a small background thread from atomic state, so a
// single step that takes 17 s still shows the clock moving. It never writes
// to standard output and never changes a result: the work only stores two
// doubles per step (note_simulated_time). Erased when done.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>

namespace impulse::harness {

// record() calls this after every step: the time reached and the run's
// duration. Relaxed atomic stores; nothing is drawn from here.
void note_simulated_time(double t, double duration);

// render calls this as it draws each body's path: how many of how many.
void note_drawn(std::size_t done, std::size_t total);

// true when a bar would be drawn: standard error is a terminal and not `quiet`.
bool progress_wanted(bool quiet);

class Progress {
  public:
    // `verb` heads the line ("check"); `enabled` comes from progress_wanted.
    Progress(std::string verb, bool enabled);
    ~Progress(); // stops the thread and erases the bar
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // Work counted in items ("scenes", "points", "cases"): how many in all.
    void set_total(std::size_t total, const char* unit);
    // The item now being worked on (a scene's name), shown on the line.
    void set_item(const std::string& name);
    // One more item done.
    void advance();

    // Runs `write` (which prints to standard output, and must flush) with the
    // bar erased and not redrawn meanwhile: on a terminal both streams share
    // the screen, and a row must not land after a half-drawn bar.
    template <typename Write> void without_bar(const Write& write) {
        const std::lock_guard<std::mutex> lock(mutex_);
        erase_locked();
        write();
    }

  private:
    void redraw_loop();
    void erase_locked();
    std::string line(const std::string& item) const;

    const std::string verb_;
    const bool enabled_;
    std::atomic<std::size_t> total_{0};
    std::atomic<std::size_t> done_{0};
    const char* unit_ = "";
    std::mutex mutex_; // guards item_, stop_, drawn_ and every write of the bar
    std::string item_;
    bool stop_ = false;
    bool drawn_ = false; // the bar is on the screen now
    std::condition_variable wake_;
    double started_ = 0.0; // steady clock, seconds
    std::thread thread_;
};

} // namespace impulse::harness
