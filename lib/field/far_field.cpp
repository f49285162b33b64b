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


// Signs every far sample (beyond the band) as the robust inside decides it, certified. Along a
// path of grid edges, w(b) = w(a) + J + ∫ ∇w · dx, with J the exact sum of the soup's jumps on
// the path's edges (grid_crossings.h) and |∫ ∇w · dx| ≤ G·(path length), G bounding |∇w| over the
// box the path stays in (rim_bound.h; 0 on a soup without rims). So in each coarse cell, a far
// sample takes w's side of ½ from the far corner that a breadth-first search over far samples
// reaches it from: that corner's estimate plus the jumps on the way, where it lies farther from ½
// than the estimate's error bound plus G times the path. The head's field (`negative_in`) is read
// at the sample itself. Every other far sample, and all of them for several soups, goes to the
// robust inside's own decision. A cell writes only the samples it holds (its lowest index; the
// last cell along an axis also holds the nodes past the last coarse node), so cells run in
// parallel.
// On a soup without rims (closed, consistently oriented parts, integer weights) w is an integer
// off the surface that changes only by the jumps: w(n) = w(ref) + J(ref → n) along any grid path.
// So one estimate at the far coarse node farthest from the surface, certified within ½ of a
// single integer, gives every far sample's w exactly, row by row (w at a row's first node from
// the reference along z then y, then the row's jumps). Returns false, signing nothing, where that
// estimate is not so certified.
bool sign_rimless_far_samples(const GridGeometry& grid, const FarField& far, int c, const GridWindingSigns& soup,
                              const DistanceField* negative_in, const std::vector<std::uint8_t>& in_band,
                              std::vector<double>& values, int threads) {
  constexpr double kRoundoff = 1e-9;  // the direct sum's own round-off, against the true w
  const int nx = grid.dims.x(), ny = grid.dims.y(), nz = grid.dims.z();
  int64_t ref = -1;
  double farthest = 0.0;
  for (int64_t q = 0; q < int64_t(far.values.size()); ++q) {
    const Vec3i v = grid_indices(q, far.dims) * c;
    if (!in_band[grid.index(v.x(), v.y(), v.z())] && std::abs(far.values[q]) > farthest) farthest = std::abs(far.values[q]), ref = q;
  }
  if (ref < 0) return false;
  const Vec3i r = grid_indices(ref, far.dims) * c;
  const WindingEstimate e = soup.soup().estimate(grid.node(r.x(), r.y(), r.z()));
  const double w_ref = std::nearbyint(e.value);
  if (!(e.error_bound + kRoundoff < 0.5) || !(std::abs(e.value - w_ref) <= e.error_bound + kRoundoff)) return false;
  const GridCrossings& jumps = soup.crossings();
  parallel_for(nz, threads, [&](int k) {
    for (int j = 0; j < ny; ++j) {
      int w = int(w_ref) + jumps.path(r, Vec3i(0, j, k));
      int i = 0;
      const int64_t row = grid.index(0, j, k);
      auto sign_to = [&](int last) {  // nodes i … last − 1 take w
        for (; i < last; ++i) {
          const int64_t n = row + i;
          if (in_band[n]) continue;
          const bool in = w > 0 || (negative_in && negative_in->value(grid.node(n)) < 0.0);
          values[n] = in ? -std::abs(values[n]) : std::abs(values[n]);
        }
      };
      jumps.for_each_jump(0, jumps.line(0, 0, j, k), [&](int edge, int jump) {
        sign_to(edge + 1);
        w += jump;
      });
      sign_to(nx);
    }
  });
  return true;
}

void sign_far_samples(const GridGeometry& grid, const FarField& far, int c, const RobustSigns& inside,
                      const std::vector<std::uint8_t>& in_band, std::vector<double>& values, int threads) {
  constexpr double kRoundoff = 1e-9;  // adding an integer to the estimate, and the slack's own sum
  const int nx = grid.dims.x(), ny = grid.dims.y(), nz = grid.dims.z();
  const int cx = far.dims.x(), cy = far.dims.y(), cz = far.dims.z();
  const double h = grid.voxel, inf = std::numeric_limits<double>::infinity();
  const DistanceField* negative_in = inside.negative_in();
  const GridWindingSigns* soup = inside.soups().size() == 1 ? inside.soups()[0].get() : nullptr;
  const bool rimless = soup && soup->rims().rims() == 0;
  if (rimless && sign_rimless_far_samples(grid, far, c, *soup, negative_in, in_band, values, threads)) return;
  auto coarse_at = [&](int i, int j, int k) { return i + int64_t(cx) * (j + int64_t(cy) * k); };
  // Per far coarse node: the soup's estimate there (a bound of −1: none).
  std::vector<WindingEstimate> corner(far.values.size(), WindingEstimate{0.0, -1.0});
  if (soup) {
    parallel_for(cz, threads, [&](int k) {
      for (int j = 0; j < cy; ++j)
        for (int i = 0; i < cx; ++i) {
          const int64_t q = coarse_at(i, j, k), fine = grid.index(c * i, c * j, c * k);
          if (!in_band[fine] && std::isfinite(far.values[q])) corner[q] = soup->soup().estimate(grid.node(fine));
        }
    });
  }
  const int cells_x = cx - 1, cells_y = cy - 1, cells_z = cz - 1;
  std::vector<std::vector<int64_t>> undecided(cells_z);  // per layer of cells
  parallel_for(cells_z, threads, [&](int ck) {
    std::vector<int> seed, steps, jumps, queue;
    for (int cj = 0; cj < cells_y; ++cj)
      for (int ci = 0; ci < cells_x; ++ci) {
        // The cell's closed box, and past it the nodes the last cell along an axis holds.
        const Vec3i lo(c * ci, c * cj, c * ck);
        const Vec3i hi(ci + 1 == cells_x ? nx - 1 : lo.x() + c, cj + 1 == cells_y ? ny - 1 : lo.y() + c,
                       ck + 1 == cells_z ? nz - 1 : lo.z() + c);
        const Vec3i held_hi(ci + 1 == cells_x ? hi.x() : hi.x() - 1, cj + 1 == cells_y ? hi.y() : hi.y() - 1,
                            ck + 1 == cells_z ? hi.z() : hi.z() - 1);
        const Vec3i w = hi - lo + Vec3i::Ones();
        auto local = [&](int i, int j, int k) { return (i - lo.x()) + w.x() * ((j - lo.y()) + w.y() * (k - lo.z())); };
        bool any = false;
        for (int k = lo.z(); k <= held_hi.z() && !any; ++k)
          for (int j = lo.y(); j <= held_hi.y() && !any; ++j)
            for (int i = lo.x(); i <= held_hi.x() && !any; ++i) any = !in_band[grid.index(i, j, k)];
        if (!any) continue;
        const int size = w.x() * w.y() * w.z();
        seed.assign(size, -1);
        steps.assign(size, 0);
        jumps.assign(size, 0);
        queue.clear();
        double g = inf;
        if (soup) {
          // A gradient bound above (|w − ½| at a corner + 2)/h decides nothing (unless the jumps
          // on the way add more than 2): the bound may stop there.
          double widest = 0.0;
          for (int q = 0; q < 8; ++q) {
            const int i = lo.x() + (q & 1) * c, j = lo.y() + (q >> 1 & 1) * c, k = lo.z() + (q >> 2) * c;
            const int64_t coarse = coarse_at(i / c, j / c, k / c);
            if (corner[coarse].error_bound < 0) continue;
            widest = std::max(widest, std::abs(corner[coarse].value - 0.5) + 2.0);
            seed[local(i, j, k)] = int(coarse), queue.push_back(local(i, j, k));
          }
          if (!queue.empty())
            g = rimless ? 0.0 : soup->rims().gradient(grid.node(lo.x(), lo.y(), lo.z()), grid.node(hi.x(), hi.y(), hi.z()), widest / h);
        }
        if (std::isfinite(g)) {
          for (std::size_t q = 0; q < queue.size(); ++q) {
            const int at = queue[q];
            const int i = lo.x() + at % w.x(), j = lo.y() + at / w.x() % w.y(), k = lo.z() + at / (w.x() * w.y());
            const Vec3i v(i, j, k);
            for (int axis = 0; axis < 3; ++axis)
              for (int step : {1, -1}) {
                Vec3i n = v;
                n[axis] += step;
                if (n[axis] < lo[axis] || n[axis] > hi[axis]) continue;
                const int there = local(n.x(), n.y(), n.z());
                if (seed[there] >= 0 || in_band[grid.index(n.x(), n.y(), n.z())]) continue;
                seed[there] = seed[at], steps[there] = steps[at] + 1;
                jumps[there] = jumps[at] + soup->crossings().along(axis, soup->crossings().line(axis, i, j, k), v[axis], n[axis]);
                queue.push_back(there);
              }
          }
        }
        for (int k = lo.z(); k <= held_hi.z(); ++k)
          for (int j = lo.y(); j <= held_hi.y(); ++j)
            for (int i = lo.x(); i <= held_hi.x(); ++i) {
              const int64_t n = grid.index(i, j, k);
              if (in_band[n]) continue;
              const int at = local(i, j, k);
              const int from = seed[at];
              const double value = from < 0 ? 0.5 : corner[from].value + jumps[at];
              const double slack = from < 0 ? inf : corner[from].error_bound + g * h * steps[at] + kRoundoff;
              if (!(std::abs(value - 0.5) > slack)) {
                undecided[ck].push_back(n);
                continue;
              }
              const bool in = value > 0.5 || (negative_in && negative_in->value(grid.node(n)) < 0.0);
              values[n] = in ? -std::abs(values[n]) : std::abs(values[n]);
            }
      }
  });
  std::vector<int64_t> nodes;
  for (const std::vector<int64_t>& layer : undecided) nodes.insert(nodes.end(), layer.begin(), layer.end());
  std::sort(nodes.begin(), nodes.end());
  std::vector<double> distance(nodes.size());
  for (std::size_t q = 0; q < nodes.size(); ++q) distance[q] = std::abs(values[nodes[q]]);
  const std::vector<std::uint8_t> in = inside.decide(nodes, distance, threads);
  for (std::size_t q = 0; q < nodes.size(); ++q) values[nodes[q]] = in[q] ? -std::abs(values[nodes[q]]) : std::abs(values[nodes[q]]);
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
        int sign = 1;  // with `inside`: signed below
        if (!inside) {
          double interpolated;
          trilinear<false>(signed_corners, frac, interpolated, nullptr);
          sign = interpolated < 0 ? -1 : 1;
        }
        values[row + i] = sign * magnitude;
      }
    }
  });
  if (inside) sign_far_samples(grid, far, c, *inside, in_band, values, threads);
}

}  // namespace hairfit::field
