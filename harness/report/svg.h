// The primitives every picture is built from, written by hand as text:
// numbers for SVG, attributes, text, the document, the shared layout and
// colours. Internal to the pictures (namespace picture).
//
// Coordinates are written with two decimals (a hundredth of a pixel) and
// nothing depends on the clock, the locale or addresses, so the same input
// always gives the same bytes.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace impulse::harness::picture {

// A picture coordinate or length: two decimals, trailing zeros dropped.
std::string f2(double value);
// A number for people: at most `digits` significant digits ("0.7667", "3", "1.5e-07").
std::string readable(double value, int digits = 4);

// ` name="value"`: value must already be escaped.
std::string attr(const char* name, const std::string& value);
// Text content made safe (markup.h).
std::string esc(const std::string& text);
// The <svg> element and its white background.
void open_svg(std::string& out, double width, double height);
// `extra` is further attributes, each starting with a space.
void text_at(std::string& out, double x, double y, const std::string& content, double size,
             const char* fill, const std::string& extra = "");
// Greedy word wrap to at most `width` characters a line (UTF-8 aware enough:
// continuation bytes do not count).
std::vector<std::string> wrap(const std::string& text, std::size_t width);
// At most `width` bytes, an ellipsis marking a cut.
std::string shortened(const std::string& text, std::size_t width);

// ---- layout -------------------------------------------------------------------

inline constexpr double pad = 18.0;         // around everything
inline constexpr double axis_left = 44.0;   // room for the y tick labels
inline constexpr double axis_bottom = 34.0; // room for the x tick labels and the axis name
inline constexpr double legend_gap = 26.0;
inline constexpr double legend_width = 200.0;
inline constexpr double title_size = 18.0;
inline constexpr double text_size = 12.0;
inline constexpr double small_size = 10.5;
inline constexpr double char_width = 6.9; // DejaVu Sans at 12 px, on average
inline constexpr const char* ink = "#222222";
inline constexpr const char* muted = "#666666";
inline constexpr const char* grid_colour = "#ebebeb";
inline constexpr const char* static_fill = "#c9c9c9";
inline constexpr const char* static_stroke = "#9a9a9a";
inline constexpr const char* event_colour = "#111111";
inline constexpr const char* divergence_colour = "#e0115f";

// Colours told apart in print and by most colour-blind readers; grey is kept
// for static bodies.
inline constexpr std::array<const char*, 9> palette = {"#1f77b4", "#e8710a", "#2ca02c",
                                                       "#9467bd", "#d62728", "#17becf",
                                                       "#8c564b", "#e377c2", "#bcbd22"};

// Title, wrapped description lines and a grey information line; returns the y below them.
double draw_title(std::string& out, double width, const std::string& title,
                  const std::vector<std::string>& paragraphs, const std::vector<std::string>& info);

// The closing tag after the body, the document around it.
std::string svg_document(double width, double height, const std::string& body);

} // namespace impulse::harness::picture
