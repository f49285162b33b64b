#include "prepare/weld.h"

#include <algorithm>
#include <array>
#include <vector>

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
  // A triangle repeating an earlier one's corners (in any order) is dropped: sorted by corners,
  // then by index, the first of each run is the one kept.
  const int m = static_cast<int>(mesh.triangles.size());
  std::vector<std::array<int, 4>> keys(m);
  for (int t = 0; t < m; ++t) {
    const Vec3i& f = mesh.triangles[t];
    std::array<int, 3> c{w.old_to_new[f[0]], w.old_to_new[f[1]], w.old_to_new[f[2]]};
    std::sort(c.begin(), c.end());
    keys[t] = {c[0], c[1], c[2], t};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<char> repeated(m, 0);
  for (int k = 1; k < m; ++k)
    repeated[keys[k][3]] = keys[k][0] == keys[k - 1][0] && keys[k][1] == keys[k - 1][1] && keys[k][2] == keys[k - 1][2];
  for (int t = 0; t < m; ++t) {
    const Vec3i& f = mesh.triangles[t];
    const Vec3i v(w.old_to_new[f[0]], w.old_to_new[f[1]], w.old_to_new[f[2]]);
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] || repeated[t]) {
      ++w.dropped_triangles;
      continue;
    }
    w.mesh.triangles.push_back(v);
  }
  return w;
}

}  // namespace hairfit
