#include "text.h"

#include "number_format.h"

#include <cmath>
#include <cstdio>

namespace impulse::harness {

std::string single_quoted(const std::string& name) {
    return "'" + name + "'";
}

std::string double_quoted(const std::string& text) {
    return "\"" + text + "\"";
}

std::string lower_case(std::string text) {
    for (char& c : text) {
        if (c >= 'A' && c <= 'Z') {
            c = static_cast<char>(c - 'A' + 'a');
        }
    }
    return text;
}

std::string plural(std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string padded(std::string text, std::size_t width, bool right) {
    if (text.size() < width) {
        text = right ? std::string(width - text.size(), ' ') + text
                     : text + std::string(width - text.size(), ' ');
    }
    return text;
}

std::string fixed_text(double value, int digits) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
    return buffer;
}

std::string sentence_number(double value) {
    if (std::isnan(value)) {
        return "NaN";
    }
    if (std::isinf(value)) {
        return value > 0.0 ? "inf" : "-inf";
    }
    return format_double(value);
}

} // namespace impulse::harness
