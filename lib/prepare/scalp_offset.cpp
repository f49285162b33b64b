#include "prepare/scalp_offset.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <queue>

#include "core/error.h"
#include "core/smoothstep.h"
#include "prepare/surface_checks.h"

namespace hairfit {

namespace {

// Monomials x^a y^b z^c of a unit vector with a + b + c ≤ 2 and c ≤ 1 (z² = 1 − x² − y² adds
// nothing on the sphere): a basis of the spherical harmonics up to degree 2.
Eigen::Matrix<double, 9, 1> envelope_basis(const Vec3& u) {
  Eigen::Matrix<double, 9, 1> b;
  b << 1.0, u.x(), u.y(), u.z(), u.x() * u.x(), u.x() * u.y(), u.y() * u.y(), u.x() * u.z(), u.y() * u.z();
  return b;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

void smooth_off_hairline(const std::vector<std::vector<int>>& next, const std::vector<int>& hairline,
                         std::vector<double>& f, int passes, const std::function<void(int)>& after) {
  const int n = static_cast<int>(next.size());
  std::vector<char> on_hairline(n, 0);
  for (int v : hairline) on_hairline[v] = 1;
  std::vector<double> previous;
  for (int pass = 0; pass < passes; ++pass) {
    previous = f;
    for (int v = 0; v < n; ++v) {
      if (on_hairline[v] || next[v].empty()) continue;
      double mean = 0.0;
      for (int k : next[v]) mean += previous[k];
      f[v] = 0.5 * previous[v] + 0.5 * mean / next[v].size();
      if (after) after(v);
    }
  }
}

ScalpResult make_scalp(const Hull& hull, const ScalpOptions& o, const std::string& file) {
  if (!(o.crown_thickness > 0.0) || !(o.ramp > 0.0) || o.smoothing_passes < 0)
    throw InputError(file, "the crown thickness and the ramp must be positive lengths and the smoothing passes ≥ 0");
  const Mesh& mesh = hull.mesh;
  const Vec3 c = hull.centre;
  const std::vector<int> facing = inward_triangles(mesh, c);
  if (!facing.empty()) {
    const Vec3 p = triangle_centroid(mesh, facing.front());
    char text[512];
    std::snprintf(text, sizeof text,
                  "the hair hull is not star-shaped about the head centre (%.4g, %.4g, %.4g): %zu of its %zu "
                  "triangles face toward it, e.g. near (%.4g, %.4g, %.4g); the scalp is built by moving the hull "
                  "toward that centre, so leave out hair that hangs below or folds over (tighten the selection)",
                  c.x(), c.y(), c.z(), facing.size(), mesh.triangles.size(), p.x(), p.y(), p.z());
    throw InputError(file, text);
  }
  const int n = static_cast<int>(mesh.positions.size());
  std::vector<char> on_hairline(n, 0);
  for (int v : hull.hairline) on_hairline[v] = 1;
  std::vector<Vec3> u(n);
  std::vector<double> radius(n);
  for (int v = 0; v < n; ++v) {
    radius[v] = (mesh.positions[v] - c).norm();
    u[v] = (mesh.positions[v] - c) / radius[v];
  }
  const std::vector<double> area = vertex_areas(mesh);
  const auto next = vertex_neighbours(mesh);

  ScalpResult r;
  // The ramp: smoothstep of the distance from the hairline, then a few Jacobi passes so the
  // polygonal isolines of edge distances do not show.
  const std::vector<double> g = edge_distances(mesh, next, hull.hairline);
  const double g_max = *std::max_element(g.begin(), g.end());
  r.hairline_reach = g_max;
  r.ramp_length = std::min(o.ramp, 0.8 * g_max);
  std::vector<double> w(n);
  for (int v = 0; v < n; ++v) w[v] = smoothstep(g[v] / r.ramp_length);
  smooth_off_hairline(next, hull.hairline, w, 10);

  // The envelope: iteratively reweighted least squares with Tukey's biweight (c = 4.685 robust
  // standard deviations, from the median absolute residual), weighted by vertex area.
  Eigen::MatrixXd basis(n, 9);
  Eigen::VectorXd target(n);
  for (int v = 0; v < n; ++v) basis.row(v) = envelope_basis(u[v]).transpose(), target[v] = radius[v];
  // Only where the ramp is complete: nearer the hairline the hair thins toward the skin, which is
  // not the envelope (unless the hull is too small to have such a region).
  std::vector<double> fit_area = area;
  const long complete = std::count_if(w.begin(), w.end(), [](double x) { return x >= 0.99; });
  if (complete >= 30)
    for (int v = 0; v < n; ++v)
      if (w[v] < 0.99) fit_area[v] = 0.0;
  Eigen::VectorXd weight = Eigen::Map<Eigen::VectorXd>(fit_area.data(), n);
  Eigen::Matrix<double, 9, 1> coefficients;
  std::vector<double> residual(n);
  for (int iteration = 0; iteration < 12; ++iteration) {
    const Eigen::MatrixXd weighted = weight.asDiagonal() * basis;
    Eigen::Matrix<double, 9, 9> normal = basis.transpose() * weighted;
    normal.diagonal().array() += 1e-9 * normal.trace();
    coefficients = normal.ldlt().solve(weighted.transpose() * target);
    std::vector<double> absolute;
    for (int v = 0; v < n; ++v) {
      residual[v] = target[v] - basis.row(v).dot(coefficients);
      if (fit_area[v] > 0.0) absolute.push_back(std::abs(residual[v]));
    }
    const double scale = std::max(1e-6, 1.4826 * median(absolute));
    for (int v = 0; v < n; ++v) {
      const double z = residual[v] / (4.685 * scale);
      weight[v] = std::abs(z) < 1.0 ? fit_area[v] * std::pow(1.0 - z * z, 2) : 0.0;
    }
  }
  double sum = 0.0, kept = 0.0;
  for (int v = 0; v < n; ++v) {
    if (fit_area[v] == 0.0) continue;
    if (weight[v] > 0.0) sum += residual[v] * residual[v], ++kept;
    else ++r.envelope_outliers;
  }
  r.envelope_rms = kept > 0 ? std::sqrt(sum / kept) : 0.0;

  const double T = o.crown_thickness;
  // Where the hull bulges (a bun's steep sides), its vertices seen from the centre bunch up, which
  // would leave the scalp with slivers; relax their directions over the sphere, in proportion to w
  // so the hairline and its neighbourhood stay put.
  std::vector<Vec3> direction = u;
  for (int pass = 0; pass < o.smoothing_passes; ++pass) {
    const std::vector<Vec3> previous = direction;
    for (int v = 0; v < n; ++v) {
      if (on_hairline[v] || next[v].empty()) continue;
      Vec3 mean = Vec3::Zero();
      for (int k : next[v]) mean += previous[k];
      mean /= static_cast<double>(next[v].size());
      direction[v] = (previous[v] + 0.5 * w[v] * (mean - previous[v])).normalized();
    }
  }
  std::vector<double> rho(n);
  for (int v = 0; v < n; ++v)
    rho[v] = (1.0 - w[v]) * radius[v] + w[v] * (envelope_basis(direction[v]).dot(coefficients) - T);
  auto clamp = [&](int v) {
    const double highest = radius[v] - 0.5 * w[v] * T;
    rho[v] = std::clamp(rho[v], std::min(0.3 * radius[v], highest), highest);
  };
  for (int v = 0; v < n; ++v)
    if (!on_hairline[v]) clamp(v);
  smooth_off_hairline(next, hull.hairline, rho, o.smoothing_passes, clamp);

  r.method = "radial";
  r.scalp = mesh;
  r.hairline = hull.hairline;
  r.volume_vertex.assign(n, -1);
  for (int v : hull.hairline) r.volume_vertex[v] = v;
  r.thickness.assign(n, 0.0);
  r.ramp = w;
  for (int v = 0; v < n; ++v) {
    if (on_hairline[v]) continue;  // exactly the hull's hairline
    r.scalp.positions[v] = c + rho[v] * direction[v];
    r.thickness[v] = radius[v] - rho[v];
  }
  // The closed volume: the hull, then the floor's own vertices (the hairline is shared).
  r.volume = mesh;
  std::vector<int> floor_vertex(n);
  for (int v = 0; v < n; ++v) {
    if (on_hairline[v]) {
      floor_vertex[v] = v;
      continue;
    }
    floor_vertex[v] = static_cast<int>(r.volume.positions.size());
    r.volume.positions.push_back(c + std::max(0.2 * radius[v], rho[v] - w[v] * T) * direction[v]);
  }
  for (const Vec3i& t : mesh.triangles)
    r.volume.triangles.emplace_back(floor_vertex[t[0]], floor_vertex[t[2]], floor_vertex[t[1]]);
  return r;
}

}  // namespace hairfit
