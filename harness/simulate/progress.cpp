#include "progress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>

namespace impulse::harness {

namespace {

// What the current run reports (note_simulated_time). One run at a time is
// shown: with check -j N the latest writer wins, which only moves the bar.
std::atomic<double> simulated_t{0.0};
std::atomic<double> simulated_duration{0.0};
std::atomic<std::size_t> drawn{0};
std::atomic<std::size_t> drawn_total{0};

double now_seconds() {
    using clock = std::chrono::steady_clock;
    return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

// About a second, so quick verbs print nothing; IMPULSE_PROGRESS_DELAY_MS for tests.
double delay_seconds() {
    const char* text = std::getenv("IMPULSE_PROGRESS_DELAY_MS");
    if (text == nullptr || *text == '\0') {
        return 1.0;
    }
    char* end = nullptr;
    const double ms = std::strtod(text, &end);
    return end != text && *end == '\0' && std::isfinite(ms) && ms >= 0.0 ? ms / 1000.0 : 1.0;
}

std::string seconds_text(double s) {
    char text[32];
    if (s < 60.0) {
        std::snprintf(text, sizeof text, "%.1f s", s);
    } else if (s < 3600.0) {
        std::snprintf(text, sizeof text, "%dm%02ds", static_cast<int>(s / 60.0),
                      static_cast<int>(std::fmod(s, 60.0)));
    } else {
        std::snprintf(text, sizeof text, "%dh%02dm", static_cast<int>(s / 3600.0),
                      static_cast<int>(std::fmod(s, 3600.0) / 60.0));
    }
    return text;
}

std::string bar(double fraction) {
    constexpr int width = 20;
    const int full = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * width);
    return "[" + std::string(static_cast<std::size_t>(full), '#') +
           std::string(static_cast<std::size_t>(width - full), '-') + "]";
}

void write_stderr(const std::string& text) {
    std::size_t written = 0;
    while (written < text.size()) {
        const ssize_t n = ::write(STDERR_FILENO, text.data() + written, text.size() - written);
        if (n <= 0) {
            return; // a bar is not worth an error
        }
        written += static_cast<std::size_t>(n);
    }
}

} // namespace

void note_simulated_time(double t, double duration) {
    simulated_t.store(t, std::memory_order_relaxed);
    simulated_duration.store(duration, std::memory_order_relaxed);
}

void note_drawn(std::size_t done, std::size_t total) {
    drawn.store(done, std::memory_order_relaxed);
    drawn_total.store(total, std::memory_order_relaxed);
}

bool progress_wanted(bool quiet) {
    return !quiet && ::isatty(STDERR_FILENO) == 1;
}

Progress::Progress(std::string verb, bool enabled) : verb_(std::move(verb)), enabled_(enabled) {
    note_simulated_time(0.0, 0.0);
    note_drawn(0, 0);
    if (enabled_) {
        started_ = now_seconds();
        thread_ = std::thread([this] { redraw_loop(); });
    }
}

Progress::~Progress() {
    if (!enabled_) {
        return;
    }
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

void Progress::set_total(std::size_t total, const char* unit) {
    unit_ = unit;
    total_.store(total);
}

void Progress::set_item(const std::string& name) {
    const std::lock_guard<std::mutex> lock(mutex_);
    item_ = name;
}

void Progress::advance() {
    ++done_;
}

std::string Progress::line(const std::string& item) const {
    const double t = simulated_t.load(std::memory_order_relaxed);
    const double duration = simulated_duration.load(std::memory_order_relaxed);
    const double run_fraction = duration > 0.0 ? std::clamp(t / duration, 0.0, 1.0) : 0.0;
    const std::size_t total = total_.load();
    const std::size_t done = std::min(done_.load(), total);
    std::string text = verb_;
    double fraction = run_fraction;
    if (total > 0) {
        text += " " + std::to_string(done) + "/" + std::to_string(total) + " " + unit_;
        fraction = (static_cast<double>(done) + (done < total ? run_fraction : 0.0)) /
                   static_cast<double>(total);
    }
    if (!item.empty()) {
        text += " " + (item.size() > 24 ? item.substr(0, 23) + "~" : item);
    }
    if (duration > 0.0) {
        char sim[64];
        std::snprintf(sim, sizeof sim, " t %.3g/%.3g s", t, duration);
        text += sim;
    }
    // render: after the run (if any), the drawing of each body's path.
    if (const std::size_t paths = drawn_total.load(std::memory_order_relaxed); paths > 0) {
        const std::size_t done_paths = std::min(drawn.load(std::memory_order_relaxed), paths);
        text += " drawn " + std::to_string(done_paths) + "/" + std::to_string(paths) + " paths";
        fraction = static_cast<double>(done_paths) / static_cast<double>(paths);
    }
    const double elapsed = now_seconds() - started_;
    text += " " + bar(fraction) + " " + seconds_text(elapsed);
    if (fraction > 0.0 && fraction < 1.0) {
        text += ", ~" + seconds_text(elapsed * (1.0 - fraction) / fraction) + " left";
    }
    return text;
}

void Progress::erase_locked() {
    if (drawn_) {
        write_stderr("\r\x1b[K");
        drawn_ = false;
    }
}

void Progress::redraw_loop() {
    const double delay = delay_seconds();
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
        // Redrawn five times a second once the delay has passed.
        const double waited = now_seconds() - started_;
        const double pause = waited < delay ? std::min(delay - waited, 0.2) : 0.2;
        wake_.wait_for(lock, std::chrono::duration<double>(pause), [this] { return stop_; });
        if (stop_ || now_seconds() - started_ < delay) {
            continue;
        }
        // \r back to the start, \x1b[K clears what a longer line left.
        write_stderr("\r" + line(item_) + "\x1b[K");
        drawn_ = true;
    }
    // With no delay (IMPULSE_PROGRESS_DELAY_MS=0) the bar is drawn once more
    // as the work ends, with the final state, so a test sees it however fast
    // or slow the work was.
    if (delay == 0.0) {
        write_stderr("\r" + line(item_) + "\x1b[K");
        drawn_ = true;
    }
    erase_locked();
}

} // namespace impulse::harness
