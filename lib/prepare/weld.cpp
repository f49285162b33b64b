#include "prepare/weld.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <unordered_map>

namespace hairfit {

namespace {

struct CellHash {
  std::size_t operator()(const std::array<long long, 3>& c) const {
    return static_cast<std::size_t>(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
  }
};

}  // namespace

Welded weld_vertices(const Mesh& mesh, double tolerance) {
  Welded w;
  const int n = static_cast<int>(mesh.positions.size());
  w.old_to_new.assign(n, -1);
  // Kept vertices hashed by the cell of side `tolerance` they fall in; a merge partner of a vertex
  // lies in its own cell or one of the 26 around it.
  const double cell = tolerance > 0.0 ? tolerance : 1.0;
  std::unordered_map<std::array<long long, 3>, std::vector<int>, CellHash> cells;
  auto cell_of = [&](const Vec3& p) {
    return std::array<long long, 3>{static_cast<long long>(std::floor(p.x() / cell)),
                                    static_cast<long long>(std::floor(p.y() / cell)),
                                    static_cast<long long>(std::floor(p.z() / cell))};
  };
  for (int i = 0; i < n; ++i) {
    const Vec3& p = mesh.positions[i];
    const std::array<long long, 3> c = cell_of(p);
    int partner = -1;
    for (int dx = -1; dx <= 1 && partner < 0; ++dx)
      for (int dy = -1; dy <= 1 && partner < 0; ++dy)
        for (int dz = -1; dz <= 1 && partner < 0; ++dz) {
          const auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == cells.end()) continue;
          for (int k : it->second)
            if ((w.mesh.positions[k] - p).norm() <= tolerance) {
              partner = k;
              break;
            }
        }
    if (partner >= 0) {
      w.old_to_new[i] = partner;
      ++w.merged_vertices;
      continue;
    }
    w.old_to_new[i] = static_cast<int>(w.mesh.positions.size());
    w.new_to_old.push_back(i);
    cells[c].push_back(w.old_to_new[i]);
    w.mesh.positions.push_back(p);
  }
  std::set<std::array<int, 3>> seen;
  for (const Vec3i& t : mesh.triangles) {
    const Vec3i m(w.old_to_new[t[0]], w.old_to_new[t[1]], w.old_to_new[t[2]]);
    std::array<int, 3> key{m[0], m[1], m[2]};
    std::sort(key.begin(), key.end());
    if (m[0] == m[1] || m[1] == m[2] || m[0] == m[2] || !seen.insert(key).second) {
      ++w.dropped_triangles;
      continue;
    }
    w.mesh.triangles.push_back(m);
  }
  return w;
}

}  // namespace hairfit
