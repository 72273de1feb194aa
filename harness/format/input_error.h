// The one way the harness reports bad input: a sentence naming the file and
// the JSON path. The command-line tool prints it and exits with code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace impulse::harness {

// A file name fit for a message: valid UTF-8 is kept; a byte that is not part
// of valid UTF-8, and a control character, is written \xNN (C1 controls as
// \u0080..\u009F), so a message is always valid text on one line.
std::string printable_path(const std::string& path);

class InputError : public std::runtime_error {
  public:
    // Renders "FILE: PATH: MESSAGE" (or "FILE: MESSAGE" when path is empty),
    // FILE through printable_path().
    InputError(const std::string& file, const std::string& json_path, const std::string& message);

    // The parts, for a caller that names the input its own way (an engine's
    // output is named by the engine and the scene, not by a file).
    const std::string& json_path() const { return json_path_; }
    const std::string& message() const { return message_; }

  private:
    std::string json_path_;
    std::string message_;
};

} // namespace impulse::harness
