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
  // Cells at least `tolerance` wide, so a merge partner lies in a point's own cell or one of the
  // 26 around it; never narrower than 2⁻⁴⁰ of the largest coordinate, so cell indices stay far
  // from overflowing (a wider cell only costs more distance tests).
  double cell = std::max(tolerance, std::ldexp(largest, -40));
  if (!(cell > 0.0)) cell = 1.0;
  auto cell_of = [cell](const Vec3& p) {
    return Cell{static_cast<long long>(std::floor(p.x() / cell)), static_cast<long long>(std::floor(p.y() / cell)),
                static_cast<long long>(std::floor(p.z() / cell))};
  };

  const int reach = tolerance > 0.0 ? 1 : 0;  // equal points share a cell; near ones may be next door
  const int n = static_cast<int>(points.size());
  std::vector<int> kept_as(n, -1);
  std::unordered_map<Cell, std::vector<int>, CellHash> cells;  // kept points, ascending, per cell
  cells.reserve(points.size());
  for (int i = 0; i < n; ++i) {
    const Vec3& p = points[i];
    const Cell c = cell_of(p);
    int partner = -1;
    for (int dx = -reach; dx <= reach; ++dx)
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dz = -reach; dz <= reach; ++dz) {
          const auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == cells.end()) continue;
          for (int k : it->second) {
            if (partner >= 0 && k > partner) break;
            // Exact welding compares coordinates, as the norm of a difference below 1e-154 underflows to 0.
            if (reach == 0 ? points[k] == p : (points[k] - p).norm() <= tolerance) {
              partner = k;
              break;
            }
          }
        }
    if (partner >= 0) {
      kept_as[i] = partner;
    } else {
      kept_as[i] = i;
      cells[c].push_back(i);
    }
  }
  return kept_as;
}

}  // namespace hairfit
