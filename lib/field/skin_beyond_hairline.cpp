#include "field/skin_beyond_hairline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "core/parallel.h"

namespace hairfit {

namespace {

// The hairline: the scalp's one boundary loop, its floor's plane (through the loop's centroid, as
// closed_head's fan) with the unit normal pointing beyond it, and the layer's thickness at each
// of its vertices.
struct Hairline {
  std::vector<Vec3> vertices;
  std::vector<double> thickness;
  Vec3 centre = Vec3::Zero();
  Vec3 beyond = Vec3::Zero();
};

Hairline hairline_of(const Mesh& scalp, const DistanceField& volume) {
  const MeshTopology topology = analyse_topology(scalp);
  if (topology.boundary_loops.size() != 1)
    throw std::invalid_argument("skin_beyond_hairline: the scalp needs exactly one hairline (boundary loop)");
  Hairline h;
  const std::vector<int>& loop = topology.boundary_loops.front();
  Vec3 newell = Vec3::Zero();
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Vec3& a = scalp.positions[loop[k]];
    const Vec3& b = scalp.positions[loop[(k + 1) % loop.size()]];
    newell += a.cross(b);
    h.vertices.push_back(a);
    h.centre += a;
    h.thickness.push_back(std::max(0.0, -volume.value(a)));
  }
  h.centre /= static_cast<double>(loop.size());
  // The loop runs with the scalp's triangles, so its area vector faces out of the scalp, away from
  // the floor's far side: beyond the floor is the other way.
  h.beyond = -newell.normalized();
  double side = 0.0;
  for (const Vec3& p : scalp.positions) side += (p - h.centre).dot(h.beyond);
  if (side > 0.0) h.beyond = -h.beyond;  // a scalp wound the other way
  return h;
}

double thickness_near(const Hairline& h, const Vec3& p) {
  double nearest = INFINITY;
  for (const Vec3& v : h.vertices) nearest = std::min(nearest, (v - p).squaredNorm());
  double sum = 0.0, weights = 0.0;
  for (std::size_t k = 0; k < h.vertices.size(); ++k) {
    const double w = std::exp(-((h.vertices[k] - p).squaredNorm() - nearest) / (2.0 * kHairlineReach * kHairlineReach));
    sum += w * h.thickness[k];
    weights += w;
  }
  return std::max(kThinnestLayer, sum / weights);
}

// thickness_near at every node origin + h·(i, j, k) of a grid, where the Gaussian's exponent
// splits: with u = v − c and q = p − c about the hairline's centre c,
//   exp(−|u − q|²/2σ²) ∝ exp(−|u|²/2σ² + u·q₀/σ²) · exp(h·i·u_x/σ²) · exp(h·j·u_y/σ²) · exp(h·k·u_z/σ²)
// (the factor exp(−|q|²/2σ²) is the same for every vertex and cancels), so a node's weights are
// products of per-vertex, per-axis tables: no exponential per node and vertex. Null where the
// products could leave the range of a double; then thickness_near is summed at each node.
class GridThickness {
 public:
  GridThickness(const Hairline& h, const Vec3& origin, double voxel, const Vec3i& dims) : hairline_(h) {
    const double s2 = kHairlineReach * kHairlineReach;
    const Vec3 q0 = origin - h.centre;
    double reach = 0.0, extent = 0.0;
    for (const Vec3& v : h.vertices) reach = std::max(reach, (v - h.centre).norm());
    for (int d = 0; d < 3; ++d) extent += std::max(std::abs(q0[d]), std::abs(q0[d] + voxel * (dims[d] - 1)));
    // Every exponent below, and every partial sum of one, lies within ±reach·(reach + 2·extent)/2σ².
    usable_ = reach * (reach + 2.0 * extent) / (2.0 * s2) < 300.0;
    if (!usable_) return;
    const std::size_t n = h.vertices.size();
    for (int d = 0; d < 3; ++d) axis_[d].resize(n * static_cast<std::size_t>(dims[d]));
    scale_.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
      const Vec3 u = h.vertices[v] - h.centre;
      scale_[v] = std::exp(-u.squaredNorm() / (2.0 * s2) + u.dot(q0) / s2);
      for (int d = 0; d < 3; ++d)
        for (int i = 0; i < dims[d]; ++i) axis_[d][v * dims[d] + i] = std::exp(voxel * i * u[d] / s2);
    }
    dims_ = dims;
  }
  bool usable() const { return usable_; }
  double at(int i, int j, int k) const {
    double sum = 0.0, weights = 0.0;
    for (std::size_t v = 0; v < scale_.size(); ++v) {
      const double w = scale_[v] * axis_[0][v * dims_.x() + i] * axis_[1][v * dims_.y() + j] * axis_[2][v * dims_.z() + k];
      sum += w * hairline_.thickness[v];
      weights += w;
    }
    return std::max(kThinnestLayer, sum / weights);
  }

 private:
  const Hairline& hairline_;
  bool usable_ = false;
  Vec3i dims_ = Vec3i::Zero();
  std::vector<double> scale_;
  std::array<std::vector<double>, 3> axis_;
};

}  // namespace

SkinBeyondHairline skin_beyond_hairline(const Mesh& scalp, const DistanceField& scalp_field,
                                        const DistanceField& volume_field, int threads) {
  const Hairline hairline = hairline_of(scalp, volume_field);
  // Bounds on T, so that a node whose skin T cannot change is not averaged over the hairline.
  const double thinnest = kThinnestLayer;
  const double thickest = std::max(kThinnestLayer, *std::max_element(hairline.thickness.begin(), hairline.thickness.end()));
  const double h = volume_field.voxel();
  const Vec3 lo = scalp_field.origin().cwiseMin(volume_field.origin());
  const Vec3 hi = (scalp_field.origin() + scalp_field.voxel() * (scalp_field.dims() - Vec3i::Ones()).cast<double>())
                      .cwiseMax(volume_field.origin() + h * (volume_field.dims() - Vec3i::Ones()).cast<double>());
  Vec3i dims;
  for (int d = 0; d < 3; ++d) dims[d] = static_cast<int>(std::ceil((hi[d] - lo[d]) / h - 1e-9)) + 1;
  const GridThickness grid(hairline, lo, h, dims);
  std::vector<double> samples(std::size_t(dims.x()) * dims.y() * dims.z());
  parallel_for(dims.z(), threads, [&](int k) {
    for (int j = 0; j < dims.y(); ++j)
      for (int i = 0; i < dims.x(); ++i) {
        const Vec3 p = lo + h * Vec3(i, j, k);
        const double s = scalp_field.value(p);
        const double above_floor = -(p - hairline.centre).dot(hairline.beyond);
        double skin = s;
        if (above_floor < s) {  // else max(T + V, above_floor) ≥ s for any T
          const double v = volume_field.value(p);
          if (thinnest + v >= s) skin = s;  // T + V ≥ s for any T
          else if (thickest + v <= above_floor) skin = std::min(s, above_floor);
          else skin = std::min(s, std::max((grid.usable() ? grid.at(i, j, k) : thickness_near(hairline, p)) + v, above_floor));
        }
        samples[i + std::size_t(dims.x()) * (j + std::size_t(dims.y()) * k)] = skin;
      }
  });
  std::vector<double> sorted = hairline.thickness;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  return {DistanceField::from_samples(lo, h, dims, std::move(samples), threads), sorted[sorted.size() / 2]};
}

}  // namespace hairfit
