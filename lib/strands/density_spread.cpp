#include "strands/density_spread.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/parallel.h"
#include "core/trilinear.h"

namespace hairfit {

namespace {

std::size_t node_index(const Vec3i& dims, int i, int j, int k) {
  return (static_cast<std::size_t>(k) * dims.y() + j) * dims.x() + i;
}

// Node coordinates of p: the base node (clamped so that base + 1 stays on the lattice) and the
// fractions past it.
void locate(const Vec3& p, const Vec3& lower, double h, const Vec3i& dims, Vec3i& base, Vec3& t) {
  for (int a = 0; a < 3; ++a) {
    const double q = (p[a] - lower[a]) / h;
    const int b = std::clamp(static_cast<int>(std::floor(q)), 0, std::max(0, dims[a] - 2));
    base[a] = b;
    t[a] = q - b;
  }
}

// One pass of [1 2 1]/4 along axis `a` (values beyond the lattice are 0) into `out` (resized,
// every value written), which then swaps with v. Rows along x are walked in memory order whatever
// the axis, so the neighbours along y and z stream through the cache as whole rows.
void smooth_axis(std::vector<double>& v, std::vector<double>& out, const Vec3i& dims, int a, int threads) {
  const std::ptrdiff_t stride = a == 0 ? 1 : a == 1 ? dims.x() : static_cast<std::ptrdiff_t>(dims.x()) * dims.y();
  out.resize(v.size());
  parallel_for_ranges(dims.y() * dims.z(), 64, threads, [&](int begin, int end) {
    for (int row = begin; row < end; ++row) {
      const int j = row % dims.y(), k = row / dims.y();
      const std::size_t first = node_index(dims, 0, j, k);
      const double* in = v.data() + first;
      double* to = out.data() + first;
      if (a == 0) {
        for (int i = 0; i < dims.x(); ++i) {
          const double left = i > 0 ? in[i - 1] : 0.0;
          const double right = i + 1 < dims.x() ? in[i + 1] : 0.0;
          to[i] = 0.25 * left + 0.5 * in[i] + 0.25 * right;
        }
        continue;
      }
      const int at = a == 1 ? j : k;
      const bool has_left = at > 0, has_right = at + 1 < dims[a];
      for (int i = 0; i < dims.x(); ++i) {
        const double left = has_left ? in[i - stride] : 0.0;
        const double right = has_right ? in[i + stride] : 0.0;
        to[i] = 0.25 * left + 0.5 * in[i] + 0.25 * right;
      }
    }
  });
  v.swap(out);
}

// `passes` passes of smooth_axis along x, y and z, through one scratch lattice.
void smooth(std::vector<double>& v, const Vec3i& dims, int passes, int threads) {
  std::vector<double> scratch;
  for (int s = 0; s < passes; ++s)
    for (int a = 0; a < 3; ++a) smooth_axis(v, scratch, dims, a, threads);
}

// Passes of the [1 2 1]/4 filter over the spread's density.
constexpr int kSpreadSmoothing = 2;

}  // namespace

PointDensity point_density(const std::vector<Vec3>& points, const Vec3& lower, double h, const Vec3i& dims,
                           int smoothing, int threads) {
  if (!(h > 0.0) || dims.minCoeff() < 2) throw std::invalid_argument("point_density: needs h > 0 and 2 nodes per axis");
  PointDensity d;
  d.lower = lower;
  d.h = h;
  d.dims = dims;
  d.values.assign(static_cast<std::size_t>(dims.x()) * dims.y() * dims.z(), 0.0);
  const Vec3 upper = lower + h * (dims - Vec3i::Ones()).cast<double>();
  // Serial, in point order: the sums do not depend on the thread count.
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Vec3& x = points[p];
    if (!((x.array() >= lower.array()).all() && (x.array() <= upper.array()).all()))
      throw std::invalid_argument("point_density: point " + std::to_string(p) + " lies outside the lattice");
    Vec3i base;
    Vec3 t;
    locate(x, lower, h, dims, base, t);
    const TrilinearWeights w = trilinear_weights(t);
    for (int corner = 0; corner < 8; ++corner)
      d.values[node_index(dims, base.x() + (corner & 1), base.y() + ((corner >> 1) & 1), base.z() + (corner >> 2))] +=
          w.w[corner];
  }
  smooth(d.values, dims, smoothing, threads);
  return d;
}

void normalise_by_region(PointDensity& density, const RegionTest& region, int smoothing, int threads) {
  const Vec3i& dims = density.dims;
  std::vector<double> share(density.values.size());
  parallel_for_ranges(dims.y() * dims.z(), 64, threads, [&](int begin, int end) {
    for (int line = begin; line < end; ++line) {
      const int j = line % dims.y(), k = line / dims.y();
      for (int i = 0; i < dims.x(); ++i)
        share[node_index(dims, i, j, k)] = region(density.lower + density.h * Vec3(i, j, k)) ? 1.0 : 0.0;
    }
  });
  smooth(share, dims, smoothing, threads);
  for (std::size_t v = 0; v < share.size(); ++v) density.values[v] /= std::max(share[v], kRegionShareFloor);
}

Vec3 PointDensity::gradient(const Vec3& p) const {
  Vec3i base;
  Vec3 t;
  locate(p, lower, h, dims, base, t);
  const TrilinearWeights weights = trilinear_weights(t);
  Vec3 g = Vec3::Zero();
  if ((base.array() >= 1).all() && (base.array() + 2 < dims.array()).all()) {
    // Every stencil inside the lattice: the same sums, by strides.
    const std::ptrdiff_t stride[3] = {1, dims.x(), static_cast<std::ptrdiff_t>(dims.x()) * dims.y()};
    const double* origin = values.data() + node_index(dims, base.x(), base.y(), base.z());
    for (int corner = 0; corner < 8; ++corner) {
      const double w = weights.w[corner];
      if (w == 0.0) continue;
      const double* v = origin + (corner & 1) * stride[0] + ((corner >> 1) & 1) * stride[1] + (corner >> 2) * stride[2];
      for (int a = 0; a < 3; ++a) g[a] += w * (v[stride[a]] - v[-stride[a]]) / (2 * h);
    }
    return g;
  }
  for (int corner = 0; corner < 8; ++corner) {
    const int n[3] = {base.x() + (corner & 1), base.y() + ((corner >> 1) & 1), base.z() + (corner >> 2)};
    const double w = weights.w[corner];
    if (w == 0.0) continue;
    for (int a = 0; a < 3; ++a) {
      int lo[3] = {n[0], n[1], n[2]}, hi[3] = {n[0], n[1], n[2]};
      lo[a] = std::max(0, n[a] - 1);
      hi[a] = std::min(dims[a] - 1, n[a] + 1);
      g[a] += w * (at(hi[0], hi[1], hi[2]) - at(lo[0], lo[1], lo[2])) / ((hi[a] - lo[a]) * h);
    }
  }
  return g;
}

double seen_density(const PointDensity& density) {
  double sum = 0.0, squares = 0.0;
  for (double v : density.values) sum += v, squares += v * v;
  return sum > 0.0 ? squares / sum : 0.0;
}

void spread_fibres(std::vector<Vec3>& points, std::size_t n, const DensitySpread& spread, int threads,
                   const RegionTest& region) {
  if (spread.passes <= 0 || points.empty()) return;
  if (n < 2 || points.size() % n != 0)
    throw std::invalid_argument("spread_fibres: " + std::to_string(points.size()) + " points are not fibres of " +
                                std::to_string(n));
  if (!(spread.voxel > 0.0) || !(spread.step >= 0.0) || !(spread.settle > 0.0))
    throw std::invalid_argument("spread_fibres: needs voxel > 0, step ≥ 0 and settle > 0");
  const int fibres = static_cast<int>(points.size() / n);
  const double h = spread.voxel, reach = 0.5 * h;
  // Each fibre's segment lengths and move weights, from the fibres as grown.
  std::vector<double> lengths(fibres * (n - 1)), weights(points.size());
  parallel_for(fibres, threads, [&](int f) {
    const Vec3* p = points.data() + f * n;
    double total = 0.0;
    for (std::size_t i = 1; i < n; ++i) total += (lengths[f * (n - 1) + i - 1] = (p[i] - p[i - 1]).norm());
    double along = 0.0;
    weights[f * n] = 0.0;
    for (std::size_t i = 1; i < n; ++i) {
      along += lengths[f * (n - 1) + i - 1];
      weights[f * n + i] = total > 0.0 ? std::min(1.0, along / (spread.settle * total)) : 0.0;
    }
  });
  std::vector<Vec3> moved(points.size());
  for (int pass = 0; pass < spread.passes; ++pass) {
    Vec3 lo = points[0], hi = points[0];
    for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const Vec3 lower = lo - Vec3::Constant(2.0 * h);
    const Vec3i dims = ((hi - lower) / h).array().ceil().cast<int>() + 3;
    PointDensity density = point_density(points, lower, h, dims, kSpreadSmoothing, threads);
    if (region) normalise_by_region(density, region, kSpreadSmoothing, threads);
    const double mean = seen_density(density);
    if (!(mean > 0.0)) return;
    const double scale = spread.step * h * h / mean;
    parallel_for(fibres, threads, [&](int f) {
      const std::size_t first = f * n;
      moved[first] = points[first];
      for (std::size_t i = 1; i < n; ++i) {
        Vec3 d = -scale * density.gradient(points[first + i]);
        const double size = d.norm();
        if (size > reach) d *= reach / size;
        moved[first + i] = points[first + i] + weights[first + i] * d;
      }
      // The segment lengths back, from the root on, each along its moved direction.
      for (std::size_t i = 1; i < n; ++i) {
        const Vec3 v = moved[first + i] - moved[first + i - 1];
        const double norm = v.norm();
        const double length = lengths[f * (n - 1) + i - 1];
        Vec3 along = Vec3::Zero();
        if (norm > 0.0) {
          along = v / norm;
        } else {  // moved onto its neighbour: keep the grown direction
          const Vec3 grown = points[first + i] - points[first + i - 1];
          if (grown.norm() > 0.0) along = grown.normalized();
        }
        moved[first + i] = moved[first + i - 1] + length * along;
      }
    });
    points.swap(moved);
  }
}

}  // namespace hairfit
