// The one way the harness reports bad input: a sentence naming the file and
// the JSON path. The command-line tool prints it and exits with code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace impulse::harness {

class InputError : public std::runtime_error {
  public:
    // Renders "FILE: PATH: MESSAGE" (or "FILE: MESSAGE" when path is empty).
    InputError(const std::string& file, const std::string& json_path, const std::string& message);
};

} // namespace impulse::harness
