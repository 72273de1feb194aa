#include "manifold.h"

#include <optional>

namespace impulse {

namespace {

struct WorldPolygon {
    int count = 0;
    std::array<Vec2, max_polygon_vertices> vertices{};
    std::array<Vec2, max_polygon_vertices> normals{};
};

WorldPolygon to_world(const Polygon& polygon, const Transform& xf) {
    WorldPolygon w;
    w.count = polygon.count;
    for (int i = 0; i < polygon.count; ++i) {
        w.vertices[i] = apply(xf, polygon.vertices[i]);
        w.normals[i] = rotate(xf.q, polygon.normals[i]);
    }
    return w;
}

struct FaceSeparation {
    int edge = 0;
    double separation = 0.0;
};

// The edge of `a` whose outward normal separates the polygons the most: the
// separating-axis test restricted to a's normals.
FaceSeparation max_face_separation(const WorldPolygon& a, const WorldPolygon& b) {
    FaceSeparation best{0, -1e300};
    for (int i = 0; i < a.count; ++i) {
        const Vec2 n = a.normals[i];
        const Vec2 v = a.vertices[i];
        double deepest = 1e300;
        for (int k = 0; k < b.count; ++k) {
            const double s = dot(n, b.vertices[k] - v);
            if (s < deepest) {
                deepest = s;
            }
        }
        if (deepest > best.separation) {
            best = {i, deepest};
        }
    }
    return best;
}

// Reference face: prefer B's face unless A's separates clearly more, so a body
// landing on static ground (B) takes the ground's normal; ties never flip.
constexpr double reference_face_bias = 0.1; // of contact_tolerance

// The cone of outward normals at vertex i of a counter-clockwise polygon: the
// directions from the normal of the edge ending at i, counter-clockwise to the
// normal of the edge starting there (less than half a turn, the polygon being
// strictly convex). They are the directions along which the vertex is the
// polygon's extreme point, so a plane with such a normal supports it there.
struct NormalCone {
    Vec2 from;
    Vec2 to;
};

NormalCone vertex_cone(const WorldPolygon& p, int i) {
    return {p.normals[(i + p.count - 1) % p.count], p.normals[i]};
}

NormalCone negated(NormalCone cone) {
    return {-cone.from, -cone.to}; // a half turn keeps the counter-clockwise order
}

bool in_cone(Vec2 u, const NormalCone& cone) {
    return cross(cone.from, u) >= 0.0 && cross(u, cone.to) >= 0.0;
}

int nearest_vertex(const WorldPolygon& p, Vec2 x) {
    int nearest = 0;
    for (int i = 1; i < p.count; ++i) {
        if (length_squared(p.vertices[i] - x) < length_squared(p.vertices[nearest] - x)) {
            nearest = i;
        }
    }
    return nearest;
}

// Vertex/vertex: vertex ia of A touches vertex ib of B. A normal n (toward A)
// separates the two corners when B's corner is extreme along n and A's along
// -n: n in B's vertex cone and in A's negated one. Two arcs of less than half a
// turn meet in at most one arc, from the later of their starts to the earlier
// of their ends; the normal is its bisector. It depends only on the two
// vertices, not on which face the separating axes happened to pick (the
// seed's arbitrary choice), so it is the same whichever body is A, turns with
// the configuration, and lies on a line of symmetry of a symmetric contact.
// An empty intersection (interpenetration by rounding) gives nothing.
std::optional<Vec2> vertex_vertex_normal(const WorldPolygon& a, int ia, const WorldPolygon& b,
                                         int ib) {
    const NormalCone cb = vertex_cone(b, ib);
    const NormalCone ca = negated(vertex_cone(a, ia));
    Vec2 from, to;
    if (in_cone(ca.from, cb)) {
        from = ca.from;
    } else if (in_cone(cb.from, ca)) {
        from = cb.from;
    } else {
        return std::nullopt;
    }
    if (in_cone(ca.to, cb)) {
        to = ca.to;
    } else if (in_cone(cb.to, ca)) {
        to = cb.to;
    } else {
        return std::nullopt;
    }
    if (cross(from, to) < 0.0) {
        return std::nullopt;
    }
    const Vec2 sum = from + to;
    const double norm = length(sum);
    if (!(norm > 0.0)) {
        return std::nullopt;
    }
    return (1.0 / norm) * sum;
}

// Turns m into a vertex/vertex contact when it is one: a vertex of the
// incident polygon sits (within contact_tolerance) on an end vertex of the
// reference face, and the clipped incident edge touches the face nowhere else.
// A point inside the face is vertex/edge and two points apart are edge/edge:
// both keep the face normal. Two kept points at the one vertex happen when the
// incident edge lies along the reference face's line and meets it only at the
// shared corner (the clipping leaves a sliver of rounding width): still one
// corner against one corner, so one point. When the incident edge misses the
// face sideways the seed's fallback point is a deepest incident vertex, which
// for an incident edge parallel to the face is either end, so there only the
// corner pair counts.
void vertex_vertex(const WorldPolygon& a, const WorldPolygon& b, bool reference_is_a, int ref_edge,
                   const Vec2 (&kept)[2], bool missed_sideways, double contact_tolerance,
                   Manifold& m) {
    const WorldPolygon& ref = reference_is_a ? a : b;
    const WorldPolygon& inc = reference_is_a ? b : a;
    const double tolerance_squared = contact_tolerance * contact_tolerance;
    // The incident vertex nearest to either end of the reference face.
    const int next = (ref_edge + 1) % ref.count;
    const int near_first = nearest_vertex(inc, ref.vertices[ref_edge]);
    const int near_next = nearest_vertex(inc, ref.vertices[next]);
    const double d_first = length_squared(inc.vertices[near_first] - ref.vertices[ref_edge]);
    const double d_next = length_squared(inc.vertices[near_next] - ref.vertices[next]);
    const int rv = d_first <= d_next ? ref_edge : next;
    const int iv = d_first <= d_next ? near_first : near_next;
    if ((d_first <= d_next ? d_first : d_next) > tolerance_squared) {
        return;
    }
    if (!missed_sideways) {
        for (int i = 0; i < m.point_count; ++i) {
            if (length_squared(kept[i] - inc.vertices[iv]) > tolerance_squared) {
                return;
            }
        }
    }
    const int ia = reference_is_a ? rv : iv;
    const int ib = reference_is_a ? iv : rv;
    const std::optional<Vec2> n = vertex_vertex_normal(a, ia, b, ib);
    if (!n) {
        return; // the seed's reference face normal stands
    }
    // Halfway between the two corners, the gap measured along the new normal;
    // both the same whichever body is A.
    const Vec2 va = a.vertices[ia];
    const Vec2 vb = b.vertices[ib];
    m.normal = *n;
    m.point_count = 1;
    m.points[0] = {0.5 * (va + vb), *n, dot(*n, va - vb)};
}

// The incident polygon's points that may touch the reference face: its
// incident edge clipped to the face's extent.
struct IncidentPoints {
    Vec2 points[2];
    int count = 0;
    bool missed = false; // the edges miss each other sideways: the deepest vertex
};

IncidentPoints incident_points(const WorldPolygon& ref, const WorldPolygon& inc, int ref_edge) {
    const Vec2 ref_n = ref.normals[ref_edge];
    // Incident edge: the edge of the other polygon facing the reference face most directly.
    int inc_edge = 0;
    double most_opposed = 1e300;
    for (int i = 0; i < inc.count; ++i) {
        const double d = dot(ref_n, inc.normals[i]);
        if (d < most_opposed) {
            most_opposed = d;
            inc_edge = i;
        }
    }
    Vec2 seg[2] = {inc.vertices[inc_edge], inc.vertices[(inc_edge + 1) % inc.count]};

    // Clip the incident edge to the reference face's extent (its two side planes).
    const Vec2 r1 = ref.vertices[ref_edge];
    const Vec2 r2 = ref.vertices[(ref_edge + 1) % ref.count];
    const Vec2 tangent = perp(ref_n); // from r1 toward r2 for counter-clockwise winding
    const double lower = dot(tangent, r1);
    const double upper = dot(tangent, r2);
    const double d0 = dot(tangent, seg[0]);
    const double d1 = dot(tangent, seg[1]);
    // The incident edge runs opposite to the reference edge, so d0 >= d1.
    double t_begin = 0.0, t_end = 1.0; // parameters along seg[0] -> seg[1]
    if (d0 != d1) {
        const double t_upper = (upper - d0) / (d1 - d0);
        const double t_lower = (lower - d0) / (d1 - d0);
        const double t_enter = t_upper < t_lower ? t_upper : t_lower;
        const double t_leave = t_upper < t_lower ? t_lower : t_upper;
        t_begin = t_enter > 0.0 ? t_enter : 0.0;
        t_end = t_leave < 1.0 ? t_leave : 1.0;
    } else if (d0 < lower || d0 > upper) {
        t_begin = 1.0;
        t_end = 0.0;
    }

    IncidentPoints r;
    r.missed = t_begin > t_end;
    if (t_begin <= t_end) {
        r.points[r.count++] = t_begin == 0.0 ? seg[0] : seg[0] + t_begin * (seg[1] - seg[0]);
        if (t_end > t_begin) {
            r.points[r.count++] = t_end == 1.0 ? seg[1] : seg[0] + t_end * (seg[1] - seg[0]);
        }
    } else {
        // The edges miss each other sideways (corner against corner): fall back
        // to the incident body's deepest vertex, the seed's vertex/edge treatment.
        int deepest = 0;
        for (int i = 1; i < inc.count; ++i) {
            if (dot(ref_n, inc.vertices[i] - r1) < dot(ref_n, inc.vertices[deepest] - r1)) {
                deepest = i;
            }
        }
        r.points[r.count++] = inc.vertices[deepest];
    }
    return r;
}

Manifold collide_polygons(const WorldPolygon& a, const WorldPolygon& b, double contact_tolerance,
                          VertexNormal vertex_normal) {
    const FaceSeparation face_a = max_face_separation(a, b);
    const FaceSeparation face_b = max_face_separation(b, a);

    Manifold m;
    const bool reference_is_a =
        face_a.separation > face_b.separation + reference_face_bias * contact_tolerance;
    const WorldPolygon& ref = reference_is_a ? a : b;
    const WorldPolygon& inc = reference_is_a ? b : a;
    const int ref_edge = reference_is_a ? face_a.edge : face_b.edge;
    m.separation = reference_is_a ? face_a.separation : face_b.separation;
    const Vec2 ref_n = ref.normals[ref_edge];
    m.normal = reference_is_a ? -ref_n : ref_n; // toward A

    if (m.separation > contact_tolerance) {
        return m;
    }

    const IncidentPoints incident = incident_points(ref, inc, ref_edge);
    const Vec2 r1 = ref.vertices[ref_edge];

    Vec2 kept[2]; // the incident points behind m.points
    for (int i = 0; i < incident.count; ++i) {
        const double s = dot(ref_n, incident.points[i] - r1);
        if (s <= contact_tolerance) {
            kept[m.point_count] = incident.points[i];
            // The point halfway between the incident vertex and the reference face.
            m.points[m.point_count++] = {incident.points[i] - (0.5 * s) * ref_n, m.normal, s};
        }
    }
    if (vertex_normal == VertexNormal::bisector && m.point_count > 0) {
        vertex_vertex(a, b, reference_is_a, ref_edge, kept, incident.missed, contact_tolerance, m);
    }
    return m;
}

// Circle (centre c, radius r) against a polygon; the normal points toward the circle.
Manifold collide_polygon_circle(const WorldPolygon& p, Vec2 c, double r) {
    FaceSeparation face{0, -1e300};
    for (int i = 0; i < p.count; ++i) {
        const double s = dot(p.normals[i], c - p.vertices[i]);
        if (s > face.separation) {
            face = {i, s};
        }
    }
    const Vec2 v1 = p.vertices[face.edge];
    const Vec2 v2 = p.vertices[(face.edge + 1) % p.count];
    Vec2 n = p.normals[face.edge];
    double distance = face.separation;
    if (face.separation > 0.0) {
        // Outside: the closest feature is the face or one of its end vertices.
        if (dot(c - v1, v2 - v1) < 0.0) {
            distance = length(c - v1);
            n = (1.0 / distance) * (c - v1);
        } else if (dot(c - v2, v1 - v2) < 0.0) {
            distance = length(c - v2);
            n = (1.0 / distance) * (c - v2);
        }
    }
    Manifold m;
    m.normal = n;
    m.separation = distance - r;
    m.point_count = 1;
    m.points[0] = {c - (r + 0.5 * m.separation) * n, n, m.separation};
    return m;
}

// Circle B against circle A; the normal points toward A.
Manifold collide_circles(Vec2 ca, double ra, Vec2 cb, double rb) {
    const Vec2 d = ca - cb;
    const double distance = length(d);
    Manifold m;
    // Concentric circles have no preferred direction; pick +y so it is deterministic.
    m.normal = distance > 0.0 ? (1.0 / distance) * d : Vec2{0.0, 1.0};
    m.separation = distance - ra - rb;
    m.point_count = 1;
    m.points[0] = {cb + (rb + 0.5 * m.separation) * m.normal, m.normal, m.separation};
    return m;
}

Manifold flipped(Manifold m) {
    m.normal = -m.normal;
    for (int i = 0; i < m.point_count; ++i) {
        m.points[i].normal = m.normal;
    }
    return m;
}

Manifold with_tolerance(Manifold m, double contact_tolerance) {
    int kept = 0;
    for (int i = 0; i < m.point_count; ++i) {
        if (m.points[i].separation <= contact_tolerance) {
            m.points[kept++] = m.points[i];
        }
    }
    m.point_count = kept;
    return m;
}

} // namespace

Manifold collide(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                 double contact_tolerance, VertexNormal vertex_normal) {
    if (a.type == ShapeType::polygon && b.type == ShapeType::polygon) {
        return collide_polygons(to_world(a.polygon, xa), to_world(b.polygon, xb), contact_tolerance,
                                vertex_normal);
    }
    if (a.type == ShapeType::polygon) {
        // Normal from the polygon A toward the circle B: flip it toward A.
        return flipped(with_tolerance(
            collide_polygon_circle(to_world(a.polygon, xa), xb.p, b.radius), contact_tolerance));
    }
    if (b.type == ShapeType::polygon) {
        return with_tolerance(collide_polygon_circle(to_world(b.polygon, xb), xa.p, a.radius),
                              contact_tolerance);
    }
    return with_tolerance(collide_circles(xa.p, a.radius, xb.p, b.radius), contact_tolerance);
}

double separation(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
    if (a.type == ShapeType::polygon && b.type == ShapeType::polygon) {
        const WorldPolygon wa = to_world(a.polygon, xa);
        const WorldPolygon wb = to_world(b.polygon, xb);
        const double sa = max_face_separation(wa, wb).separation;
        const double sb = max_face_separation(wb, wa).separation;
        return sa > sb ? sa : sb;
    }
    return collide(a, xa, b, xb, -1e300).separation;
}

} // namespace impulse
