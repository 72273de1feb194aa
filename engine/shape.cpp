#include "shape.h"

#include "trig.h"

#include <algorithm>
#include <limits>

namespace impulse {

Shape make_circle(double radius) {
    Shape shape;
    shape.type = ShapeType::circle;
    shape.radius = radius;
    return shape;
}

Shape make_box(double hx, double hy) {
    const Vec2 corners[4] = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
    return make_polygon(corners, 4);
}

Shape make_polygon(const Vec2* vertices, int count) {
    Shape shape;
    shape.type = ShapeType::polygon;
    Polygon& polygon = shape.polygon;
    polygon.count = count;
    for (int i = 0; i < count; ++i) {
        polygon.vertices[i] = vertices[i];
    }
    for (int i = 0; i < count; ++i) {
        const Vec2 edge = vertices[(i + 1) % count] - vertices[i];
        // Counter-clockwise winding puts the outside on the right of each edge.
        polygon.normals[i] = (1.0 / length(edge)) * Vec2{edge.y, -edge.x};
    }
    return shape;
}

MassProperties mass_properties(const Shape& shape) {
    MassProperties mp;
    if (shape.type == ShapeType::circle) {
        const double r = shape.radius;
        mp.area = pi * r * r;
        mp.inertia_per_unit_mass = 0.5 * r * r; // disc: I = M r^2 / 2
        return mp;
    }

    // Fan of triangles from the first vertex; each triangle's second moment is
    // integrated exactly, so a box gives I = M (4a^2 + 4b^2) / 12 up to rounding.
    const Polygon& polygon = shape.polygon;
    const Vec2 origin = polygon.vertices[0];
    double area = 0.0;
    Vec2 first_moment;
    double second_moment = 0.0; // about origin, per unit density
    for (int i = 1; i + 1 < polygon.count; ++i) {
        const Vec2 e1 = polygon.vertices[i] - origin;
        const Vec2 e2 = polygon.vertices[i + 1] - origin;
        const double d = cross(e1, e2);
        const double triangle_area = 0.5 * d;
        area += triangle_area;
        first_moment += (triangle_area / 3.0) * (e1 + e2);
        const double ix = e1.x * e1.x + e2.x * e1.x + e2.x * e2.x;
        const double iy = e1.y * e1.y + e2.y * e1.y + e2.y * e2.y;
        second_moment += (d / 12.0) * (ix + iy);
    }
    const Vec2 centroid_from_origin = (1.0 / area) * first_moment;
    mp.area = area;
    mp.centroid = origin + centroid_from_origin;
    // Parallel-axis theorem moves the moment from the fan's origin to the centroid.
    mp.inertia_per_unit_mass = second_moment / area - length_squared(centroid_from_origin);
    return mp;
}

double circumradius(const Shape& shape) {
    if (shape.type == ShapeType::circle) {
        return shape.radius;
    }
    double r = 0.0;
    for (int i = 0; i < shape.polygon.count; ++i) {
        r = std::max(r, length(shape.polygon.vertices[static_cast<std::size_t>(i)]));
    }
    return r;
}

double inradius(const Shape& shape) {
    if (shape.type == ShapeType::circle) {
        return shape.radius;
    }
    // The polygon is the intersection of its edges' half-planes, each
    // dot(n_i, v_i) from the centre (the harness centres every shape on its
    // centroid).
    double r = std::numeric_limits<double>::infinity();
    for (int i = 0; i < shape.polygon.count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        r = std::min(r, dot(shape.polygon.normals[k], shape.polygon.vertices[k]));
    }
    return r;
}

} // namespace impulse
