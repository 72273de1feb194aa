#include "input_error.h"

namespace impulse::harness {

namespace {
std::string render(const std::string& file, const std::string& json_path,
                   const std::string& message) {
    std::string out = file.empty() ? std::string("<input>") : file;
    out += ": ";
    if (!json_path.empty()) {
        out += json_path;
        out += ": ";
    }
    out += message;
    return out;
}
} // namespace

InputError::InputError(const std::string& file, const std::string& json_path,
                       const std::string& message)
    : std::runtime_error(render(file, json_path, message)) {}

} // namespace impulse::harness
