#include "field/distance_field.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "core/triangle_closest.h"
#include "field/band_scan.h"
#include "field/cell_corners.h"
#include "field/far_field.h"
#include "field/mesh_features.h"
#include "field/winding_signs.h"

namespace hairfit {

namespace {

std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, fmt, a, b, c, d);
  return buffer;
}

// Throws std::invalid_argument unless the grid is one: non-negative dimensions, a finite voxel
// > 0, and one sample (and one flag) per node.
void check_grid(const Vec3i& d, double voxel, std::size_t samples, std::size_t flags) {
  if (d.minCoeff() < 0 || !(std::isfinite(voxel) && voxel > 0.0))
    throw std::invalid_argument("a distance field needs non-negative dimensions and a finite voxel > 0");
  if (samples != std::size_t(d.x()) * d.y() * d.z() || flags != samples)
    throw std::invalid_argument("distance field grid sizes do not match their samples");
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

namespace {

// Signs every band sample and every coarse node by the robust inside at its node, in one decision
// (so that a node both grids share gets one answer).
void sign_band_and_coarse(const field::RobustSigns& inside, const GridGeometry& grid, field::BandScan& band,
                          field::FarField& far, int c, int threads) {
  const int nx = grid.dims.x(), ny = grid.dims.y(), nz = grid.dims.z();
  auto coarse_index = [&](int i, int j, int k) {
    return i / c + int64_t(far.dims.x()) * (j / c + int64_t(far.dims.y()) * (k / c));
  };
  // The nodes to sign and their distances, gathered per layer in index order.
  std::vector<std::vector<int64_t>> layer_nodes(nz);
  std::vector<std::vector<double>> layer_distance(nz);
  parallel_for(nz, threads, [&](int k) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int64_t n = grid.index(i, j, k);
        const bool coarse = i % c == 0 && j % c == 0 && k % c == 0;
        if (band.key[n] >= 0) {
          layer_nodes[k].push_back(n), layer_distance[k].push_back(std::abs(band.value[n]));
        } else if (coarse && std::isfinite(far.values[coarse_index(i, j, k)])) {
          layer_nodes[k].push_back(n), layer_distance[k].push_back(std::abs(far.values[coarse_index(i, j, k)]));
        }
      }
  });
  std::vector<int64_t> nodes;
  std::vector<double> distance;
  for (int k = 0; k < nz; ++k) {
    nodes.insert(nodes.end(), layer_nodes[k].begin(), layer_nodes[k].end());
    distance.insert(distance.end(), layer_distance[k].begin(), layer_distance[k].end());
  }
  const std::vector<std::uint8_t> in = inside.decide(nodes, distance, threads);
  parallel_for(nz, threads, [&](int k) {
    const auto first = std::lower_bound(nodes.begin(), nodes.end(), grid.index(0, 0, k));
    for (auto it = first; it != nodes.end() && *it < grid.index(0, 0, k + 1); ++it) {
      const int64_t n = *it;
      const std::size_t q = std::size_t(it - nodes.begin());
      const Vec3i v = grid.indices(n);
      auto sign = [&](double& value) { value = in[q] ? -std::abs(value) : std::abs(value); };
      if (band.key[n] >= 0) sign(band.value[n]);
      if (v.x() % c == 0 && v.y() % c == 0 && k % c == 0) sign(far.values[coarse_index(v.x(), v.y(), k)]);
    }
  });
}

// The value carried from the vertices to p, whose closest feature is `key` (band_scan.h's keys).
double carried_value(const field::MeshFeatures& f, const std::vector<double>& at_vertex, int key, const Vec3& p) {
  const int nf = static_cast<int>(f.faces.size()), ne = static_cast<int>(f.edges.size());
  if (key < nf) {
    const Vec3i& t = f.faces[key];
    const Vec3 w = closest_barycentric(p, f.vertices[t[0]], f.vertices[t[1]], f.vertices[t[2]]);
    return w[0] * at_vertex[t[0]] + w[1] * at_vertex[t[1]] + w[2] * at_vertex[t[2]];
  }
  if (key < nf + ne) {
    const auto [a, b] = f.edges[key - nf];
    const Vec3 d = f.vertices[b] - f.vertices[a];
    const double t = std::clamp((p - f.vertices[a]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (1.0 - t) * at_vertex[a] + t * at_vertex[b];
  }
  return at_vertex[key - nf - ne];
}

}  // namespace

DistanceField DistanceField::build(const Mesh& mesh, const FieldSpec& spec, int threads, const RobustInside& inside,
                                   const std::vector<double>* vertex_values, std::vector<double>* carried) {
  require_field_fits(mesh, spec);
  const FieldGridPlan plan = plan_field_grid(mesh, spec);
  threads = resolve_thread_count(threads);
  const field::MeshFeatures features = field::extract_features(mesh, spec.name);
  GridGeometry grid{plan.origin, spec.voxel, plan.dims};
  const double r = spec.band * spec.voxel;
  const field::ScanRegions regions = field::scan_regions(features, threads);
  field::BandScan band = field::scan_band(features, regions, grid, r, threads);
  field::FarField far = field::make_far_field(features, regions, grid, band, r, plan.coarse_factor, threads);
  std::optional<field::RobustSigns> signs;
  if (!inside.empty()) {
    signs.emplace(inside, grid, threads);
    sign_band_and_coarse(*signs, grid, band, far, plan.coarse_factor, threads);
  }
  std::vector<std::uint8_t> in_band(band.value.size());
  for (std::size_t n = 0; n < in_band.size(); ++n) in_band[n] = band.key[n] >= 0;
  if (vertex_values) {
    std::vector<double> at_vertex(features.vertices.size(), std::numeric_limits<double>::infinity());
    for (std::size_t v = 0; v < features.vertex_of_input.size(); ++v)
      if (features.vertex_of_input[v] >= 0)
        at_vertex[features.vertex_of_input[v]] = std::min(at_vertex[features.vertex_of_input[v]], (*vertex_values)[v]);
    carried->assign(band.value.size(), std::numeric_limits<double>::quiet_NaN());
    const int nx = grid.dims.x(), ny = grid.dims.y();
    parallel_for(grid.dims.z(), threads, [&](int k) {
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const int64_t n = grid.index(i, j, k);
          if (band.key[n] >= 0) (*carried)[n] = carried_value(features, at_vertex, band.key[n], grid.node(i, j, k));
        }
    });
  }
  std::vector<int32_t>().swap(band.key);
  field::fill_beyond_band(features, grid, far, plan.coarse_factor, r, signs ? &*signs : nullptr, in_band, band.value,
                          threads);
  DistanceField out;
  out.origin_ = plan.origin;
  out.h_ = spec.voxel;
  out.dims_ = plan.dims;
  out.band_cm_ = r;
  out.band_voxels_ = band.band_voxels;
  out.finish(std::move(band.value), std::move(in_band), threads);
  return out;
}

DistanceField DistanceField::from_parts(DistanceFieldParts parts) {
  check_grid(parts.dims, parts.voxel, parts.samples.size(), parts.flags.size());
  DistanceField f;
  f.origin_ = parts.origin;
  f.h_ = parts.voxel;
  f.dims_ = parts.dims;
  f.band_cm_ = parts.band_width;
  f.band_voxels_ = parts.band_voxels;
  f.set_geometry();
  f.samples_ = std::make_shared<const std::vector<double>>(std::move(parts.samples));
  f.flags_ = std::make_shared<const std::vector<std::uint8_t>>(std::move(parts.flags));
  return f;
}

DistanceField DistanceField::from_samples(const Vec3& origin, double voxel, const Vec3i& dims, std::vector<double> samples,
                                         int threads) {
  check_grid(dims, voxel, samples.size(), samples.size());
  DistanceField f;
  f.origin_ = origin;
  f.h_ = voxel;
  f.dims_ = dims;
  std::vector<std::uint8_t> in_band(samples.size(), 0);
  f.finish(std::move(samples), std::move(in_band), threads);
  return f;
}

DistanceField make_distance_field(const Mesh& mesh, const FieldSpec& spec, int threads, const RobustInside& inside) {
  return DistanceField::build(mesh, spec, threads, inside, nullptr, nullptr);
}

CarriedField make_distance_field_carrying(const Mesh& mesh, const std::vector<double>& vertex_values,
                                          const FieldSpec& spec, int threads, const RobustInside& inside) {
  if (vertex_values.size() != mesh.positions.size())
    throw std::invalid_argument("make_distance_field_carrying: one value per vertex of the mesh");
  std::vector<double> carried;
  DistanceField field = DistanceField::build(mesh, spec, threads, inside, &vertex_values, &carried);
  return CarriedField{std::move(field), std::move(carried)};
}

void DistanceField::finish(std::vector<double> values, std::vector<std::uint8_t> in_band, int threads) {
  set_geometry();
  const int nx = dims_.x(), ny = dims_.y(), nz = dims_.z();
  const int64_t dy = nx, dz = int64_t(nx) * ny;
  // Flags of each cell (lowest node (i, j, k)), from its 8 corners.
  constexpr double kTiny = 1e-290;  // products with interpolation weights stay normal numbers
  std::vector<std::uint8_t> flags(values.size(), 0);
  parallel_for(nz, threads, [&](int k) {
    for (int j = 0; j < ny; ++j) {
      const int64_t row = index(0, j, k);
      for (int i = 0; i < nx; ++i) flags[row + i] = in_band[row + i] ? kInBand : 0;
      if (j + 1 == ny || k + 1 == nz) continue;  // no cell has these lowest nodes
      for (int i = 0; i + 1 < nx; ++i) {
        const double* s = values.data() + row + i;
        const double c[8] = {s[0], s[1], s[dy], s[dy + 1], s[dz], s[dz + 1], s[dz + dy], s[dz + dy + 1]};
        const double lo = std::min({c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]});
        const double hi = std::max({c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]});
        if (lo > kTiny) flags[row + i] |= kCellPositive;
        else if (hi < -kTiny) flags[row + i] |= kCellNegative;
        else if (lo < 0 && hi > 0 && field::is_seam(c, h_)) flags[row + i] |= kCellSeam;
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

int64_t DistanceField::memory_bytes() const { return int64_t(sizeof(double)) * int64_t(samples_->size()); }


template <bool kGradient>
void DistanceField::inside_grid(const Vec3& p, double& value, Vec3* gradient) const {
  // The cell and fractions as locate() finds them, with the per-axis constants kept.
  double frac[3];
  int64_t base = 0;
  for (int d = 0; d < 3; ++d) {
    const double clamped = std::clamp((p[d] - origin_[d]) / h_, 0.0, last_node_[d]);
    const int cell = std::min(static_cast<int>(clamped), dims_[d] - 2);
    frac[d] = clamped - cell;
    base += stride_[d] * cell;
  }
  const int64_t dy = dims_.x(), dz = int64_t(dims_.x()) * dims_.y();
  const double* s = samples_->data() + base;
  const double corners[8] = {s[0], s[1], s[dy], s[dy + 1], s[dz], s[dz + 1], s[dz + dy], s[dz + dy + 1]};
  trilinear<kGradient>(corners, frac, value, gradient);
  if ((*flags_)[base] & kCellSeam) {
    // The sign of the interpolated samples, the magnitude of the interpolated magnitudes.
    double magnitudes[8];
    for (int q = 0; q < 8; ++q) magnitudes[q] = std::abs(corners[q]);
    const double sign = value < 0 ? -1.0 : 1.0;
    trilinear<kGradient>(magnitudes, frac, value, gradient);
    value *= sign;
    if constexpr (kGradient) *gradient *= sign;
  }
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

double DistanceField::nearest_sample(const Vec3& p) const {
  int node[3];
  for (int d = 0; d < 3; ++d) node[d] = static_cast<int>(std::clamp((p[d] - origin_[d]) / h_, 0.0, last_node_[d]) + 0.5);
  return sample(node[0], node[1], node[2]);
}

double DistanceField::distance_lower_bound(const Vec3& p) const {
  if (!p.allFinite()) return -std::numeric_limits<double>::infinity();
  int node[3];
  Vec3 at;
  for (int d = 0; d < 3; ++d) {
    node[d] = static_cast<int>(std::clamp((p[d] - origin_[d]) / h_, 0.0, last_node_[d]) + 0.5);
    at[d] = origin_[d] + node[d] * h_;
  }
  const double known = in_band(node[0], node[1], node[2]) ? std::abs(sample(node[0], node[1], node[2])) : band_cm_;
  return known - (p - at).norm();
}

FieldSmooth DistanceField::smooth(const Vec3& p) const {
  // Per axis the four nodes i−1 … i+2 around the cell [i, i+1] holding p, with the cubic B-spline
  // weights at the fraction t and their first and second derivatives.
  int first[3];
  double b[3][4], db[3][4], ddb[3][4];
  for (int d = 0; d < 3; ++d) {
    const double u = std::clamp((p[d] - origin_[d]) / h_, 0.0, last_node_[d]);
    const int i = std::min(static_cast<int>(u), std::max(dims_[d] - 2, 0));
    const double t = u - i, s = 1.0 - t;
    first[d] = i - 1;
    b[d][0] = s * s * s / 6.0;
    b[d][1] = (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0;
    b[d][2] = (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0;
    b[d][3] = t * t * t / 6.0;
    db[d][0] = -0.5 * s * s / h_;
    db[d][1] = (1.5 * t * t - 2.0 * t) / h_;
    db[d][2] = (-1.5 * t * t + t + 0.5) / h_;
    db[d][3] = 0.5 * t * t / h_;
    ddb[d][0] = s / (h_ * h_);
    ddb[d][1] = (3.0 * t - 2.0) / (h_ * h_);
    ddb[d][2] = (1.0 - 3.0 * t) / (h_ * h_);
    ddb[d][3] = t / (h_ * h_);
  }
  // Separably: along x for each of the 16 lines (value, d/dx, d²/dx²), then along y, then z.
  int64_t offset[3][4];
  for (int d = 0; d < 3; ++d)
    for (int a = 0; a < 4; ++a) offset[d][a] = stride_[d] * std::clamp(first[d] + a, 0, dims_[d] - 1);
  const double* v = samples_->data();
  FieldSmooth out;
  double& f = out.value;
  double fx = 0, fy = 0, fz = 0, fxx = 0, fyy = 0, fzz = 0, fxy = 0, fxz = 0, fyz = 0;
  for (int c = 0; c < 4; ++c) {
    double l0 = 0, lx = 0, ly = 0, lxx = 0, lxy = 0, lyy = 0;  // the plane z = c, weighted in x and y
    for (int bj = 0; bj < 4; ++bj) {
      const double* line = v + offset[1][bj] + offset[2][c];
      double s0 = 0, s1 = 0, s2 = 0;
      for (int a = 0; a < 4; ++a) {
        const double x = line[offset[0][a]];
        s0 += x * b[0][a];
        s1 += x * db[0][a];
        s2 += x * ddb[0][a];
      }
      l0 += s0 * b[1][bj];
      lx += s1 * b[1][bj];
      ly += s0 * db[1][bj];
      lxx += s2 * b[1][bj];
      lxy += s1 * db[1][bj];
      lyy += s0 * ddb[1][bj];
    }
    f += l0 * b[2][c];
    fx += lx * b[2][c];
    fy += ly * b[2][c];
    fz += l0 * db[2][c];
    fxx += lxx * b[2][c];
    fyy += lyy * b[2][c];
    fzz += l0 * ddb[2][c];
    fxy += lxy * b[2][c];
    fxz += lx * db[2][c];
    fyz += ly * db[2][c];
  }
  out.gradient = Vec3(fx, fy, fz);
  out.hessian << fxx, fxy, fxz, fxy, fyy, fyz, fxz, fyz, fzz;
  return out;
}

}  // namespace hairfit
