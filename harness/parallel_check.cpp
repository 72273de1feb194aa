#include "parallel_check.h"

#include <algorithm>
#include <atomic>
#include <thread>

namespace impulse::harness {

std::vector<SceneCheck> check_each(const std::vector<std::string>& scene_paths, int jobs,
                                   const std::function<SceneCheck(const std::string&)>& check_one) {
    std::vector<SceneCheck> results(scene_paths.size());
    const int threads_wanted =
        std::max(1, std::min<int>(jobs, static_cast<int>(scene_paths.size())));
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
        for (std::size_t i = next++; i < scene_paths.size(); i = next++) {
            results[i] = check_one(scene_paths[i]);
        }
    };
    std::vector<std::thread> threads;
    for (int t = 1; t < threads_wanted; ++t) {
        threads.emplace_back(worker);
    }
    worker();
    for (std::thread& t : threads) {
        t.join();
    }
    return results;
}

} // namespace impulse::harness
