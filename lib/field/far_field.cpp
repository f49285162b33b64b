#include "field/far_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "field/cell_corners.h"

namespace hairfit::field {

FarField make_far_field(const MeshFeatures& features, const ScanRegions& regions, const GridGeometry& grid,
                        const BandScan& band, double r, int coarse_factor, int threads) {
  const int c = coarse_factor;
  FarField out;
  for (int d = 0; d < 3; ++d) out.dims[d] = (grid.dims[d] - 1) / c + 1;
  const int nx = out.dims.x(), ny = out.dims.y(), nz = out.dims.z();
  const int64_t count = int64_t(nx) * ny * nz;
  auto at = [&](int i, int j, int k) { return i + int64_t(nx) * (j + int64_t(ny) * k); };
  const GridGeometry coarse{grid.origin, c * grid.voxel, out.dims};
  auto node = [&](int i, int j, int k) { return coarse.node(i, j, k); };

  // Exact values for every coarse node a fine voxel just outside the band interpolates from.
  const BandScan near = scan_band(features, regions, coarse, r + std::sqrt(3.0) * coarse.voxel, threads);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Vec3> closest(count);
  std::vector<int32_t> feature(count, -1);
  std::vector<double> distance(count, inf);
  std::vector<signed char> sign(count, 1);
  std::vector<char> fixed(count, 0);
  bool any_seed = false;
  for (int64_t q = 0; q < count; ++q) {
    if (near.key[q] < 0) continue;
    closest[q] = closest_on_feature(features, near.key[q], coarse.node(q)).point;
    feature[q] = near.key[q];
    distance[q] = std::abs(near.value[q]);
    sign[q] = near.value[q] < 0 ? -1 : 1;
    fixed[q] = 1;
    any_seed = true;
  }
  if (!any_seed) {
    // A mesh much smaller than the coarse spacing can miss every coarse node: seed the node
    // nearest to a mesh vertex with its exact closest point (brute force over all features).
    const Vec3 u = (features.vertices[0] - grid.origin) / coarse.voxel;
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


// Whether the test must decide every pending sample of the (disagreeing) coarse cell at `base`:
// where it is a seam of the inside at its own scale (is_seam), the sign changes inside it in empty
// space, where no flood from the band can tell where; where its corners all share a sign, the band
// samples that disagree with them bound a pocket the corners do not see, and a flood from them
// could run past it.
bool ask_every_sample(const FarField& far, int64_t base, double spacing) {
  const int64_t dy = far.dims.x(), dz = int64_t(far.dims.x()) * far.dims.y();
  double corners[8];
  bool positive = false, negative = false;
  for (int q = 0; q < 8; ++q) {
    corners[q] = far.values[base + (q & 1) + dy * (q >> 1 & 1) + dz * (q >> 2)];
    positive = positive || corners[q] > 0;
    negative = negative || corners[q] < 0;
  }
  return !(positive && negative) || is_seam(corners, spacing);
}

// Signs the pending far samples of every coarse cell whose corners and band samples differ: a
// flood through the cell's far samples from the samples whose sign is known (the band's, the
// coarse nodes', and far samples of agreeing cells), in index order; where two signs meet, where
// nothing reaches, and in cells ask_every_sample names, the robust inside decides, all such
// samples at once. A cell writes only the samples it holds (lowest index), so cells run in
// parallel.
void settle_pending(const GridGeometry& grid, const FarField& far, int c, const RobustSigns& inside,
                    const std::vector<std::uint8_t>& in_band, std::vector<char>& pending, std::vector<double>& values,
                    int threads) {
  const int nx = grid.dims.x(), ny = grid.dims.y(), nz = grid.dims.z();
  const int cx = far.dims.x(), cy = far.dims.y(), cz = far.dims.z();
  auto owner = [c](int n, int cells) { return std::min(n / c, cells - 1); };
  std::vector<std::vector<int64_t>> undecided(cz - 1);  // per layer of cells
  parallel_for(cz - 1, threads, [&](int ck) {
    const int w = c + 1, cells_x = cx - 1, cells_y = cy - 1, cells_z = cz - 1;
    std::vector<signed char> sign(w * w * w);
    std::vector<char> conflict(w * w * w);
    std::vector<int> queue;
    for (int cj = 0; cj < cells_y; ++cj)
      for (int ci = 0; ci < cells_x; ++ci) {
        const int i0 = c * ci, j0 = c * cj, k0 = c * ck;
        // The samples this cell holds, and whether any is pending.
        auto held = [&](int i, int j, int k) {
          return owner(i, cells_x) == ci && owner(j, cells_y) == cj && owner(k, cells_z) == ck;
        };
        bool any = false;
        for (int k = k0; k <= std::min(nz - 1, k0 + c) && !any; ++k)
          for (int j = j0; j <= std::min(ny - 1, j0 + c) && !any; ++j)
            for (int i = i0; i <= std::min(nx - 1, i0 + c); ++i)
              if (pending[grid.index(i, j, k)] && held(i, j, k)) {
                any = true;
                break;
              }
        if (!any) continue;
        const int64_t base = ci + int64_t(cx) * (cj + int64_t(cy) * ck);
        const bool seam = ask_every_sample(far, base, c * grid.voxel);
        // Seeds: every sample of the cell's closed box whose sign is known.
        queue.clear();
        for (int k = 0; k < w; ++k)
          for (int j = 0; j < w; ++j)
            for (int i = 0; i < w; ++i) {
              const int local = i + w * (j + w * k);
              sign[local] = 0;
              if (i0 + i >= nx || j0 + j >= ny || k0 + k >= nz) continue;
              const int64_t n = grid.index(i0 + i, j0 + j, k0 + k);
              const bool corner = i % c == 0 && j % c == 0 && k % c == 0;
              if (corner) {
                const int64_t coarse = (i0 + i) / c + int64_t(cx) * ((j0 + j) / c + int64_t(cy) * ((k0 + k) / c));
                sign[local] = far.values[coarse] < 0 ? -1 : 1;
                queue.push_back(local);
              } else if (in_band[n] || !pending[n]) {
                sign[local] = values[n] < 0 ? -1 : 1;
                queue.push_back(local);
              }
            }
        std::fill(conflict.begin(), conflict.end(), 0);
        for (std::size_t q = 0; q < queue.size() && !seam; ++q) {
          const int local = queue[q];
          const int i = local % w, j = (local / w) % w, k = local / (w * w);
          const int steps[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
          for (const auto& st : steps) {
            const int a = i + st[0], b = j + st[1], d = k + st[2];
            if (a < 0 || b < 0 || d < 0 || a >= w || b >= w || d >= w) continue;
            if (i0 + a >= nx || j0 + b >= ny || k0 + d >= nz) continue;
            const int there = a + w * (b + w * d);
            const int64_t n = grid.index(i0 + a, j0 + b, k0 + d);
            if (!pending[n] || in_band[n]) continue;
            if (sign[there] == 0) {
              sign[there] = sign[local];
              queue.push_back(there);
            } else if (sign[there] != sign[local]) {
              conflict[there] = 1;
            }
          }
        }
        for (int k = 0; k < w; ++k)
          for (int j = 0; j < w; ++j)
            for (int i = 0; i < w; ++i) {
              if (i0 + i >= nx || j0 + j >= ny || k0 + k >= nz || !held(i0 + i, j0 + j, k0 + k)) continue;
              const int64_t n = grid.index(i0 + i, j0 + j, k0 + k);
              if (!pending[n]) continue;
              const int local = i + w * (j + w * k);
              const int s = sign[local];
              if (seam || s == 0 || conflict[local]) {
                undecided[ck].push_back(n);
              } else {
                values[n] = s * std::abs(values[n]);
              }
            }
      }
  });
  std::vector<int64_t> nodes;
  for (const std::vector<int64_t>& layer : undecided) nodes.insert(nodes.end(), layer.begin(), layer.end());
  std::sort(nodes.begin(), nodes.end());
  std::vector<double> distance(nodes.size());
  for (std::size_t q = 0; q < nodes.size(); ++q) distance[q] = values[nodes[q]];
  const std::vector<std::uint8_t> in = inside.decide(nodes, distance, threads);
  for (std::size_t q = 0; q < nodes.size(); ++q) values[nodes[q]] = in[q] ? -values[nodes[q]] : values[nodes[q]];
}

}  // namespace

void fill_beyond_band(const MeshFeatures& features, const GridGeometry& grid, const FarField& far, int coarse_factor, double r,
                      const RobustSigns* inside, const std::vector<std::uint8_t>& in_band, std::vector<double>& values,
                      int threads) {
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
            if (!in_band[row + fi]) continue;
            const signed char s = values[row + fi] < 0 ? -1 : 1;
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

  std::vector<char> pending(inside ? values.size() : 0, 0);  // far samples whose cell did not agree
  parallel_for(nz, threads, [&](int k) {
    for (int j = 0; j < ny; ++j) {
      const int64_t row = grid.index(0, j, k);
      for (int i = 0; i < nx; ++i) {
        if (in_band[row + i]) continue;
        const int64_t base = coarse_at(ax.cell[i], ay.cell[j], az.cell[k]);
        const int64_t dy = cx, dz = int64_t(cx) * cy;
        const double* s = far.values.data() + base;
        const Vec3 p = grid.node(i, j, k);
        double signed_corners[8], magnitudes[8];
        for (int q = 0; q < 8; ++q) {
          signed_corners[q] = s[(q & 1) + dy * (q >> 1 & 1) + dz * (q >> 2)];
          magnitudes[q] = std::abs(signed_corners[q]);
        }
        const double frac[3] = {ax.frac[i], ay.frac[j], az.frac[k]};
        double magnitude;
        trilinear<false>(magnitudes, frac, magnitude, nullptr);
        signed char agreed = 0;
        if (inside) agreed = agree[ax.cell[i] + int64_t(cx - 1) * (ay.cell[j] + int64_t(cy - 1) * az.cell[k])];
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
          sign = agreed;  // 0: pending, settled below
          if (agreed == 0) pending[row + i] = 1;
        } else {
          double interpolated;
          trilinear<false>(signed_corners, frac, interpolated, nullptr);
          sign = interpolated < 0 ? -1 : 1;
        }
        values[row + i] = sign == 0 ? magnitude : sign * magnitude;
      }
    }
  });
  if (inside) settle_pending(grid, far, c, *inside, in_band, pending, values, threads);
}

}  // namespace hairfit::field
