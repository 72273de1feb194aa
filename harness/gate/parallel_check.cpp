#include "parallel_check.h"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <mutex>
#include <new>
#include <thread>

namespace impulse::harness {

namespace {

std::string failure_text(const std::exception_ptr& failure) {
    try {
        std::rethrow_exception(failure);
    } catch (const std::bad_alloc&) {
        return "ran out of memory while checking this scene";
    } catch (const std::exception& e) {
        return std::string("internal error while checking this scene: ") + e.what();
    } catch (...) {
        return "internal error while checking this scene (an exception of unknown type)";
    }
}

} // namespace

SceneCheck error_row(const std::string& scene_path, const std::exception_ptr& failure) {
    SceneCheck row;
    row.scene_file = scene_path;
    row.name = std::filesystem::path(scene_path).stem().string();
    row.status = SceneCheck::Status::error;
    row.error_source = SceneCheck::ErrorSource::internal;
    row.message = scene_path + ": " + failure_text(failure);
    return row;
}

void for_each_index(std::size_t count, int jobs, const std::function<void(std::size_t)>& work) {
    const int threads_wanted = std::max(1, std::min<int>(jobs, static_cast<int>(count)));
    std::atomic<std::size_t> next{0};
    // An exception escaping a thread's function calls std::terminate, so
    // nothing may: what escapes `work` is kept and rethrown on the calling
    // thread, where the tool turns it into one sentence and exit 2.
    std::mutex kept_mutex;
    std::exception_ptr kept;
    auto worker = [&]() noexcept {
        try {
            for (std::size_t i = next++; i < count; i = next++) {
                work(i);
            }
        } catch (...) {
            const std::lock_guard<std::mutex> lock(kept_mutex);
            if (!kept) {
                kept = std::current_exception();
            }
        }
    };
    std::vector<std::thread> threads;
    for (int t = 1; t < threads_wanted; ++t) {
        try {
            threads.emplace_back(worker);
        } catch (...) {
            // No more threads (no memory for a stack, a thread limit): the
            // ones started share the work.
            break;
        }
    }
    worker();
    for (std::thread& t : threads) {
        t.join();
    }
    if (kept) {
        std::rethrow_exception(kept);
    }
}

std::vector<SceneCheck> check_each(const std::vector<std::string>& scene_paths, int jobs,
                                   const std::function<SceneCheck(const std::string&)>& check_one) {
    std::vector<SceneCheck> results(scene_paths.size());
    for_each_index(scene_paths.size(), jobs, [&](std::size_t i) {
        try {
            results[i] = check_one(scene_paths[i]);
        } catch (...) {
            // The failed check's memory is freed by now, so the row can be
            // built; a failure even the row cannot be built for (memory still
            // exhausted) escapes to for_each_index.
            results[i] = error_row(scene_paths[i], std::current_exception());
        }
    });
    return results;
}

} // namespace impulse::harness
