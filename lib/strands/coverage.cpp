#include "strands/coverage.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/parallel.h"
#include "core/point_grid.h"

namespace hairfit {

std::vector<AreaSample> area_samples_on_triangles(const Mesh& mesh, int samples) {
  std::vector<double> cumulative(mesh.triangles.size());
  double total = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) cumulative[t] = total += triangle_area(mesh, static_cast<int>(t));
  std::vector<AreaSample> out;
  if (!(total > 0.0) || samples <= 0) return out;
  out.reserve(samples);
  // R2 (Roberts 2018): the additive recurrence with the plastic number's powers.
  constexpr double g = 1.32471795724474602596;
  const double a1 = 1.0 / g, a2 = 1.0 / (g * g);
  for (int k = 0; k < samples; ++k) {
    const double at = (k + 0.5) / samples * total;
    const std::size_t t = std::min<std::size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin(),
                                                cumulative.size() - 1);
    double u = std::fmod(0.5 + a1 * k, 1.0), v = std::fmod(0.5 + a2 * k, 1.0);
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    const Vec3i& tri = mesh.triangles[t];
    const Vec3& a = mesh.positions[tri[0]];
    out.push_back({static_cast<int>(t), a + u * (mesh.positions[tri[1]] - a) + v * (mesh.positions[tri[2]] - a)});
  }
  return out;
}

std::vector<Vec3> area_samples(const Mesh& mesh, int samples) {
  std::vector<Vec3> out;
  for (const AreaSample& s : area_samples_on_triangles(mesh, samples)) out.push_back(s.point);
  return out;
}

Coverage strand_coverage(const Mesh& hull, const std::vector<Vec3>& strand_points,
                         const std::function<bool(const Vec3&)>& counts, const CoverageOptions& o) {
  if (!(o.radius > 0.0) || o.samples < 1) throw std::invalid_argument("strand_coverage: needs radius > 0 and samples ≥ 1");
  Coverage result;
  const std::vector<Vec3> samples = area_samples(hull, o.samples);
  std::vector<signed char> state(samples.size(), -1);  // −1 not counted, 0 uncovered, 1 covered
  if (strand_points.empty()) {
    for (std::size_t k = 0; k < samples.size(); ++k) state[k] = counts(samples[k]) ? 0 : -1;
  } else {
    const PointGrid grid(strand_points, o.radius);
    parallel_for(static_cast<int>(samples.size()), o.threads, [&](int k) {
      if (!counts(samples[k])) return;
      state[k] = grid.nearest(samples[k], -1, o.radius) >= 0 ? 1 : 0;
    });
  }
  for (signed char s : state) {
    result.samples += s >= 0;
    result.covered += s == 1;
  }
  result.share = result.samples ? static_cast<double>(result.covered) / result.samples : 0.0;
  return result;
}

}  // namespace hairfit
