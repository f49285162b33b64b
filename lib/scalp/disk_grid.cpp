#include "scalp/disk_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hairfit {

DiskGrid::DiskGrid(const std::vector<Vec2>& points, double cell) : cell_(cell) {
  if (!(cell > 0) || !std::isfinite(cell)) throw std::invalid_argument("DiskGrid: cell size must be positive");
  const int n = static_cast<int>(points.size());
  if (n == 0) {
    start_.assign(2, 0);
    return;
  }
  Vec2 hi = points[0];
  lo_ = points[0];
  for (const Vec2& p : points) lo_ = lo_.cwiseMin(p), hi = hi.cwiseMax(p);
  // No more cells than about four per point, whatever the spread (the queries are exact for any
  // cell size; it only sets their cost).
  const double needed = std::sqrt((hi - lo_).prod() / (4.0 * n + 16.0));
  if (needed > cell_) cell_ = needed;
  nx_ = static_cast<int>((hi.x() - lo_.x()) / cell_) + 1;
  ny_ = static_cast<int>((hi.y() - lo_.y()) / cell_) + 1;
  // Counting sort by cell, stable, so a cell holds its points by ascending index.
  std::vector<int> cell_of(n);
  start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (int i = 0; i < n; ++i) {
    cell_of[i] = clamped((points[i].y() - lo_.y()) / cell_, ny_) * nx_ + clamped((points[i].x() - lo_.x()) / cell_, nx_);
    ++start_[cell_of[i] + 1];
  }
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  std::vector<int> next(start_.begin(), start_.end() - 1);
  points_.resize(n);
  index_.resize(n);
  for (int i = 0; i < n; ++i) {
    const int k = next[cell_of[i]]++;
    points_[k] = points[i];
    index_[k] = i;
  }
}

int DiskGrid::nearest(const Vec2& p) const {
  if (points_.empty()) return -1;
  const int cx = clamped((p.x() - lo_.x()) / cell_, nx_), cy = clamped((p.y() - lo_.y()) / cell_, ny_);
  int best = -1;
  double best_d2 = INFINITY;
  auto test_cells = [&](int y, int x_first, int x_last) {  // cells x_first … x_last of row y
    for (int k = start_[y * nx_ + x_first]; k < start_[y * nx_ + x_last + 1]; ++k) {
      const double dx = points_[k].x() - p.x(), dy = points_[k].y() - p.y();
      const double d2 = dx * dx + dy * dy;
      if (d2 < best_d2 || (d2 == best_d2 && index_[k] < best)) best = index_[k], best_d2 = d2;
    }
  };
  // Rings of cells around p's cell, outward, until no cell outside the searched block can hold a
  // nearer point: each side of the block that is not the grid's edge is at least its distance
  // from p away (the margin covers round-off in the binning).
  for (int ring = 0;; ++ring) {
    const int x0 = cx - ring, x1 = cx + ring, y0 = cy - ring, y1 = cy + ring;
    const int xa = std::max(x0, 0), xb = std::min(x1, nx_ - 1);
    for (int y = std::max(y0, 0); y <= std::min(y1, ny_ - 1); ++y) {
      if (y == y0 || y == y1) {
        test_cells(y, xa, xb);
      } else {
        if (x0 >= 0) test_cells(y, x0, x0);
        if (x1 < nx_) test_cells(y, x1, x1);
      }
    }
    double bound = INFINITY;
    if (x0 > 0) bound = std::min(bound, p.x() - (lo_.x() + x0 * cell_));
    if (x1 < nx_ - 1) bound = std::min(bound, lo_.x() + (x1 + 1) * cell_ - p.x());
    if (y0 > 0) bound = std::min(bound, p.y() - (lo_.y() + y0 * cell_));
    if (y1 < ny_ - 1) bound = std::min(bound, lo_.y() + (y1 + 1) * cell_ - p.y());
    if (bound == INFINITY) return best;  // the whole grid is searched
    if (best >= 0 && bound > 0 && best_d2 < bound * bound * (1.0 - 1e-9)) return best;
  }
}

}  // namespace hairfit
