// A picture's legend: a swatch and a label per item, or a wrapped note.
#pragma once

#include "svg.h"
#include "tracks.h"

#include <string>
#include <vector>

namespace impulse::harness::picture {

struct LegendItem {
    enum class Kind { line, body, static_body, contact, ring, normal, divergence, note };
    Kind kind = Kind::line;
    std::string label;
    std::string colour = ink;
    std::string dash;    // stroke-dasharray; empty for a solid line
    bool wide = false;   // the golden path: wide and light
    bool circle = false; // a body's swatch: a disc rather than a square
};

// One swatch per body in its colour: a disc for a circle (or an unknown
// shape), a square otherwise.
std::vector<LegendItem> body_legend(const std::vector<Track>& tracks);

// Draws the items from (x, y) down; returns the y below the last.
double draw_legend(std::string& out, double x, double y, const std::vector<LegendItem>& items);

} // namespace impulse::harness::picture
