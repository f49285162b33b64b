#include "field/far_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hairfit::field {

FarField make_far_field(const MeshFeatures& features, const GridGeometry& grid, const BandScan& band, double r,
                        int coarse_factor, int threads) {
  const int c = coarse_factor;
  FarField out;
  for (int d = 0; d < 3; ++d) out.dims[d] = (grid.dims[d] - 1) / c + 1;
  const int nx = out.dims.x(), ny = out.dims.y(), nz = out.dims.z();
  const int64_t count = int64_t(nx) * ny * nz;
  auto at = [&](int i, int j, int k) { return i + int64_t(nx) * (j + int64_t(ny) * k); };
  const GridGeometry coarse{grid.origin, c * grid.h, out.dims};
  auto node = [&](int i, int j, int k) { return coarse.node(i, j, k); };

  // Exact values for every coarse node a fine voxel just outside the band interpolates from.
  const BandScan near = scan_band(features, coarse, r + std::sqrt(3.0) * coarse.h, threads);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Vec3> closest(count);
  std::vector<double> distance(count, inf);
  std::vector<signed char> sign(count, 1);
  std::vector<char> fixed(count, 0);
  bool any_seed = false;
  for (int64_t q = 0; q < count; ++q) {
    if (near.key[q] < 0) continue;
    const int i = int(q % nx), j = int((q / nx) % ny), k = int(q / (int64_t(nx) * ny));
    closest[q] = closest_on_feature(features, near.key[q], node(i, j, k)).point;
    distance[q] = std::abs(near.value[q]);
    sign[q] = near.value[q] < 0 ? -1 : 1;
    fixed[q] = 1;
    any_seed = true;
  }
  if (!any_seed) {
    // A mesh much smaller than the coarse spacing can miss every coarse node: seed the node
    // nearest to a mesh vertex with its exact closest point (brute force over all features).
    const Vec3 u = (features.vertices[0] - grid.origin) / coarse.h;
    const int i = std::clamp(int(std::lround(u.x())), 0, nx - 1);
    const int j = std::clamp(int(std::lround(u.y())), 0, ny - 1);
    const int k = std::clamp(int(std::lround(u.z())), 0, nz - 1);
    const Vec3 p = node(i, j, k);
    const int keys = int(features.faces.size() + features.edges.size() + features.vertices.size());
    Vec3 best_normal = Vec3::Zero();
    for (int key = 0; key < keys; ++key) {
      const FeaturePoint fp = closest_on_feature(features, key, p);
      if (key < int(features.faces.size())) {  // a face counts only where p projects inside it
        const Vec3i& t = features.faces[key];
        bool inside = true;
        for (int e = 0; e < 3; ++e) {
          const Vec3& a = features.vertices[t[e]];
          const Vec3& b = features.vertices[t[(e + 1) % 3]];
          if ((b - a).cross(fp.point - a).dot(fp.normal) < 0) inside = false;
        }
        if (!inside) continue;
      }
      const double d = (p - fp.point).norm();
      if (d < distance[at(i, j, k)]) {
        distance[at(i, j, k)] = d;
        closest[at(i, j, k)] = fp.point;
        best_normal = fp.normal;
      }
    }
    sign[at(i, j, k)] = (p - closest[at(i, j, k)]).dot(best_normal) < 0 ? -1 : 1;
    fixed[at(i, j, k)] = 1;
  }

  // Sweeps in the 8 diagonal orders; each node looks at its 3 upwind neighbours. Repeated until
  // nothing changes (two rounds suffice for most surfaces; capped for safety).
  for (int round = 0; round < 6; ++round) {
    bool changed = false;
    for (int dir = 0; dir < 8; ++dir) {
      const int sx = dir & 1 ? -1 : 1, sy = dir & 2 ? -1 : 1, sz = dir & 4 ? -1 : 1;
      for (int kk = 0; kk < nz; ++kk) {
        const int k = sz > 0 ? kk : nz - 1 - kk;
        for (int jj = 0; jj < ny; ++jj) {
          const int j = sy > 0 ? jj : ny - 1 - jj;
          for (int ii = 0; ii < nx; ++ii) {
            const int i = sx > 0 ? ii : nx - 1 - ii;
            const int64_t here = at(i, j, k);
            if (fixed[here]) continue;
            const Vec3 p = node(i, j, k);
            const int ni[3] = {i - sx, i, i};
            const int nj[3] = {j, j - sy, j};
            const int nk[3] = {k, k, k - sz};
            for (int q = 0; q < 3; ++q) {
              if (ni[q] < 0 || ni[q] >= nx || nj[q] < 0 || nj[q] >= ny || nk[q] < 0 || nk[q] >= nz) continue;
              const int64_t there = at(ni[q], nj[q], nk[q]);
              if (distance[there] == inf) continue;
              const double d = (p - closest[there]).norm();
              if (d < distance[here]) {
                distance[here] = d;
                closest[here] = closest[there];
                sign[here] = sign[there];
                changed = true;
              }
            }
          }
        }
      }
    }
    if (!changed) break;
  }

  out.values.resize(count);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int64_t here = at(i, j, k);
        const int64_t fine = grid.index(c * i, c * j, c * k);
        if (band.key[fine] >= 0) {
          out.values[here] = band.value[fine];  // exact, and equal to the fine sample
        } else {
          out.values[here] = sign[here] * distance[here];
        }
      }
  return out;
}

}  // namespace hairfit::field
