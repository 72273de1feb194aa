#include "broad_phase.h"

#include <algorithm>
#include <cmath>

namespace impulse {

Aabb aabb_of(const Shape& shape, const Transform& xf, double margin) {
    if (shape.type == ShapeType::circle) {
        const double r = shape.radius + margin;
        return {{xf.p.x - r, xf.p.y - r}, {xf.p.x + r, xf.p.y + r}};
    }
    const Polygon& polygon = shape.polygon;
    Vec2 lower = apply(xf, polygon.vertices[0]);
    Vec2 upper = lower;
    for (int i = 1; i < polygon.count; ++i) {
        const Vec2 v = apply(xf, polygon.vertices[static_cast<std::size_t>(i)]);
        lower = {std::min(lower.x, v.x), std::min(lower.y, v.y)};
        upper = {std::max(upper.x, v.x), std::max(upper.y, v.y)};
    }
    return {{lower.x - margin, lower.y - margin}, {upper.x + margin, upper.y + margin}};
}

namespace {

double extent_of(const Aabb& box) {
    return std::max(box.upper.x - box.lower.x, box.upper.y - box.lower.y);
}

// A box this many cells across or more is oversized.
constexpr double oversized_cells = 4.0;

// At most this many cells per box filed, so a grid stretched by one far-away
// body cannot cost more memory or time than the bodies themselves.
constexpr double cells_per_box = 4.0;

int clamp_cell(double coordinate, double origin, double inverse_cell, int count) {
    const double cell = std::floor((coordinate - origin) * inverse_cell);
    // Compare as doubles first: a box far outside the grid must not overflow int.
    if (!(cell > 0.0)) {
        return 0;
    }
    if (cell >= static_cast<double>(count - 1)) {
        return count - 1;
    }
    return static_cast<int>(cell);
}

} // namespace

bool UniformGrid::oversized(const Aabb& box) const {
    return extent_of(box) > oversized_cells * cell_size_;
}

UniformGrid::CellRange UniformGrid::cells_of(const Aabb& box) const {
    return {clamp_cell(box.lower.x, origin_.x, inverse_cell_size_, columns_),
            clamp_cell(box.lower.y, origin_.y, inverse_cell_size_, rows_),
            clamp_cell(box.upper.x, origin_.x, inverse_cell_size_, columns_),
            clamp_cell(box.upper.y, origin_.y, inverse_cell_size_, rows_)};
}

void UniformGrid::build(const std::vector<Aabb>& boxes) {
    entries_.clear();
    oversized_ids_.clear();
    seen_.assign(boxes.size(), 0u);
    stamp_ = 0;

    // The cell is as wide as the median box: most boxes then touch at most
    // four cells, and each cell holds about one box wherever bodies are dense.
    std::vector<double> extents;
    extents.reserve(boxes.size());
    for (const Aabb& box : boxes) {
        extents.push_back(extent_of(box));
    }
    const auto median = extents.begin() + static_cast<std::ptrdiff_t>(extents.size() / 2);
    std::nth_element(extents.begin(), median, extents.end());
    cell_size_ = extents.empty() || !(*median > 0.0) ? 1.0 : *median;

    Aabb bounds{{0.0, 0.0}, {0.0, 0.0}};
    bool any = false;
    for (const Aabb& box : boxes) {
        if (oversized(box)) {
            continue;
        }
        bounds = any ? Aabb{{std::min(bounds.lower.x, box.lower.x),
                             std::min(bounds.lower.y, box.lower.y)},
                            {std::max(bounds.upper.x, box.upper.x),
                             std::max(bounds.upper.y, box.upper.y)}}
                     : box;
        any = true;
    }
    const double width = bounds.upper.x - bounds.lower.x;
    const double height = bounds.upper.y - bounds.lower.y;
    const double max_cells = cells_per_box * static_cast<double>(boxes.size()) + 64.0;
    const double cells = (width / cell_size_ + 1.0) * (height / cell_size_ + 1.0);
    if (cells > max_cells) {
        // Coarser cells for a sparse world; the oversized rule keeps the old size.
        const double coarser = cell_size_ * std::sqrt(cells / max_cells);
        columns_ = static_cast<int>(std::min(width / coarser + 1.0, max_cells));
        rows_ = static_cast<int>(std::min(height / coarser + 1.0, max_cells));
        inverse_cell_size_ = 1.0 / coarser;
    } else {
        columns_ = static_cast<int>(width / cell_size_) + 1;
        rows_ = static_cast<int>(height / cell_size_) + 1;
        inverse_cell_size_ = 1.0 / cell_size_;
    }
    columns_ = std::max(columns_, 1);
    rows_ = std::max(rows_, 1);
    origin_ = bounds.lower;
    heads_.assign(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_), -1);
    for (std::size_t id = 0; id < boxes.size(); ++id) {
        insert(static_cast<int>(id), boxes[id]);
    }
}

void UniformGrid::insert(int id, const Aabb& box) {
    if (oversized(box)) {
        oversized_ids_.push_back(id);
        return;
    }
    const CellRange r = cells_of(box);
    for (int y = r.y0; y <= r.y1; ++y) {
        for (int x = r.x0; x <= r.x1; ++x) {
            int& head = heads_[static_cast<std::size_t>(y * columns_ + x)];
            entries_.push_back({id, head});
            head = static_cast<int>(entries_.size()) - 1;
        }
    }
}

} // namespace impulse
