#include "number_format.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <system_error>

namespace impulse::harness {

namespace {

bool is_digit(char c) {
    return c >= '0' && c <= '9';
}

// Advances `i` past a run of digits; returns how many there were.
std::size_t skip_digits(const std::string& text, std::size_t& i) {
    const std::size_t start = i;
    while (i < text.size() && is_digit(text[i])) {
        ++i;
    }
    return i - start;
}

// The JSON number grammar (RFC 8259 section 6). std::from_chars alone would
// also take "inf", "nan", ".5" and "1.", none of which is JSON.
bool is_json_number(const std::string& text) {
    std::size_t i = 0;
    if (i < text.size() && text[i] == '-') {
        ++i;
    }
    if (i < text.size() && text[i] == '0') {
        ++i; // a leading zero stands alone: "01" is not a number
    } else if (skip_digits(text, i) == 0) {
        return false;
    }
    if (i < text.size() && text[i] == '.') {
        ++i;
        if (skip_digits(text, i) == 0) {
            return false;
        }
    }
    if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
            ++i;
        }
        if (skip_digits(text, i) == 0) {
            return false;
        }
    }
    return i == text.size();
}

} // namespace

std::string format_double(double value) {
    if (std::isnan(value)) {
        throw std::logic_error("format_double: NaN cannot be written as JSON; the caller must "
                               "reject non-finite values before writing");
    }
    if (std::isinf(value)) {
        throw std::logic_error("format_double: infinity cannot be written as JSON; the caller "
                               "must reject non-finite values before writing");
    }
    if (value == 0.0 && std::signbit(value)) {
        return "-0.0";
    }
    // The longest shortest form is 24 characters ("-2.2250738585072014e-308");
    // fixed notation is only chosen when it is shorter than scientific.
    char buffer[32];
    const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
    if (result.ec != std::errc()) {
        throw std::logic_error("format_double: std::to_chars failed");
    }
    return std::string(buffer, result.ptr);
}

std::string significant_text(double value, int digits) {
    if (std::isnan(value)) {
        return "NaN";
    }
    if (std::isinf(value)) {
        return value > 0.0 ? "inf" : "-inf";
    }
    char buffer[64];
    const std::to_chars_result result =
        std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general,
                      std::clamp(digits, 1, 17));
    if (result.ec != std::errc()) {
        throw std::logic_error("significant_text: std::to_chars failed");
    }
    return std::string(buffer, result.ptr);
}

bool parse_double(const std::string& text, double& value) {
    if (!is_json_number(text)) {
        return false;
    }
    double parsed = 0.0;
    const char* first = text.data();
    const char* last = first + text.size();
    const std::from_chars_result result = std::from_chars(first, last, parsed);
    // result_out_of_range covers both overflow and underflow to zero.
    if (result.ec != std::errc() || result.ptr != last || !std::isfinite(parsed)) {
        return false;
    }
    value = parsed;
    return true;
}

} // namespace impulse::harness
