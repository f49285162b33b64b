#include "density/grid.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "core/trilinear.h"

namespace hairfit {


GridGeometry make_grid_geometry(const Vec3& lower, const Vec3& upper, double voxel, double max_memory_gib) {
  if (!lower.allFinite() || !upper.allFinite() || !(upper.array() > lower.array()).all()) {
    std::ostringstream m;
    m << "density grid: the box [" << lower.transpose() << "] .. [" << upper.transpose()
      << "] cm is not finite and non-empty; give a box whose upper corner exceeds the lower one";
    throw InputError("density", m.str());
  }
  if (!std::isfinite(voxel) || voxel <= 0.0) {
    std::ostringstream m;
    m << "density grid: voxel " << voxel << " cm must be finite and > 0 (the paper uses about 0.25)";
    throw InputError("density", m.str());
  }
  const Vec3 size = upper - lower;
  const Vec3 cells = (size / voxel).array().ceil().max(1.0);
  const double bytes = cells.prod() * sizeof(double);
  const double limit = max_memory_gib * 1024.0 * 1024.0 * 1024.0;
  if (!(bytes <= limit) || !(cells.maxCoeff() < 2.0e9)) {
    const double fit = std::cbrt(size.prod() * sizeof(double) / limit);
    std::ostringstream m;
    m << "density grid: voxel " << voxel << " cm over a box of " << size.transpose() << " cm needs "
      << bytes / (1024.0 * 1024.0 * 1024.0) << " GiB (limit " << max_memory_gib
      << " GiB); use a voxel of at least " << fit << " cm";
    throw InputError("density", m.str());
  }
  GridGeometry g;
  g.voxel = voxel;
  g.dims = cells.cast<int>();
  // Centre the whole-cell grid on the box, so the margin is the same on both sides.
  g.origin = 0.5 * (lower + upper) - 0.5 * voxel * cells;
  return g;
}

DensityGrid DensityGrid::from_values(const GridGeometry& geometry, std::vector<double> values) {
  if (geometry.dims.minCoeff() < 0 || !(std::isfinite(geometry.voxel) && geometry.voxel > 0.0))
    throw std::invalid_argument("a density grid needs non-negative dimensions and a finite voxel > 0");
  if (std::int64_t(values.size()) != geometry.count())
    throw std::invalid_argument("density grid size does not match its values");
  return DensityGrid(geometry, std::make_shared<const std::vector<double>>(std::move(values)));
}

double DensityGrid::cell(int i, int j, int k) const {
  return geometry_.contains(i, j, k) ? (*values_)[geometry_.index(i, j, k)] : 0.0;
}

namespace {

// Position of p in cell-centre coordinates: base cell b (lower of the 2×2×2 interpolation block)
// and the fraction f ∈ [0, 1) along each axis.
void locate(const GridGeometry& g, const Vec3& p, Vec3i& b, Vec3& f) {
  const Vec3 q = (p - g.origin) / g.voxel - Vec3::Constant(0.5);
  for (int a = 0; a < 3; ++a) {
    // Clamp far outside points before the cast (cells there are 0 anyway).
    const double c = std::min(std::max(q[a], -4.0), double(g.dims[a]) + 4.0);
    const double fl = std::floor(c);
    b[a] = int(fl);
    f[a] = c - fl;
  }
}

}  // namespace

double DensityGrid::value(const Vec3& p) const { return value_and_gradient(p).value; }

DensityValueGradient DensityGrid::value_and_gradient(const Vec3& p) const {
  DensityValueGradient out;
  if (geometry_.count() == 0 || !p.allFinite()) return out;
  Vec3i b;
  Vec3 f;
  locate(geometry_, p, b, f);
  const TrilinearWeights w = trilinear_weights(f);
  for (int c = 0; c < 8; ++c) {
    const double v = cell(b.x() + (c & 1), b.y() + ((c >> 1) & 1), b.z() + ((c >> 2) & 1));
    out.value += w.w[c] * v;
    out.gradient += w.dw[c] * v;
  }
  out.gradient /= geometry_.voxel;
  return out;
}

void DensityGrid::central_gradient_at(const Vec3& p, Vec3& gradient, Mat3* jacobian) const {
  const GridGeometry& geometry = geometry_;
  gradient = Vec3::Zero();
  if (jacobian) *jacobian = Mat3::Zero();
  if (geometry.count() == 0 || !p.allFinite()) return;
  Vec3i b;
  Vec3 f;
  locate(geometry, p, b, f);
  const TrilinearWeights w = trilinear_weights(f);
  const double h = geometry.voxel;
  // Every cell the differences read lies within one of the block: away from the grid's faces
  // they are read by offset, without bounds checks (the guide optimiser calls this per sample).
  const Vec3i& n = geometry.dims;
  const bool interior = b.x() >= 1 && b.y() >= 1 && b.z() >= 1 && b.x() + 2 < n.x() && b.y() + 2 < n.y() && b.z() + 2 < n.z();
  const std::ptrdiff_t sy = n.x(), sz = static_cast<std::ptrdiff_t>(n.x()) * n.y();
  for (int c = 0; c < 8; ++c) {
    const int i = b.x() + (c & 1), j = b.y() + ((c >> 1) & 1), k = b.z() + ((c >> 2) & 1);
    Vec3 g;
    if (interior) {
      const double* v = values_->data() + geometry.index(i, j, k);
      g = Vec3((v[1] - v[-1]) / (2.0 * h), (v[sy] - v[-sy]) / (2.0 * h), (v[sz] - v[-sz]) / (2.0 * h));
    } else {
      g = Vec3((cell(i + 1, j, k) - cell(i - 1, j, k)) / (2.0 * h), (cell(i, j + 1, k) - cell(i, j - 1, k)) / (2.0 * h),
               (cell(i, j, k + 1) - cell(i, j, k - 1)) / (2.0 * h));
    }
    gradient += w.w[c] * g;
    if (jacobian) *jacobian += g * w.dw[c].transpose();
  }
  if (jacobian) *jacobian /= h;
}

Vec3 DensityGrid::central_gradient(const Vec3& p) const {
  Vec3 gradient;
  central_gradient_at(p, gradient, nullptr);
  return gradient;
}

DensityGradientJacobian DensityGrid::central_gradient_and_jacobian(const Vec3& p) const {
  DensityGradientJacobian out;
  central_gradient_at(p, out.gradient, &out.jacobian);
  return out;
}

}  // namespace hairfit
