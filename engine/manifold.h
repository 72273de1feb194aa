// Narrow phase: how two shapes in given poses touch.
#pragma once

#include "contact.h"
#include "rotation.h"
#include "shape.h"
#include "solver_settings.h"

#include <array>

namespace impulse {

// The touching points of a pair. The normal points toward body A (contact.h).
// Polygon pairs give up to two points (the incident edge clipped to the
// reference face, so every point is a vertex of one body on an edge of the
// other: Hecker's vertex/edge contact); circle pairs give one. A vertex/vertex
// contact (a corner on an end of the reference face) is one point.
struct Manifold {
    Vec2 normal;
    double separation = 0.0; // signed gap of the pair: negative when they interpenetrate
    int point_count = 0;
    std::array<Contact, 2> points{};
};

// Signed gap between two shapes: for polygons the separating-axis maximum over
// every edge normal, which is negative exactly when they overlap. This is all
// the time-of-impact search needs.
double separation(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb);

// The contact points of a pair whose separation is within contact_tolerance:
// only points at most contact_tolerance apart are reported. vertex_normal
// decides a polygon pair's vertex/vertex normal: reference_face (the seed's)
// keeps the face the separating axes picked, as for vertex/edge; bisector
// takes the bisector of the normals that separate both corners, halfway
// between the two corners (docs/engine.md, "Vertex/vertex").
Manifold collide(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                 double contact_tolerance,
                 VertexNormal vertex_normal = VertexNormal::reference_face);

} // namespace impulse
