#include "core/weld.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace hairfit {

namespace {

using Cell = std::array<long long, 3>;

struct CellHash {
  std::size_t operator()(const Cell& c) const {
    // Unsigned arithmetic: cell indices reach 2⁴⁰, and the products wrap around.
    const auto u = [](long long x) { return static_cast<std::size_t>(static_cast<unsigned long long>(x)); };
    return u(c[0]) * 73856093u ^ u(c[1]) * 19349663u ^ u(c[2]) * 83492791u;
  }
};

}  // namespace

std::vector<int> weld_points(const std::vector<Vec3>& points, double tolerance) {
  if (!(tolerance >= 0.0)) throw std::invalid_argument("weld_points: the tolerance must be ≥ 0");
  double largest = 0.0;
  for (const Vec3& p : points) {
    if (!p.allFinite()) throw std::invalid_argument("weld_points: a point is not finite");
    largest = std::max(largest, p.cwiseAbs().maxCoeff());
  }
  // Cells at least four tolerances wide (never narrower than 2⁻⁴⁰ of the largest coordinate, so
  // cell indices stay far from overflowing): a merge partner lies in a point's own cell or, along
  // each axis, in the neighbour whose border the point lies within the tolerance of, which is at
  // most one and on average half of the axes. The cells looked in always hold every point within
  // the tolerance (the border test is generous), so the partner is the same as over all 27.
  double cell = std::max(4.0 * tolerance, std::ldexp(largest, -40));
  if (!(cell > 0.0)) cell = 1.0;
  auto cell_of = [cell](const Vec3& p) {
    return Cell{static_cast<long long>(std::floor(p.x() / cell)), static_cast<long long>(std::floor(p.y() / cell)),
                static_cast<long long>(std::floor(p.z() / cell))};
  };
  const double near_border = tolerance > 0.0 ? 1.01 * tolerance + 1e-9 * cell : -1.0;

  const int n = static_cast<int>(points.size());
  std::vector<int> kept_as(n, -1);
  // Per cell its kept points, ascending: the first and last, and each one's successor in `next`.
  std::unordered_map<Cell, std::pair<int, int>, CellHash> cells;
  std::vector<int> next(n, -1);
  cells.reserve(points.size());
  for (int i = 0; i < n; ++i) {
    const Vec3& p = points[i];
    const Cell c = cell_of(p);
    // Per axis the cell offsets to look in: 0, and −1 or +1 next to a border.
    int offsets[3][2], count[3];
    for (int a = 0; a < 3; ++a) {
      offsets[a][0] = 0;
      count[a] = 1;
      const double low = p[a] - static_cast<double>(c[a]) * cell, high = static_cast<double>(c[a] + 1) * cell - p[a];
      if (low <= near_border) offsets[a][count[a]++] = -1;
      else if (high <= near_border) offsets[a][count[a]++] = 1;
    }
    int partner = -1;
    for (int x = 0; x < count[0]; ++x)
      for (int y = 0; y < count[1]; ++y)
        for (int z = 0; z < count[2]; ++z) {
          const auto it = cells.find({c[0] + offsets[0][x], c[1] + offsets[1][y], c[2] + offsets[2][z]});
          if (it == cells.end()) continue;
          for (int k = it->second.first; k >= 0; k = next[k]) {
            if (partner >= 0 && k > partner) break;
            // Exact welding compares coordinates, as the norm of a difference below 1e-154 underflows to 0.
            if (tolerance == 0.0 ? points[k] == p : (points[k] - p).norm() <= tolerance) {
              partner = k;
              break;
            }
          }
        }
    if (partner >= 0) {
      kept_as[i] = partner;
    } else {
      kept_as[i] = i;
      const auto [it, added] = cells.try_emplace(c, i, i);
      if (!added) next[it->second.second] = i, it->second.second = i;
    }
  }
  return kept_as;
}

}  // namespace hairfit
