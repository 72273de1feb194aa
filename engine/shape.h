// Collision shapes in body coordinates, with the centre of mass at the origin.
#pragma once

#include "vec2.h"

#include <array>

namespace impulse {

inline constexpr int max_polygon_vertices = 16;

// A convex polygon, vertices counter-clockwise. normals[i] is the outward unit
// normal of the edge from vertices[i] to vertices[i + 1].
struct Polygon {
    int count = 0;
    std::array<Vec2, max_polygon_vertices> vertices{};
    std::array<Vec2, max_polygon_vertices> normals{};
};

enum class ShapeType { circle, polygon };

struct Shape {
    ShapeType type = ShapeType::circle;
    double radius = 0.0; // circles only
    Polygon polygon;     // polygons only
};

struct MassProperties {
    double area = 0.0;
    Vec2 centroid;                      // in the coordinates the shape was given in
    double inertia_per_unit_mass = 0.0; // about the centroid
};

Shape make_circle(double radius);
// A box with half extents (hx, hy), centred on the origin.
Shape make_box(double hx, double hy);
// Vertices must be convex and counter-clockwise (the harness validates that);
// normals are computed here.
Shape make_polygon(const Vec2* vertices, int count);

MassProperties mass_properties(const Shape& shape);

// r of the disc about the centre that the shape contains, half its thinnest
// thickness: the radius of a circle, a polygon's smallest distance from its
// centre to an edge's line (shapes are centred on their centroid). Two bodies
// cannot pass through each other within a step unless they move at least the
// sum of their inradii, doubled, relative to each other.
double inradius(const Shape& shape);

// R, the farthest a point of the shape lies from its centre: the radius of a
// circle, a polygon's farthest vertex. Two shapes whose centres are more than
// the sum of their circumradii apart cannot overlap, at any angles.
double circumradius(const Shape& shape);

// Twice the signed area of the triangle (a, b, c): positive when counter-clockwise.
constexpr double twice_signed_area(Vec2 a, Vec2 b, Vec2 c) {
    return cross(b - a, c - a);
}

} // namespace impulse
