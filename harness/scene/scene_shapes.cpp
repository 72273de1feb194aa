// A body's or the gas's "shape": a box, a circle or a convex polygon, checked
// so that make_polygon's assumptions hold, and recentred on its centroid.
#include "scene_reading.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace impulse::harness::scene_reading {

namespace {

constexpr int min_polygon_vertices = 3;
// A polygon whose centroid is further than this fraction of its size from the
// origin is recentred (docs/design.md: "centroid at the origin or recentred").
constexpr double centroid_tolerance = 1e-9;
// ... or further than this fraction of its least width (recentre_on_centroid).
constexpr double width_tolerance = 1e-3;

Shape read_box(const Node& node) {
    if (!node.json().is_array() || node.json().size() != 2) {
        node.fail("must be the half extents [hx, hy], got " + shown(node));
    }
    // In document order: a function's arguments are evaluated in no fixed order.
    const double hx = read_positive(node.element(0));
    const double hy = read_positive(node.element(1));
    return make_box(hx, hy);
}

// make_polygon assumes a convex counter-clockwise outline traced once; these
// checks are what make that assumption true.
void require_distinct_neighbours(const Node& node, const std::vector<Vec2>& v) {
    const std::size_t n = v.size();
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t previous = (i + n - 1) % n;
        if (v[i] == v[previous]) {
            node.element(i).fail("repeats vertex " + std::to_string(previous) +
                                 "; consecutive vertices must differ");
        }
    }
}

// A fan from the first vertex, as mass_properties integrates it: the shoelace
// sum about the origin cancels to 0 for a 0.16 m triangle given 1e8 m from
// its body's origin (found by an outside review), this does not.
double twice_area(const std::vector<Vec2>& v) {
    double sum = 0.0;
    for (std::size_t i = 1; i + 1 < v.size(); ++i) {
        sum += twice_signed_area(v[0], v[i], v[i + 1]);
    }
    return sum;
}

void require_counter_clockwise(const Node& node, const std::vector<Vec2>& v) {
    const double area = 0.5 * twice_area(v);
    if (!std::isfinite(area)) { // inf, or inf - inf: the vertices are finite
        node.fail("spans so far that its area overflows double precision; give a polygon whose "
                  "area is finite");
    }
    if (!(area > 0.0)) {
        node.fail("vertices must be counter-clockwise (positive area), got area " +
                  number_text(area));
    }
}

// Every corner turns left: cross(edge in, edge out) > 0. Zero (collinear) and
// negative (reflex) are both refused: a collinear vertex gives a zero-length
// normal pair that the contact code would treat as two faces.
void require_left_turns(const Node& node, const std::vector<Vec2>& v) {
    const std::size_t n = v.size();
    for (std::size_t i = 0; i < n; ++i) {
        const double turn = twice_signed_area(v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
        if (turn == 0.0) {
            node.element(i).fail("is collinear with its neighbours; the polygon must be "
                                 "strictly convex");
        }
        if (turn < 0.0) {
            node.element(i).fail("is a reflex corner (turns right); the polygon must be convex "
                                 "with counter-clockwise vertices");
        }
    }
}

// Left turns everywhere still allow a star that winds round twice; a convex
// outline traced once has every vertex on the inner side of every edge.
void require_simple(const Node& node, const std::vector<Vec2>& v) {
    const std::size_t n = v.size();
    for (std::size_t edge = 0; edge < n; ++edge) {
        const Vec2 a = v[edge];
        const Vec2 b = v[(edge + 1) % n];
        for (std::size_t k = 0; k < n; ++k) {
            if (k != edge && k != (edge + 1) % n && !(twice_signed_area(a, b, v[k]) > 0.0)) {
                node.fail("winds around more than once (the outline crosses itself); a convex "
                          "polygon's vertices go round once");
            }
        }
    }
}

// The polygon's least width: over its edges, the furthest vertex from the
// edge's line (a convex polygon's narrowest strip lies flush with an edge).
double least_width(const Polygon& polygon) {
    double least = std::numeric_limits<double>::infinity();
    for (int i = 0; i < polygon.count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        double furthest = 0.0;
        for (int j = 0; j < polygon.count; ++j) {
            const Vec2 v = polygon.vertices[static_cast<std::size_t>(j)];
            furthest = std::max(furthest, dot(polygon.normals[k], polygon.vertices[k] - v));
        }
        least = std::min(least, furthest);
    }
    return least;
}

// A polygon thinner than the rounding of its own vertices has no thickness
// to double precision: its least width below 2^-40 of its longest extent
// (the triangle [[-0.1, 0], [0.1, 0], [0, 1e-15]], 5e-15 of its length, once
// had an inradius of -0 m). The engine's contact tests need its normals and
// its inradius to mean something; a sliver of 1e-9 of its length is fine.
void require_thickness(const Node& node, const Polygon& polygon) {
    double extent = 0.0;
    for (int i = 0; i < polygon.count; ++i) {
        for (int j = i + 1; j < polygon.count; ++j) {
            extent = std::max(extent, length(polygon.vertices[static_cast<std::size_t>(i)] -
                                             polygon.vertices[static_cast<std::size_t>(j)]));
        }
    }
    const double width = least_width(polygon);
    if (!(width > std::ldexp(extent, -40))) {
        node.fail("is " + number_text(width) + " m across at its thinnest and " +
                  number_text(extent) +
                  " m long: no thickness to double precision (its width must be more than "
                  "2^-40 of its length); make the shape thicker");
    }
}

Shape read_polygon(const Node& node) {
    require_array(node);
    const std::size_t n = node.json().size();
    if (n < static_cast<std::size_t>(min_polygon_vertices) ||
        n > static_cast<std::size_t>(max_polygon_vertices)) {
        node.fail("must have " + std::to_string(min_polygon_vertices) + " to " +
                  std::to_string(max_polygon_vertices) + " vertices, got " + std::to_string(n));
    }
    std::vector<Vec2> vertices;
    for (std::size_t i = 0; i < n; ++i) {
        vertices.push_back(read_vec2(node.element(i)));
    }
    require_distinct_neighbours(node, vertices);
    require_counter_clockwise(node, vertices);
    require_left_turns(node, vertices);
    require_simple(node, vertices);
    return make_polygon(vertices.data(), static_cast<int>(n));
}

} // namespace

Shape read_shape(const Node& node) {
    require_object(node);
    const std::vector<std::string> kinds = {"box", "circle", "polygon"};
    reject_unknown_keys(node, kinds);
    std::optional<std::string> kind;
    for (const std::string& candidate : kinds) {
        if (!node.has(candidate)) {
            continue;
        }
        if (kind) {
            node.member(candidate).fail("a shape is exactly one of box, circle or polygon; this "
                                        "one also has " +
                                        *kind);
        }
        kind = candidate;
    }
    if (!kind) {
        node.fail("must have one of box, circle or polygon");
    }
    const Node value = node.member(*kind);
    if (*kind == "box") {
        return read_box(value);
    }
    if (*kind == "circle") {
        return make_circle(read_positive(value));
    }
    const Shape polygon = read_polygon(value);
    require_thickness(node, polygon.polygon);
    return polygon;
}

// Moves a polygon's vertices by minus its centroid; returns the centroid when
// it was off the origin by more than centroid_tolerance of its size, or more
// than width_tolerance of its least width. The width matters for a sliver:
// the triangle [[-1, 0], [1, 0], [0, 2.1e-9]] has its centroid 7e-10 m off, a
// tiny fraction of its size but a third of its width, and left there its
// origin lay on an edge, so its inradius about the origin (engine/shape.h) was
// 0 and the scene was refused as having no thickness. An offset of a
// thousandth of the width takes at most that much off the inradius, and stays
// far above the centroid's own rounding (its size times 2^-52), which would
// otherwise make every given-centred sliver "off its centroid".
std::optional<Vec2> recentre_on_centroid(Shape& shape) {
    if (shape.type != ShapeType::polygon) {
        return std::nullopt;
    }
    const Polygon& polygon = shape.polygon;
    double size = 0.0;
    for (int i = 0; i < polygon.count; ++i) {
        size = std::max(size, length(polygon.vertices[static_cast<std::size_t>(i)]));
    }
    const Vec2 centroid = mass_properties(shape).centroid;
    const double offset = length(centroid);
    if (!(offset > centroid_tolerance * size) &&
        !(offset > width_tolerance * least_width(polygon))) {
        return std::nullopt;
    }
    std::vector<Vec2> moved;
    for (int i = 0; i < polygon.count; ++i) {
        moved.push_back(polygon.vertices[static_cast<std::size_t>(i)] - centroid);
    }
    shape = make_polygon(moved.data(), polygon.count);
    return centroid;
}

std::string centroid_warning(const std::string& file, const std::string& shape_path, Vec2 centroid,
                             const std::string& consequence) {
    return file + ": " + shape_path + ".polygon: centroid is at (" + number_text(centroid.x) +
           ", " + number_text(centroid.y) + "), not at the origin; " + consequence;
}

} // namespace impulse::harness::scene_reading
