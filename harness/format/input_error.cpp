#include "input_error.h"

#include <cstdio>

namespace impulse::harness {

namespace {

std::string hex_escape(unsigned char byte) {
    char text[5];
    std::snprintf(text, sizeof text, "\\x%02x", static_cast<unsigned>(byte));
    return text;
}

// The length of the well-formed UTF-8 sequence at `at` (RFC 3629: no overlong
// forms, no surrogates, nothing past U+10FFFF), or 0 when there is none.
std::size_t utf8_length(const std::string& text, std::size_t at) {
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[at + i]); };
    const unsigned char lead = byte(0);
    std::size_t length = 0;
    unsigned char low = 0x80, high = 0xBF; // the allowed range of the second byte
    if (lead < 0x80) {
        return 1;
    } else if (lead >= 0xC2 && lead <= 0xDF) {
        length = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
        length = 3;
        low = lead == 0xE0 ? 0xA0 : 0x80;
        high = lead == 0xED ? 0x9F : 0xBF;
    } else if (lead >= 0xF0 && lead <= 0xF4) {
        length = 4;
        low = lead == 0xF0 ? 0x90 : 0x80;
        high = lead == 0xF4 ? 0x8F : 0xBF;
    } else {
        return 0;
    }
    if (at + length > text.size() || byte(1) < low || byte(1) > high) {
        return 0;
    }
    for (std::size_t i = 2; i < length; ++i) {
        if ((byte(i) & 0xC0U) != 0x80U) {
            return 0;
        }
    }
    return length;
}

std::string render(const std::string& file, const std::string& json_path,
                   const std::string& message) {
    std::string out = file.empty() ? std::string("<input>") : printable_path(file);
    out += ": ";
    if (!json_path.empty()) {
        out += json_path;
        out += ": ";
    }
    out += message;
    return out;
}

} // namespace

std::string printable_path(const std::string& path) {
    std::string out;
    std::size_t at = 0;
    while (at < path.size()) {
        const auto lead = static_cast<unsigned char>(path[at]);
        const std::size_t length = utf8_length(path, at);
        if (length == 0 || lead < 0x20 || lead == 0x7F) {
            out += hex_escape(lead);
            at += 1;
        } else if (length == 2 && lead == 0xC2 && static_cast<unsigned char>(path[at + 1]) < 0xA0) {
            // U+0080..U+009F: valid UTF-8, but control characters.
            char text[7];
            std::snprintf(text, sizeof text, "\\u%04x",
                          static_cast<unsigned>(static_cast<unsigned char>(path[at + 1])));
            out += text;
            at += 2;
        } else {
            out.append(path, at, length);
            at += length;
        }
    }
    return out;
}

InputError::InputError(const std::string& file, const std::string& json_path,
                       const std::string& message)
    : std::runtime_error(render(file, json_path, message)), json_path_(json_path),
      message_(message) {}

} // namespace impulse::harness
