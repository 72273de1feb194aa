// The pictures' primitives (svg.h).
#include "svg.h"

#include "markup.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <system_error>

namespace impulse::harness::picture {

namespace {

std::string without_trailing_zeros(std::string text) {
    if (text.find('.') != std::string::npos && text.find('e') == std::string::npos) {
        while (!text.empty() && text.back() == '0') {
            text.pop_back();
        }
        if (!text.empty() && text.back() == '.') {
            text.pop_back();
        }
    }
    if (text == "-0") {
        text = "0";
    }
    return text;
}

} // namespace

// A picture coordinate or length: two decimals, trailing zeros dropped.
std::string f2(double value) {
    if (!std::isfinite(value)) {
        value = 0.0;
    }
    value = std::clamp(value, -1e6, 1e6);
    char buffer[64];
    const auto result =
        std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, 2);
    return without_trailing_zeros(std::string(buffer, result.ptr));
}

// A number for people: at most `digits` significant digits ("0.7667", "3", "1.5e-07").
std::string readable(double value, int digits) {
    if (std::isnan(value)) {
        return "NaN";
    }
    if (std::isinf(value)) {
        return value > 0 ? "inf" : "-inf";
    }
    char buffer[64];
    const auto result =
        std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, digits);
    std::string text(buffer, result.ptr);
    return text == "-0" ? "0" : text;
}

std::string attr(const char* name, const std::string& value) {
    return std::string(" ") + name + "=\"" + value + "\"";
}

std::string esc(const std::string& text) {
    return xml_escape(text, false);
}

void open_svg(std::string& out, double width, double height) {
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\"" + attr("width", f2(width)) +
           attr("height", f2(height)) + attr("viewBox", "0 0 " + f2(width) + " " + f2(height)) +
           " font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n";
    out += "<rect class=\"background\"" + attr("width", f2(width)) + attr("height", f2(height)) +
           " fill=\"#ffffff\"/>\n";
}

// `extra` is further attributes, each starting with a space.
void text_at(std::string& out, double x, double y, const std::string& content, double size,
             const char* fill, const std::string& extra) {
    out += "<text" + attr("x", f2(x)) + attr("y", f2(y)) + attr("font-size", f2(size)) +
           attr("fill", fill) + extra + ">" + esc(content) + "</text>\n";
}

// Greedy word wrap to at most `width` characters a line (UTF-8 aware enough:
// continuation bytes do not count).
std::vector<std::string> wrap(const std::string& text, std::size_t width) {
    auto length = [](const std::string& s) {
        std::size_t n = 0;
        for (const char c : s) {
            n += (static_cast<unsigned char>(c) & 0xC0U) != 0x80U ? 1 : 0;
        }
        return n;
    };
    std::vector<std::string> lines;
    std::string line;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find_first_of(" \n", start);
        if (end == std::string::npos) {
            end = text.size();
        }
        const std::string word = text.substr(start, end - start);
        if (!word.empty()) {
            if (!line.empty() && length(line) + 1 + length(word) > width) {
                lines.push_back(line);
                line.clear();
            }
            line += (line.empty() ? "" : " ") + word;
        }
        if (end < text.size() && text[end] == '\n' && !line.empty()) {
            lines.push_back(line);
            line.clear();
        }
        start = end + 1;
    }
    if (!line.empty()) {
        lines.push_back(line);
    }
    return lines;
}

std::string shortened(const std::string& text, std::size_t width) {
    if (text.size() <= width) {
        return text;
    }
    std::size_t cut = width - 1;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U) {
        --cut;
    }
    return text.substr(0, cut) + "\u2026";
}

// Title, wrapped description lines and a grey information line; returns the y below them.
double draw_title(std::string& out, double width, const std::string& title,
                  const std::vector<std::string>& paragraphs,
                  const std::vector<std::string>& info) {
    double y = pad + title_size;
    text_at(out, pad, y, title, title_size, ink, " font-weight=\"bold\" class=\"title\"");
    const auto columns = static_cast<std::size_t>(std::max(20.0, (width - 2 * pad) / char_width));
    for (const std::string& paragraph : paragraphs) {
        for (const std::string& line : wrap(paragraph, columns)) {
            y += 17.0;
            text_at(out, pad, y, line, text_size, "#444444", " class=\"description\"");
        }
    }
    for (const std::string& line : info) {
        y += 15.0;
        text_at(out, pad, y, line, small_size, muted, " class=\"info\"");
    }
    return y + 22.0;
}

std::string svg_document(double width, double height, const std::string& body) {
    std::string out;
    open_svg(out, width, height);
    out += body;
    out += "</svg>\n";
    return out;
}

} // namespace impulse::harness::picture
