// The report page's embedded JSON (page_json.h).
#include "page_json.h"

#include "number_format.h"

#include <algorithm>
#include <cmath>

namespace impulse::harness {

std::string json_number(double value, int digits) {
    if (!std::isfinite(value)) {
        return "null";
    }
    return significant_text(value, digits);
}

std::string json_string(const std::string& text) {
    static const char* const hex = "0123456789abcdef";
    std::string out = "\"";
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (u < 0x20U || c == '<' || c == '>' || c == '&') {
            out += "\\u00";
            out += hex[u >> 4U];
            out += hex[u & 0xFU];
        } else {
            out += c;
        }
    }
    return out + "\"";
}

std::string json_numbers(const std::vector<double>& values, int digits) {
    std::string out = "[";
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i > 0) {
            out += ',';
        }
        out += json_number(values[i], digits);
    }
    return out + "]";
}

std::vector<std::size_t> sampled_frames(std::size_t count, std::size_t budget, std::size_t keep) {
    std::vector<std::size_t> frames;
    if (count == 0) {
        return frames;
    }
    const std::size_t stride = budget == 0 || count <= budget ? 1 : (count + budget - 1) / budget;
    for (std::size_t k = 0; k < count; k += stride) {
        frames.push_back(k);
    }
    if (frames.back() != count - 1) {
        frames.push_back(count - 1);
    }
    if (keep < count && !std::binary_search(frames.begin(), frames.end(), keep)) {
        frames.insert(std::lower_bound(frames.begin(), frames.end(), keep), keep);
    }
    return frames;
}

} // namespace impulse::harness
