// Checking scenes on several threads (`check -j N`): results in the order
// given, identical for any number of threads, and one scene's failure never
// takes the others or the process down.
#pragma once

#include "scene_check.h"

#include <cstddef>
#include <exception>
#include <functional>
#include <string>
#include <vector>

namespace impulse::harness {

// Calls work(i) for every i in [0, count) on up to `jobs` threads (fewer when
// the system refuses to start more). An exception escaping `work` is rethrown
// on the calling thread once every thread has stopped, never std::terminate.
void for_each_index(std::size_t count, int jobs, const std::function<void(std::size_t)>& work);

// Runs check_one for every scene path on up to `jobs` threads (fewer when the
// system refuses to start more). Any exception escaping check_one becomes
// that scene's ERROR row (see error_row), whichever thread ran it.
std::vector<SceneCheck> check_each(const std::vector<std::string>& scene_paths, int jobs,
                                   const std::function<SceneCheck(const std::string&)>& check_one);

// The ERROR row of a scene whose check threw: "PATH: ran out of memory while
// checking this scene" for std::bad_alloc, "PATH: internal error while
// checking this scene: WHAT" for any other exception.
SceneCheck error_row(const std::string& scene_path, const std::exception_ptr& failure);

} // namespace impulse::harness
