// Checking scenes on several threads (`check -j N`): results in the order
// given, identical for any number of threads.
#pragma once

#include "report.h"

#include <exception>
#include <functional>
#include <string>
#include <vector>

namespace impulse::harness {

// Runs check_one for every scene path on up to `jobs` threads.
std::vector<SceneCheck> check_each(const std::vector<std::string>& scene_paths, int jobs,
                                   const std::function<SceneCheck(const std::string&)>& check_one);

} // namespace impulse::harness
