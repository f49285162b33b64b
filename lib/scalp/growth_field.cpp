#include "scalp/growth_field.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace hairfit {

Vec3 tangent_toward_down(const Vec3& normal, const Vec3& down, const Vec3& front) {
  Vec3 tangent = down - down.dot(normal) * normal;
  if (tangent.norm() < 1e-9) tangent = -front + front.dot(normal) * normal;
  if (tangent.norm() < 1e-9) tangent = normal.unitOrthogonal();
  return tangent.normalized();
}

Vec3 tilted(const Vec3& normal, const Vec3& unit_tangent, double tilt_degrees) {
  const double angle = tilt_degrees * M_PI / 180.0;
  return (std::cos(angle) * normal + std::sin(angle) * unit_tangent).normalized();
}

Vec3 growth_guidance(const Vec3& normal, const Vec3& thickness_gradient, const RootOptions& o, const Vec3& down,
                     const Vec3& front) {
  const Vec3 toward_down = tangent_toward_down(normal, down, front);
  const double sure_of_down = down.normalized().cross(normal).norm();
  if (o.tilt_toward == TiltToward::down) return sure_of_down * toward_down;
  const Vec3 g = thickness_gradient - thickness_gradient.dot(normal) * normal;
  const double slope = g.norm();
  if (!(slope > 1e-12)) return sure_of_down * toward_down;  // also NaN gradients
  const double w = std::min(1.0, slope / kFlatLayerGradient);
  return w * (g / slope) + (1.0 - w) * sure_of_down * toward_down;
}

DirectionField make_growth_field(const ScalpChart& ch, const RootOptions& o) {
  const Mesh& mesh = ch.mesh;
  const int n = static_cast<int>(mesh.positions.size());
  std::vector<double> thickness(n, 0.0);
  if (o.tilt_toward == TiltToward::thicker)
    parallel_for(n, o.threads, [&](int i) { thickness[i] = o.thickness(mesh.positions[i]).value; });
  // The surface gradient of the piecewise-linear thickness, ∇T = Σ_k T_k (N × e_k) / |N|² with
  // N = (p1 − p0) × (p2 − p0) and e_k the edge opposite corner k (either winding gives the same),
  // averaged at the vertices by area.
  std::vector<Vec3> gradient(n, Vec3::Zero());
  std::vector<double> weight(n, 0.0);
  if (o.tilt_toward == TiltToward::thicker)
    for (const Vec3i& t : mesh.triangles) {
      const Vec3 p[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
      const Vec3 normal = (p[1] - p[0]).cross(p[2] - p[0]);
      const double n2 = normal.squaredNorm();
      if (!(n2 > 0.0)) continue;
      Vec3 g = Vec3::Zero();
      for (int k = 0; k < 3; ++k) g += thickness[t[k]] * normal.cross(p[(k + 2) % 3] - p[(k + 1) % 3]);
      g /= n2;
      const double area = 0.5 * std::sqrt(n2);
      for (int k = 0; k < 3; ++k) {
        gradient[t[k]] += area * g;
        weight[t[k]] += area;
      }
    }
  std::vector<Vec3> guidance(n);
  for (int i = 0; i < n; ++i) {
    const Vec3 g = weight[i] > 0.0 ? Vec3(gradient[i] / weight[i]) : Vec3::Zero();
    guidance[i] = growth_guidance(ch.vertex_normals[i], g, o, ch.down, ch.front);
  }
  DirectionFieldOptions field;
  field.smoothing = o.flow_smoothing;
  return smoothest_aligned_field(mesh, ch.vertex_normals, guidance, field);
}

}  // namespace hairfit
