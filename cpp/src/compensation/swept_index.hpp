#pragma once
// A uniform XY grid over the segments of a polyline, for "is this point within r of the polyline
// before point i" and "within r of any cutting segment after block b" queries whose cost does not
// grow with the length of the path: a query visits only the segments listed in its own cell.
//
// Segment j (1 ≤ j < n) joins points j − 1 and j; "segment" 0 is the lone point 0, so the union of
// segments 0 … k is the polyline through points 0 … k. Each cell lists, in ascending order, every
// segment whose bounding box inflated by `reach` meets the cell; a query point q therefore finds in
// its cell every segment that comes within `reach` of q.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "netshape/core/types.hpp"

namespace netshape::compensation::detail {

class SweptIndex {
 public:
  SweptIndex() = default;

  /// Index the polyline of n points (point_of(j) → Vec2) for queries with distances up to `reach`
  /// [mm]. The cell edge is about `reach`, enlarged so that the grid has at most ~4n + 4096 cells.
  template <typename PointOf>
  void build(Eigen::Index n, PointOf point_of, double reach) {
    n_ = n;
    reach_ = reach;
    cell_start_.clear();
    items_.clear();
    if (n <= 0) return;
    double x0 = point_of(0).x(), x1 = x0, y0 = point_of(0).y(), y1 = y0;
    for (Eigen::Index j = 1; j < n; ++j) {
      const Vec2 p = point_of(j);
      x0 = std::min(x0, p.x());
      x1 = std::max(x1, p.x());
      y0 = std::min(y0, p.y());
      y1 = std::max(y1, p.y());
    }
    x0_ = x0 - reach;
    y0_ = y0 - reach;
    const double w = x1 - x0 + 2.0 * reach, h = y1 - y0 + 2.0 * reach;
    const double max_cells = 4.0 * static_cast<double>(n) + 4096.0;
    cell_ = std::max(reach, 1e-6);
    while ((w / cell_ + 1.0) * (h / cell_ + 1.0) > max_cells) cell_ *= 1.5;
    nx_ = static_cast<int>(w / cell_) + 1;
    ny_ = static_cast<int>(h / cell_) + 1;
    cell_start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    // two passes over the segments' inflated boxes: count per cell, then fill (ascending j per cell)
    auto for_cells = [&](Eigen::Index j, auto&& visit) {
      const Vec2 b = point_of(j), a = j > 0 ? point_of(j - 1) : b;
      const int i0 = cx(std::min(a.x(), b.x()) - reach), i1 = cx(std::max(a.x(), b.x()) + reach);
      const int k0 = cy(std::min(a.y(), b.y()) - reach), k1 = cy(std::max(a.y(), b.y()) + reach);
      for (int k = k0; k <= k1; ++k)
        for (int i = i0; i <= i1; ++i) visit(static_cast<std::size_t>(k) * nx_ + i);
    };
    for (Eigen::Index j = 0; j < n; ++j) for_cells(j, [&](std::size_t c) { ++cell_start_[c + 1]; });
    for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
    items_.resize(cell_start_.back());
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (Eigen::Index j = 0; j < n; ++j)
      for_cells(j, [&](std::size_t c) { items_[fill[c]++] = static_cast<std::int32_t>(j); });
  }

  Eigen::Index size() const { return n_; }
  double reach() const { return reach_; }

  /// True if q lies closer than r (≤ reach) to the polyline through points 0 … last (last < n),
  /// point_of giving the points as they are now (within reach − r of where they were indexed).
  /// Visits the candidates newest first: the latest moves are the likeliest to contain q.
  template <typename PointOf>
  bool near_before(const Vec2& q, Eigen::Index last, double r, PointOf point_of) const {
    if (last < 0 || n_ == 0) return false;
    const std::int32_t* b = nullptr;
    const std::int32_t* e = nullptr;
    if (!cell_of(q, b, e)) return false;
    const double r2 = r * r;
    const std::int32_t* it = std::upper_bound(b, e, static_cast<std::int32_t>(last));
    while (it != b) {
      const Eigen::Index j = *--it;
      if (segment_dist2(q, j, point_of) < r2) return true;
    }
    return false;
  }

  /// True if q lies closer than r (≤ reach) to a segment j ≥ first with accept(j) true.
  template <typename PointOf, typename Accept>
  bool near_from(const Vec2& q, Eigen::Index first, double r, PointOf point_of, Accept accept) const {
    if (first >= n_ || n_ == 0) return false;
    const std::int32_t* b = nullptr;
    const std::int32_t* e = nullptr;
    if (!cell_of(q, b, e)) return false;
    const double r2 = r * r;
    for (const std::int32_t* it = std::lower_bound(b, e, static_cast<std::int32_t>(std::max<Eigen::Index>(first, 0)));
         it != e; ++it)
      if (accept(*it) && segment_dist2(q, *it, point_of) < r2) return true;
    return false;
  }

 private:
  int cx(double x) const { return std::clamp(static_cast<int>(std::floor((x - x0_) / cell_)), 0, nx_ - 1); }
  int cy(double y) const { return std::clamp(static_cast<int>(std::floor((y - y0_) / cell_)), 0, ny_ - 1); }

  bool cell_of(const Vec2& q, const std::int32_t*& b, const std::int32_t*& e) const {
    const double fx = (q.x() - x0_) / cell_, fy = (q.y() - y0_) / cell_;
    if (!(fx >= 0.0 && fy >= 0.0 && fx < nx_ && fy < ny_)) return false;  // beyond every inflated box
    const std::size_t c = static_cast<std::size_t>(static_cast<int>(fy)) * nx_ + static_cast<int>(fx);
    b = items_.data() + cell_start_[c];
    e = items_.data() + cell_start_[c + 1];
    return true;
  }

  template <typename PointOf>
  static double segment_dist2(const Vec2& q, Eigen::Index j, PointOf& point_of) {
    const Vec2 pb = point_of(j);
    if (j == 0) return (q - pb).squaredNorm();
    const Vec2 pa = point_of(j - 1), ab = pb - pa;
    const double l2 = ab.squaredNorm();
    const double t = l2 > 0.0 ? std::clamp((q - pa).dot(ab) / l2, 0.0, 1.0) : 0.0;
    return (pa + t * ab - q).squaredNorm();
  }

  Eigen::Index n_ = 0;
  double reach_ = 0.0, x0_ = 0.0, y0_ = 0.0, cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> cell_start_;
  std::vector<std::int32_t> items_;
};

}  // namespace netshape::compensation::detail
