// A hashed uniform grid over points in 3D (or 2D with z = 0) for fixed-radius neighbour queries.
// Built once, then read-only: safe to query from many threads. Queries visit points in a fixed
// order (cells in x-fastest order, points by index within a cell), so sums over neighbours are
// deterministic.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/types.h"

namespace hairfit {

class PointGrid {
 public:
  // cell: edge length of a grid cell (> 0), in the points' unit.
  PointGrid(const std::vector<Vec3>& points, double cell);

  double cell() const { return cell_; }

  // Calls visit(index, squared_distance) for every point within `radius` of p.
  template <class Visit>
  void for_each_within(const Vec3& p, double radius, Visit&& visit) const {
    const double r2 = radius * radius;
    const int reach_x = static_cast<int>(std::ceil(radius / cell_));
    const Vec3i c = cell_of(p);
    for (int dz = -reach_x; dz <= reach_x; ++dz)
      for (int dy = -reach_x; dy <= reach_x; ++dy)
        for (int dx = -reach_x; dx <= reach_x; ++dx) {
          const auto it = cells_.find(key(c + Vec3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (int k = it->second.first; k < it->second.second; ++k) {
            const int i = order_[k];
            const double d2 = (points_[i] - p).squaredNorm();
            if (d2 <= r2) visit(i, d2);
          }
        }
  }

  // Index of the nearest point other than `exclude` (−1 for none), searching outward up to max_radius.
  int nearest(const Vec3& p, int exclude, double max_radius) const;

 private:
  Vec3i cell_of(const Vec3& p) const {
    return Vec3i(static_cast<int>(std::floor((p.x() - origin_.x()) / cell_)),
                 static_cast<int>(std::floor((p.y() - origin_.y()) / cell_)),
                 static_cast<int>(std::floor((p.z() - origin_.z()) / cell_)));
  }
  static std::uint64_t key(const Vec3i& c) {
    const auto f = [](int v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffff; };
    return f(c.x()) | (f(c.y()) << 21) | (f(c.z()) << 42);
  }

  std::vector<Vec3> points_;
  double cell_;
  Vec3 origin_;
  std::vector<int> order_;  // point indices sorted by cell key, then index
  std::unordered_map<std::uint64_t, std::pair<int, int>> cells_;
};

}  // namespace hairfit
