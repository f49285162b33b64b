#include "scalp/point_grid.h"

#include <numeric>
#include <stdexcept>

namespace hairfit {

PointGrid::PointGrid(const std::vector<Vec3>& points, double cell) : points_(points), cell_(cell) {
  if (!(cell > 0) || !std::isfinite(cell)) throw std::invalid_argument("PointGrid: cell size must be positive");
  origin_ = Vec3::Zero();
  if (!points.empty()) {
    origin_ = points.front();
    for (const Vec3& p : points) origin_ = origin_.cwiseMin(p);
  }
  std::vector<std::uint64_t> keys(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) keys[i] = key(cell_of(points[i]));
  order_.resize(points.size());
  std::iota(order_.begin(), order_.end(), 0);
  std::sort(order_.begin(), order_.end(), [&](int a, int b) { return keys[a] != keys[b] ? keys[a] < keys[b] : a < b; });
  cells_.reserve(points.size());
  for (std::size_t k = 0; k < order_.size();) {
    std::size_t e = k;
    while (e < order_.size() && keys[order_[e]] == keys[order_[k]]) ++e;
    cells_.emplace(keys[order_[k]], std::make_pair(static_cast<int>(k), static_cast<int>(e)));
    k = e;
  }
}

int PointGrid::nearest(const Vec3& p, int exclude, double max_radius) const {
  for (double radius = cell_;; radius *= 2) {
    const double r = std::min(radius, max_radius);
    int best = -1;
    double best_d2 = INFINITY;
    for_each_within(p, r, [&](int i, double d2) {
      if (i != exclude && (d2 < best_d2 || (d2 == best_d2 && i < best))) best = i, best_d2 = d2;
    });
    if (best >= 0 || r >= max_radius) return best;
  }
}

}  // namespace hairfit
