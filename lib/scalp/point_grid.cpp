#include "scalp/point_grid.h"

#include <numeric>
#include <stdexcept>

namespace hairfit {

PointGrid::PointGrid(const std::vector<Vec3>& points, double cell) : cell_(cell) {
  if (!(cell > 0) || !std::isfinite(cell)) throw std::invalid_argument("PointGrid: cell size must be positive");
  origin_ = Vec3::Zero();
  if (!points.empty()) {
    origin_ = points.front();
    for (const Vec3& p : points) origin_ = origin_.cwiseMin(p);
  }
  std::vector<std::uint64_t> keys(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) keys[i] = key(cell_of(points[i]));
  // (key, index) pairs sort faster than indices compared through the key array; the order is the
  // same: by cell key, then by index.
  std::vector<std::pair<std::uint64_t, int>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) keyed[i] = {keys[i], static_cast<int>(i)};
  std::sort(keyed.begin(), keyed.end());
  order_.resize(points.size());
  sorted_.resize(points.size());
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    order_[k] = keyed[k].second;
    sorted_[k] = points[order_[k]];
  }
  for (std::size_t k = 0; k < order_.size();) {
    std::size_t e = k;
    while (e < order_.size() && keyed[e].first == keyed[k].first) ++e;
    cell_keys_.push_back(keyed[k].first);
    cell_begin_.push_back(static_cast<int>(k));
    const Vec3i c = cell_of(sorted_[k]);
    cell_coords_.push_back(c);
    if (k == 0) occupied_lo_ = occupied_hi_ = c;
    occupied_lo_ = occupied_lo_.cwiseMin(c);
    occupied_hi_ = occupied_hi_.cwiseMax(c);
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

std::vector<PointGrid::CellRange> PointGrid::neighbourhood(int k, int reach) const {
  std::vector<CellRange> ranges;
  for_each_cell_near(cell_coords_[k], reach,
                     [&](int cell) { ranges.push_back({cell_begin_[cell], cell_begin_[cell + 1], cell_coords_[cell]}); });
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
