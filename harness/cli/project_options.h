// What the verbs share about the project they work in (docs/project-file.md):
// the folders no verb but bless writes into, and how a list of engines is named in a header line.
#pragma once

#include "project.h"

#include <optional>
#include <string>
#include <vector>

namespace impulse::harness::cli {

// The project's goldens folder, ROOT/goldens and ./goldens (goldens_folders).
std::vector<std::string> protected_folders(const Project& project);
// "impulse, fast" for a header line.
std::string engine_names(const std::vector<EngineSpec>& engines);

} // namespace impulse::harness::cli
