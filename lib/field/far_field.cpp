#include "field/far_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"

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
  std::vector<int32_t> feature(count, -1);
  std::vector<double> distance(count, inf);
  std::vector<signed char> sign(count, 1);
  std::vector<char> fixed(count, 0);
  bool any_seed = false;
  for (int64_t q = 0; q < count; ++q) {
    if (near.key[q] < 0) continue;
    const int i = int(q % nx), j = int((q / nx) % ny), k = int(q / (int64_t(nx) * ny));
    closest[q] = closest_on_feature(features, near.key[q], node(i, j, k)).point;
    feature[q] = near.key[q];
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
        feature[at(i, j, k)] = key;
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
                feature[here] = feature[there];
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

  out.key = std::move(feature);
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

namespace hairfit::field {

namespace {

// Per fine index along one axis: the coarse cell that holds the node (the last cell for the last
// node) and the node's fraction in it.
struct CoarseAxis {
  std::vector<int> cell;
  std::vector<double> frac;
};

CoarseAxis coarse_axis(int fine_count, int coarse_count, int c) {
  CoarseAxis a;
  a.cell.resize(fine_count);
  a.frac.resize(fine_count);
  for (int n = 0; n < fine_count; ++n) {
    a.cell[n] = std::min(n / c, coarse_count - 2);
    a.frac[n] = double(n - c * a.cell[n]) / c;
  }
  return a;
}

// The trilinear interpolation of 8 corner values (x fastest) at fractions (fx, fy, fz).
double lerp3(const double v[8], double fx, double fy, double fz) {
  const double x0 = 1 - fx, y0 = 1 - fy, z0 = 1 - fz;
  const double c00 = v[0] * x0 + v[1] * fx, c10 = v[2] * x0 + v[3] * fx;
  const double c01 = v[4] * x0 + v[5] * fx, c11 = v[6] * x0 + v[7] * fx;
  return (c00 * y0 + c10 * fy) * z0 + (c01 * y0 + c11 * fy) * fz;
}

}  // namespace

void fill_beyond_band(const MeshFeatures& features, const GridGeometry& grid, const FarField& far, int coarse_factor, double r,
                      const InsideTest& inside, std::vector<double>& values, int threads) {
  const int c = coarse_factor;
  const int nx = grid.dims.x(), ny = grid.dims.y(), nz = grid.dims.z();
  const int cx = far.dims.x(), cy = far.dims.y(), cz = far.dims.z();
  const CoarseAxis ax = coarse_axis(nx, cx, c), ay = coarse_axis(ny, cy, c), az = coarse_axis(nz, cz, c);
  auto coarse_at = [&](int i, int j, int k) { return i + int64_t(cx) * (j + int64_t(cy) * k); };
  constexpr double kInf = std::numeric_limits<double>::infinity();

  // With a test: the sign each coarse cell agrees on (+1, −1, or 0 where its corners or the band
  // samples within it, faces included, differ). Each coarse layer is written by one work item.
  std::vector<signed char> agree;
  if (inside) {
    const int64_t cells = int64_t(cx - 1) * (cy - 1) * (cz - 1);
    agree.assign(cells, 0);
    auto cell_at = [&](int i, int j, int k) { return i + int64_t(cx - 1) * (j + int64_t(cy - 1) * k); };
    parallel_for(cz - 1, threads, [&](int k) {
      for (int j = 0; j + 1 < cy; ++j)
        for (int i = 0; i + 1 < cx; ++i) {
          int positive = 0;
          for (int q = 0; q < 8; ++q) positive += far.values[coarse_at(i + (q & 1), j + (q >> 1 & 1), k + (q >> 2))] >= 0;
          agree[cell_at(i, j, k)] = positive == 8 ? 1 : positive == 0 ? -1 : 0;
        }
      // The band samples of the layer's cells: fine layers c·k to c·(k + 1), faces included.
      for (int fk = c * k; fk <= std::min(nz - 1, c * (k + 1)); ++fk)
        for (int fj = 0; fj < ny; ++fj) {
          const int64_t row = grid.index(0, fj, fk);
          for (int fi = 0; fi < nx; ++fi) {
            const double v = values[row + fi];
            if (v == kInf) continue;
            const signed char s = v < 0 ? -1 : 1;
            // The cells whose closed box holds the node (two per axis on a cell face).
            const int i1 = std::min(fi / c, cx - 2), i0 = fi % c == 0 && fi > 0 ? fi / c - 1 : i1;
            const int j1 = std::min(fj / c, cy - 2), j0 = fj % c == 0 && fj > 0 ? fj / c - 1 : j1;
            for (int ci = i0; ci <= i1; ++ci)
              for (int cj = j0; cj <= j1; ++cj) {
                signed char& a = agree[cell_at(ci, cj, k)];
                if (a != s) a = 0;
              }
          }
        }
    });
  }

  parallel_for(nz, threads, [&](int k) {
    for (int j = 0; j < ny; ++j) {
      const int64_t row = grid.index(0, j, k);
      for (int i = 0; i < nx; ++i) {
        if (values[row + i] != kInf) continue;
        const int64_t base = coarse_at(ax.cell[i], ay.cell[j], az.cell[k]);
        const int64_t dy = cx, dz = int64_t(cx) * cy;
        const double* s = far.values.data() + base;
        const Vec3 p = grid.node(i, j, k);
        double signed_corners[8], magnitudes[8];
        for (int q = 0; q < 8; ++q) {
          signed_corners[q] = s[(q & 1) + dy * (q >> 1 & 1) + dz * (q >> 2)];
          magnitudes[q] = std::abs(signed_corners[q]);
        }
        double magnitude = lerp3(magnitudes, ax.frac[i], ay.frac[j], az.frac[k]);
        if (!(magnitude > r)) {
          // The interpolant dips below the band's width (a concave distance, as inside a curved
          // surface): the distance to the nearest of the features the corners are closest to
          // instead, which is never below the true distance, itself beyond the band here.
          double best = kInf;
          for (int q = 0; q < 8; ++q) {
            const int32_t feature = far.key[base + (q & 1) + dy * (q >> 1 & 1) + dz * (q >> 2)];
            if (feature >= 0) best = std::min(best, (p - closest_on_feature(features, feature, p).point).squaredNorm());
          }
          magnitude = std::max(r, std::sqrt(best));
        }
        int sign;
        if (inside) {
          const signed char a = agree[ax.cell[i] + int64_t(cx - 1) * (ay.cell[j] + int64_t(cy - 1) * az.cell[k])];
          sign = a != 0 ? a : inside(p) ? -1 : 1;
        } else {
          sign = lerp3(signed_corners, ax.frac[i], ay.frac[j], az.frac[k]) < 0 ? -1 : 1;
        }
        values[row + i] = sign * magnitude;
      }
    }
  });
}

}  // namespace hairfit::field
