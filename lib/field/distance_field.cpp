#include "field/distance_field.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "field/band_scan.h"
#include "field/far_field.h"
#include "field/mesh_features.h"

namespace hairfit {

namespace {

std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, fmt, a, b, c, d);
  return buffer;
}

void check_spec(const FieldSpec& spec) {
  auto bad = [&](const std::string& what) { throw InputError(spec.name, "distance field: " + what); };
  if (!(std::isfinite(spec.voxel) && spec.voxel > 0)) bad(format("voxel must be a positive length in cm, got %g", spec.voxel));
  if (!(std::isfinite(spec.band) && spec.band >= 1 && spec.band <= 1000))
    bad(format("band must be between 1 and 1000 voxels, got %g", spec.band));
  if (!(std::isfinite(spec.margin) && spec.margin >= 0)) bad(format("margin must be ≥ 0 cm, got %g", spec.margin));
  if (!(std::isfinite(spec.max_memory_gib) && spec.max_memory_gib > 0))
    bad(format("max_memory must be a positive number of GiB, got %g", spec.max_memory_gib));
}

// Bytes at the build's peak: fine samples + feature keys, the coarse grid with its closest points
// and normals, and about 200 bytes per mesh feature for the scan regions.
double plan_bytes(const Vec3i& dims, int coarse_factor, size_t triangles) {
  const double fine = double(dims.x()) * dims.y() * dims.z();
  double coarse = 1;
  for (int d = 0; d < 3; ++d) coarse *= (dims[d] - 1) / coarse_factor + 1;
  return fine * (sizeof(double) + sizeof(int32_t)) + coarse * 64 + double(triangles) * 3 * 200;
}

FieldGridPlan plan_with_voxel(const std::pair<Vec3, Vec3>& box, const FieldSpec& spec, double voxel,
                              size_t triangles) {
  FieldGridPlan plan;
  // The far-field grid's spacing, floor(2·band) voxels, is at most the band's full width, so
  // every coarse grid line that crosses the surface has a node inside the exact band.
  plan.coarse_factor = std::max(1, static_cast<int>(std::floor(2 * spec.band)));
  const double cell = plan.coarse_factor * voxel;
  for (int d = 0; d < 3; ++d) {
    const double extent = box.second[d] - box.first[d] + 2 * spec.margin;
    const double cells = std::max(1.0, std::ceil(extent / cell));
    plan.dims[d] = cells * plan.coarse_factor + 1 > 2e9 ? 2000000000 : int(cells) * plan.coarse_factor + 1;
    plan.origin[d] = box.first[d] - spec.margin - 0.5 * (cells * cell - extent);
  }
  plan.bytes = plan_bytes(plan.dims, plan.coarse_factor, triangles);
  return plan;
}

std::pair<Vec3, Vec3> checked_box(const Mesh& mesh, const std::string& name) {
  if (mesh.triangles.empty()) throw InputError(name, "the mesh has no triangles; a distance field needs a surface");
  for (const Vec3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= int(mesh.positions.size()) || !mesh.positions[t[k]].allFinite())
        throw InputError(name, "triangle vertex " + std::to_string(t[k]) +
                                   " is out of range or has a non-finite coordinate");
  return bounding_box(mesh);
}

}  // namespace

FieldGridPlan plan_field_grid(const Mesh& mesh, const FieldSpec& spec) {
  check_spec(spec);
  return plan_with_voxel(checked_box(mesh, spec.name), spec, spec.voxel, mesh.triangles.size());
}

void require_field_fits(const Mesh& mesh, const FieldSpec& spec) {
  const FieldGridPlan plan = plan_field_grid(mesh, spec);
  const double limit = spec.max_memory_gib * 1024.0 * 1024.0 * 1024.0;
  if (plan.bytes > limit) {
    // Suggest the smallest voxel (in 1% steps) whose grid fits.
    const auto box = bounding_box(mesh);
    double voxel = spec.voxel * std::cbrt(plan.bytes / limit);
    while (plan_with_voxel(box, spec, voxel, mesh.triangles.size()).bytes > limit) voxel *= 1.01;
    const double unit = std::pow(10.0, std::floor(std::log10(voxel)) - 2);  // 3 digits, rounded up
    voxel = std::ceil(voxel / unit) * unit;
    throw InputError(spec.name,
                     "distance field: a grid of " + std::to_string(plan.dims.x()) + "×" + std::to_string(plan.dims.y()) +
                         "×" + std::to_string(plan.dims.z()) + " voxels at " + format("%g", spec.voxel) +
                         " cm needs " + format("%.2f", plan.bytes / 1073741824.0) + " GiB, more than the limit of " +
                         format("%g", spec.max_memory_gib) + " GiB; use a voxel of at least " +
                         format("%.3g", voxel) + " cm, or raise max_memory");
  }
}

DistanceField make_distance_field(const Mesh& mesh, const FieldSpec& spec, int threads) {
  require_field_fits(mesh, spec);
  const FieldGridPlan plan = plan_field_grid(mesh, spec);
  threads = resolve_thread_count(threads);
  const field::MeshFeatures features = field::extract_features(mesh, spec.name);
  field::GridGeometry grid{plan.origin, spec.voxel, plan.dims};
  const double r = spec.band * spec.voxel;
  field::BandScan band = field::scan_band(features, grid, r, threads);
  field::FarField far = field::make_far_field(features, grid, band, r, plan.coarse_factor, threads);

  DistanceField out;
  out.origin_ = plan.origin;
  out.h_ = spec.voxel;
  out.dims_ = plan.dims;
  out.band_cm_ = r;
  out.band_voxels_ = band.band_voxels;
  out.coarse_factor_ = plan.coarse_factor;
  out.coarse_dims_ = far.dims;
  out.coarse_ = std::make_shared<const std::vector<double>>(std::move(far.values));
  out.finish(std::move(band.value), threads);
  return out;
}

namespace {

// Trilinear interpolation of the 8 corner values c[x + 2y + 4z] at fractions f ∈ [0,1]³, and
// (kGradient) its derivative with respect to f. The value is the same expression either way, so
// value() and value_and_gradient() agree bit for bit.
template <bool kGradient>
void trilinear(const double c[8], const double f[3], double& value, Vec3* gradient) {
  const double x0 = 1 - f[0], y0 = 1 - f[1], z0 = 1 - f[2];
  const double c00 = c[0] * x0 + c[1] * f[0], c10 = c[2] * x0 + c[3] * f[0];
  const double c01 = c[4] * x0 + c[5] * f[0], c11 = c[6] * x0 + c[7] * f[0];
  const double c0 = c00 * y0 + c10 * f[1], c1 = c01 * y0 + c11 * f[1];
  value = c0 * z0 + c1 * f[2];
  if constexpr (kGradient) {
    gradient->z() = c1 - c0;
    gradient->y() = (c10 - c00) * z0 + (c11 - c01) * f[2];
    const double dx00 = c[1] - c[0], dx10 = c[3] - c[2], dx01 = c[5] - c[4], dx11 = c[7] - c[6];
    gradient->x() = (dx00 * y0 + dx10 * f[1]) * z0 + (dx01 * y0 + dx11 * f[1]) * f[2];
  }
}

// Cell index and fraction along one axis for a coordinate u in grid units, clamped to [0, n−1].
void locate(double u, int n, int& cell, double& frac) {
  u = std::clamp(u, 0.0, double(n - 1));
  cell = std::min(static_cast<int>(u), n - 2);
  frac = u - cell;
}

}  // namespace

void DistanceField::finish(std::vector<double> values, int threads) {
  set_geometry();
  const int nx = dims_.x(), ny = dims_.y(), nz = dims_.z();
  const int64_t dy = nx, dz = int64_t(nx) * ny;
  const int c = coarse_factor_;
  const int64_t cdx = coarse_dims_.x(), cdy = coarse_dims_.y();
  const std::vector<double>& coarse = *coarse_;
  // Per axis and fine index: the coarse cell and fraction at which the node interpolates the
  // coarse grid (locate(index / c)), and the coarse cells a lookup in the fine cell from this index
  // may read (index / c rounds, so also the next one where the fine cell ends on a coarse node).
  struct Axis {
    std::vector<int> cell, first;
    std::vector<char> one;  // the first candidate is the only one
    std::vector<double> frac;
  } axes[3];
  for (int d = 0; d < 3; ++d) {
    Axis& a = axes[d];
    a.cell.resize(dims_[d]), a.frac.resize(dims_[d]), a.first.resize(dims_[d]), a.one.resize(dims_[d]);
    for (int n = 0; n < dims_[d]; ++n) {
      locate(double(n) / c, coarse_dims_[d], a.cell[n], a.frac[n]);
      a.first[n] = std::min(static_cast<int>(double(n) / c), coarse_dims_[d] - 2);
      a.one[n] = std::min(static_cast<int>(double(n + 1) / c), coarse_dims_[d] - 2) == a.first[n];
    }
  }
  // Beyond the band: the trilinear interpolation of the coarse grid at the node.
  std::vector<std::uint8_t> in_band(values.size(), 0);
  parallel_for(nz, threads, [&](int k) {
    const double fz = axes[2].frac[k];
    for (int j = 0; j < ny; ++j) {
      const double fy = axes[1].frac[j];
      const int64_t row = index(0, j, k), coarse_yz = cdx * (axes[1].cell[j] + cdy * axes[2].cell[k]);
      for (int i = 0; i < nx; ++i) {
        if (values[row + i] != std::numeric_limits<double>::infinity()) {
          in_band[row + i] = kInBand;
          continue;
        }
        const double* s = coarse.data() + coarse_yz + axes[0].cell[i];
        const double corners[8] = {s[0], s[1], s[cdx], s[cdx + 1], s[cdx * cdy], s[cdx * cdy + 1], s[cdx * cdy + cdx],
                                   s[cdx * cdy + cdx + 1]};
        const double frac[3] = {axes[0].frac[i], fy, fz};
        trilinear<false>(corners, frac, values[row + i], nullptr);
      }
    }
  });
  // The lowest and highest node of every coarse cell, and of every block of 2×2×2 coarse cells
  // (clamped to the grid): a far fine cell reads the coarse cell at its first candidate, or, where
  // it ends on a coarse node, possibly the next one, within the block.
  const int64_t cdz = coarse_dims_.z();
  std::vector<double> cell_lo(coarse.size()), cell_hi(coarse.size()), block_lo(coarse.size()), block_hi(coarse.size());
  for (int64_t z = 0; z < cdz; ++z)
    for (int64_t y = 0; y < cdy; ++y)
      for (int64_t x = 0; x < cdx; ++x)
        for (int64_t reach : {1, 2}) {
          double lo = std::numeric_limits<double>::infinity(), hi = -lo;
          for (int64_t cz = z; cz <= std::min(z + reach, cdz - 1); ++cz)
            for (int64_t cy = y; cy <= std::min(y + reach, cdy - 1); ++cy)
              for (int64_t cx = x; cx <= std::min(x + reach, cdx - 1); ++cx) {
                lo = std::min(lo, coarse[cx + cdx * (cy + cdy * cz)]);
                hi = std::max(hi, coarse[cx + cdx * (cy + cdy * cz)]);
              }
          (reach == 1 ? cell_lo : block_lo)[x + cdx * (y + cdy * z)] = lo;
          (reach == 1 ? cell_hi : block_hi)[x + cdx * (y + cdy * z)] = hi;
        }
  // Flags of each cell (lowest node (i, j, k)), from the samples its lookups read: its 8 corners,
  // or, when none is in the band, (a superset of) the coarse nodes it may interpolate.
  constexpr double kTiny = 1e-290;  // products with interpolation weights stay normal numbers
  std::vector<std::uint8_t> flags(in_band.size(), 0);
  parallel_for(nz, threads, [&](int k) {
    for (int j = 0; j < ny; ++j) {
      const int64_t row = index(0, j, k);
      for (int i = 0; i < nx; ++i) flags[row + i] = in_band[row + i];
      if (j + 1 == ny || k + 1 == nz) continue;  // no cell has these lowest nodes
      for (int i = 0; i + 1 < nx; ++i) {
        const int64_t at = row + i;
        const std::uint8_t* b = in_band.data() + at;
        double lo, hi;
        if (b[0] | b[1] | b[dy] | b[dy + 1] | b[dz] | b[dz + 1] | b[dz + dy] | b[dz + dy + 1]) {
          const double* s = values.data() + at;
          lo = std::min({s[0], s[1], s[dy], s[dy + 1], s[dz], s[dz + 1], s[dz + dy], s[dz + dy + 1]});
          hi = std::max({s[0], s[1], s[dy], s[dy + 1], s[dz], s[dz + 1], s[dz + dy], s[dz + dy + 1]});
        } else {
          flags[at] |= kCellFar;
          const int64_t first = axes[0].first[i] + cdx * (axes[1].first[j] + cdy * axes[2].first[k]);
          const bool one = axes[0].one[i] && axes[1].one[j] && axes[2].one[k];
          lo = (one ? cell_lo : block_lo)[first];
          hi = (one ? cell_hi : block_hi)[first];
        }
        if (lo > kTiny) flags[at] |= kCellPositive;
        if (hi < -kTiny) flags[at] |= kCellNegative;
      }
    }
  });
  samples_ = std::make_shared<const std::vector<double>>(std::move(values));
  flags_ = std::make_shared<const std::vector<std::uint8_t>>(std::move(flags));
}

void DistanceField::set_geometry() {
  upper_ = origin_ + h_ * (dims_ - Vec3i::Ones()).cast<double>();
  last_node_ = (dims_ - Vec3i::Ones()).cast<double>();
  stride_ = {1, dims_.x(), int64_t(dims_.x()) * dims_.y()};
}

bool DistanceField::in_band(int i, int j, int k) const { return (*flags_)[index(i, j, k)] & kInBand; }

double DistanceField::sample(int i, int j, int k) const { return (*samples_)[index(i, j, k)]; }

int64_t DistanceField::memory_bytes() const {
  return int64_t(sizeof(double)) * int64_t(samples_->size() + coarse_->size());
}


template <bool kGradient>
void DistanceField::inside_grid(const Vec3& p, double& value, Vec3* gradient) const {
  // The cell and fractions as locate() finds them, with the per-axis constants kept.
  double u[3], frac[3];
  int64_t base = 0;
  for (int d = 0; d < 3; ++d) {
    u[d] = (p[d] - origin_[d]) / h_;
    const double clamped = std::clamp(u[d], 0.0, last_node_[d]);
    const int cell = std::min(static_cast<int>(clamped), dims_[d] - 2);
    frac[d] = clamped - cell;
    base += stride_[d] * cell;
  }
  if ((*flags_)[base] & kCellFar) {
    // Every corner is beyond the band: the samples there are the coarse interpolant, which is
    // trilinear over the whole coarse cell, so interpolating it directly gives the same value.
    int cc[3];
    double cf[3];
    for (int d = 0; d < 3; ++d) locate(u[d] / coarse_factor_, coarse_dims_[d], cc[d], cf[d]);
    const int64_t cy = coarse_dims_.x(), cz = int64_t(coarse_dims_.x()) * coarse_dims_.y();
    const double* s = coarse_->data() + (cc[0] + cy * (cc[1] + int64_t(coarse_dims_.y()) * cc[2]));
    const double corners[8] = {s[0], s[1], s[cy], s[cy + 1], s[cz], s[cz + 1], s[cz + cy], s[cz + cy + 1]};
    trilinear<kGradient>(corners, cf, value, gradient);
    if constexpr (kGradient) *gradient /= coarse_factor_ * h_;
    return;
  }
  // Band samples and far samples alike (samples_ holds both).
  const int64_t dy = dims_.x(), dz = int64_t(dims_.x()) * dims_.y();
  const double* s = samples_->data() + base;
  const double corners[8] = {s[0], s[1], s[dy], s[dy + 1], s[dz], s[dz + 1], s[dz + dy], s[dz + dy + 1]};
  trilinear<kGradient>(corners, frac, value, gradient);
  if constexpr (kGradient) *gradient /= h_;
}

FieldValueGradient DistanceField::value_and_gradient(const Vec3& p) const {
  // A non-finite point (from a rod the integrator could not follow) has no distance: NaN, not
  // an index computed from NaN.
  if (!p.allFinite()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, Vec3::Constant(nan)};
  }
  const Vec3 q = p.cwiseMax(origin_).cwiseMin(upper_);
  FieldValueGradient out;
  inside_grid<true>(q, out.value, &out.gradient);
  if (q == p) return out;
  const Vec3 outside = p - q;
  const double distance = outside.norm();
  if (distance > 0) {
    // Beyond the grid the magnitude grows with the distance to the grid box, so the gradient
    // still leads back toward the surface.
    const double sign = out.value < 0 ? -1.0 : 1.0;
    out.value += sign * distance;
    for (int d = 0; d < 3; ++d)
      if (outside[d] != 0) out.gradient[d] = sign * outside[d] / distance;
  }
  return out;
}

double DistanceField::value(const Vec3& p) const {
  if (!p.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  const Vec3 q = p.cwiseMax(origin_).cwiseMin(upper_);
  double value;
  inside_grid<false>(q, value, nullptr);
  if (q == p) return value;
  const double distance = (p - q).norm();  // as value_and_gradient: the same bits
  if (distance > 0) value += (value < 0 ? -1.0 : 1.0) * distance;
  return value;
}

int DistanceField::side(const Vec3& p) const {
  if (!p.allFinite()) return 0;
  // The cell inside_grid reads (beyond the grid, value() only adds to the magnitude), found as
  // it finds it, without the fractions. Clamping u to [0, n − 1] alone picks the same cell as
  // clamping p to the grid box first: beyond either face both end on the last cell.
  int64_t at = 0;
  for (int d = 0; d < 3; ++d) {
    const double u = std::clamp((p[d] - origin_[d]) / h_, 0.0, last_node_[d]);
    at += stride_[d] * std::min(static_cast<int>(u), dims_[d] - 2);
  }
  const std::uint8_t f = (*flags_)[at];
  return (f & kCellPositive) ? 1 : (f & kCellNegative) ? -1 : 0;
}

std::vector<std::int8_t> DistanceField::sides_on_lattice(const std::vector<double>& x, const std::vector<double>& y,
                                                         const std::vector<double>& z, int threads) const {
  // Per axis, the term each coordinate adds to the cell index, as side() computes it (it treats
  // the axes separately); a non-finite coordinate makes its points undecided (−1 here).
  const std::vector<double>* axes[3] = {&x, &y, &z};
  std::vector<int64_t> terms[3];
  for (int d = 0; d < 3; ++d)
    for (double c : *axes[d]) {
      if (!std::isfinite(c)) {
        terms[d].push_back(-1);
        continue;
      }
      const double u = std::clamp((c - origin_[d]) / h_, 0.0, last_node_[d]);
      terms[d].push_back(stride_[d] * std::min(static_cast<int>(u), dims_[d] - 2));
    }
  const std::size_t nx = x.size(), ny = y.size();
  std::vector<std::int8_t> out(nx * ny * z.size(), 0);
  // The side for each combination of the two side bits (kCellPositive = 4, kCellNegative = 8).
  static_assert(kCellPositive == 4 && kCellNegative == 8, "the table below");
  constexpr std::int8_t kSide[4] = {0, 1, -1, 1};
  const std::uint8_t* flags = flags_->data();
  parallel_for(static_cast<int>(z.size()), threads, [&](int k) {
    for (std::size_t j = 0; j < ny; ++j) {
      if (terms[1][j] < 0 || terms[2][k] < 0) continue;
      const std::uint8_t* row = flags + terms[1][j] + terms[2][k];
      std::int8_t* sides = out.data() + nx * (j + ny * k);
      for (std::size_t i = 0; i < nx; ++i)
        if (terms[0][i] >= 0) sides[i] = kSide[(row[terms[0][i]] >> 2) & 3];
    }
  });
  return out;
}

Vec3 DistanceField::gradient(const Vec3& p) const { return value_and_gradient(p).gradient; }

}  // namespace hairfit
