// Chart points (2D) binned in a dense grid of square cells over their bounding box, for the
// cluster queries in the unit disk: a dense array of cells is small there and cheaper to index
// than PointGrid's hashed cells. Built once, then read-only (safe from many threads).
#pragma once
#include <vector>

#include "core/types.h"

namespace hairfit {

class DiskGrid {
 public:
  // cell: edge length of a cell (> 0).
  DiskGrid(const std::vector<Vec2>& points, double cell);

  // Index of the point nearest to p: the smallest squared distance dx² + dy², ties to the lower
  // index; −1 for no points. Exact (the search widens until no nearer point can remain).
  int nearest(const Vec2& p) const;

  // Calls visit(index) for every point with dx² + dy² ≤ radius², in no particular order.
  template <class Visit>
  void for_each_within(const Vec2& p, double radius, Visit&& visit) const {
    if (points_.empty()) return;
    const double r2 = radius * radius;
    // The cells the square around the disk touches, widened by a hair against round-off.
    const int x0 = clamped((p.x() - radius - lo_.x()) / cell_ - 1e-9, nx_);
    const int x1 = clamped((p.x() + radius - lo_.x()) / cell_ + 1e-9, nx_);
    const int y0 = clamped((p.y() - radius - lo_.y()) / cell_ - 1e-9, ny_);
    const int y1 = clamped((p.y() + radius - lo_.y()) / cell_ + 1e-9, ny_);
    for (int y = y0; y <= y1; ++y)
      for (int k = start_[y * nx_ + x0]; k < start_[y * nx_ + x1 + 1]; ++k) {
        const double dx = points_[k].x() - p.x(), dy = points_[k].y() - p.y();
        if (dx * dx + dy * dy <= r2) visit(index_[k]);
      }
  }

 private:
  // The cell column (or row) of a coordinate already divided by the cell size, within [0, n).
  static int clamped(double u, int n) { return u <= 0 ? 0 : u >= n - 1 ? n - 1 : static_cast<int>(u); }

  double cell_;
  Vec2 lo_ = Vec2::Zero();
  int nx_ = 1, ny_ = 1;
  std::vector<int> start_;     // per cell (row-major) + 1: its range in points_ and index_
  std::vector<Vec2> points_;   // in cell order, by index within a cell
  std::vector<int> index_;
};

}  // namespace hairfit
