// Escaping text for XML 1.0, the markup every picture and report is written in.
#include "markup.h"

#include <cstddef>

namespace impulse::harness {

std::string xml_escape(const std::string& text, bool attribute) {
    static const char* const replacement = "\xEF\xBF\xBD"; // U+FFFD
    std::string out;
    out.reserve(text.size());
    const std::size_t n = text.size();
    auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
    auto continuation = [&](std::size_t i, unsigned lo, unsigned hi) {
        return i < n && byte(i) >= lo && byte(i) <= hi;
    };
    for (std::size_t i = 0; i < n;) {
        const unsigned char c = byte(i);
        if (c < 0x80U) {
            switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            case '\n':
                out += attribute ? "&#10;" : "\n";
                break;
            case '\t':
                out += attribute ? "&#9;" : "\t";
                break;
            case '\r':
                out += "&#13;";
                break;
            default:
                if (c < 0x20U) {
                    out += replacement; // not allowed in XML 1.0, not even as a reference
                } else {
                    out += static_cast<char>(c);
                }
            }
            ++i;
            continue;
        }
        // A well-formed UTF-8 sequence is copied; anything else becomes U+FFFD.
        std::size_t length = 0;
        if (c >= 0xC2U && c <= 0xDFU) {
            length = continuation(i + 1, 0x80, 0xBF) ? 2 : 0;
        } else if (c >= 0xE0U && c <= 0xEFU) {
            const unsigned lo = c == 0xE0U ? 0xA0 : 0x80;
            const unsigned hi = c == 0xEDU ? 0x9F : 0xBF; // no surrogates
            length = continuation(i + 1, lo, hi) && continuation(i + 2, 0x80, 0xBF) ? 3 : 0;
            // U+FFFE and U+FFFF are not XML characters either.
            if (length == 3 && c == 0xEFU && byte(i + 1) == 0xBFU && byte(i + 2) >= 0xBEU) {
                length = 0;
                i += 2;
            }
        } else if (c >= 0xF0U && c <= 0xF4U) {
            const unsigned lo = c == 0xF0U ? 0x90 : 0x80;
            const unsigned hi = c == 0xF4U ? 0x8F : 0xBF;
            length = continuation(i + 1, lo, hi) && continuation(i + 2, 0x80, 0xBF) &&
                             continuation(i + 3, 0x80, 0xBF)
                         ? 4
                         : 0;
        }
        if (length == 0) {
            out += replacement;
            ++i;
        } else {
            out.append(text, i, length);
            i += length;
        }
    }
    return out;
}

} // namespace impulse::harness
