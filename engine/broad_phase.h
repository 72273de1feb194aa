// Which pairs are worth a narrow-phase test: axis-aligned boxes in a uniform
// grid, so a world of N similar bodies costs about N per query round instead of
// N^2 (docs/engine.md, "Local stepping"). The broad phase only prunes: a pair
// whose boxes do not overlap cannot interpenetrate, so it never changes which
// collisions happen, only how many pairs are looked at.
#pragma once

#include "rotation.h"
#include "shape.h"

#include <algorithm>
#include <vector>

namespace impulse {

struct Aabb {
    Vec2 lower;
    Vec2 upper;
};

constexpr bool overlaps(const Aabb& a, const Aabb& b) {
    return a.lower.x <= b.upper.x && b.lower.x <= a.upper.x && a.lower.y <= b.upper.y &&
           b.lower.y <= a.upper.y;
}

// The shape's box at a pose, grown by `margin` on every side. The margin
// covers the rounding of the rotated vertices, so a pair the narrow phase
// finds interpenetrating always has overlapping boxes.
Aabb aabb_of(const Shape& shape, const Transform& xf, double margin);

// A uniform grid of boxes with the cell size chosen from the boxes themselves.
// Boxes far larger than a cell (walls, the ground) are kept in a list every
// query returns, so they neither flood the cells nor stretch the grid.
class UniformGrid {
  public:
    // Forgets everything and files boxes[id] under id for every id.
    void build(const std::vector<Aabb>& boxes);
    // Files one more box under id. Earlier entries for id stay (callers
    // filter candidates against the id's current box), which keeps this O(1)
    // per cell instead of a search for the old entries.
    void insert(int id, const Aabb& box);
    // Calls visit(id) once for every id with an entry in a cell `box` touches,
    // and for every oversized id; ids in ascending order of discovery, which
    // depends only on the boxes filed, never on addresses.
    template <class Visit> void query(const Aabb& box, Visit&& visit);

  private:
    struct CellRange {
        int x0, y0, x1, y1;
    };
    CellRange cells_of(const Aabb& box) const;
    bool oversized(const Aabb& box) const;

    struct Entry {
        int id;
        int next; // the next entry in the same cell, or -1
    };
    double cell_size_ = 1.0;
    double inverse_cell_size_ = 1.0;
    Vec2 origin_;
    int columns_ = 1;
    int rows_ = 1;
    std::vector<int> heads_; // first entry of each cell, or -1
    std::vector<Entry> entries_;
    std::vector<int> oversized_ids_;
    std::vector<unsigned> seen_; // seen_[id] == stamp_: already visited in this query
    unsigned stamp_ = 0;
};

template <class Visit> void UniformGrid::query(const Aabb& box, Visit&& visit) {
    if (++stamp_ == 0) { // wrapped: forget every old mark
        std::fill(seen_.begin(), seen_.end(), 0u);
        stamp_ = 1;
    }
    const auto visit_once = [&](int id) {
        if (seen_[static_cast<std::size_t>(id)] != stamp_) {
            seen_[static_cast<std::size_t>(id)] = stamp_;
            visit(id);
        }
    };
    for (const int id : oversized_ids_) {
        visit_once(id);
    }
    const CellRange r = cells_of(box);
    for (int y = r.y0; y <= r.y1; ++y) {
        for (int x = r.x0; x <= r.x1; ++x) {
            for (int e = heads_[static_cast<std::size_t>(y * columns_ + x)]; e >= 0;
                 e = entries_[static_cast<std::size_t>(e)].next) {
                visit_once(entries_[static_cast<std::size_t>(e)].id);
            }
        }
    }
}

} // namespace impulse
