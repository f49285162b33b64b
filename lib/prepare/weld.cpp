#include "prepare/weld.h"

#include <algorithm>
#include <array>
#include <set>

#include "core/weld.h"

namespace hairfit {

Welded weld_vertices(const Mesh& mesh, double tolerance) {
  Welded w;
  const std::vector<int> kept_as = weld_points(mesh.positions, tolerance);
  const int n = static_cast<int>(mesh.positions.size());
  w.old_to_new.assign(n, -1);
  for (int i = 0; i < n; ++i) {
    if (kept_as[i] != i) {
      w.old_to_new[i] = w.old_to_new[kept_as[i]];
      ++w.merged_vertices;
      continue;
    }
    w.old_to_new[i] = static_cast<int>(w.mesh.positions.size());
    w.new_to_old.push_back(i);
    w.mesh.positions.push_back(mesh.positions[i]);
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
