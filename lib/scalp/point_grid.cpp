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
  for (std::size_t k = 0; k < order_.size();) {
    std::size_t e = k;
    while (e < order_.size() && keys[order_[e]] == keys[order_[k]]) ++e;
    cell_keys_.push_back(keys[order_[k]]);
    cell_begin_.push_back(static_cast<int>(k));
    cell_coords_.push_back(cell_of(points_[order_[k]]));
    k = e;
  }
  cell_begin_.push_back(static_cast<int>(order_.size()));
  std::size_t capacity = 16;
  while (capacity < 2 * cell_keys_.size()) capacity *= 2;
  mask_ = capacity - 1;
  table_.assign(capacity, -1);
  for (int c = 0; c < static_cast<int>(cell_keys_.size()); ++c) {
    std::size_t slot = mix(cell_keys_[c]) & mask_;
    while (table_[slot] >= 0) slot = (slot + 1) & mask_;
    table_[slot] = c;
  }
}

std::vector<std::pair<int, int>> PointGrid::neighbourhood(int k, int reach) const {
  std::vector<std::pair<int, int>> ranges;
  const Vec3i c = cell_coords_[k];
  for (int dz = -reach; dz <= reach; ++dz)
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx) {
        const int cell = find(key(c + Vec3i(dx, dy, dz)));
        if (cell >= 0) ranges.emplace_back(cell_begin_[cell], cell_begin_[cell + 1]);
      }
  return ranges;
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
