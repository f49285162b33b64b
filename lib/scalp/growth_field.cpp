#include "scalp/growth_field.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "core/smoothstep.h"
#include "scalp/hanging.h"

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

Vec3 down_guidance(const Vec3& normal, const Vec3& down, const Vec3& front) {
  return down.normalized().cross(normal).norm() * tangent_toward_down(normal, down, front);
}

Vec3 growth_guidance(const Vec3& normal, const Vec3& thickness_gradient, const RootOptions& o, const Vec3& down,
                     const Vec3& front) {
  const Vec3 toward_down = down_guidance(normal, down, front);
  if (o.tilt_toward == TiltToward::down) return toward_down;
  const Vec3 g = thickness_gradient - thickness_gradient.dot(normal) * normal;
  const double slope = g.norm();
  if (!(slope > 1e-12)) return toward_down;  // also NaN gradients
  const double w = std::min(1.0, slope / kFlatLayerGradient);
  return w * (g / slope) + (1.0 - w) * toward_down;
}

namespace {

// a in the tangent plane with this normal, turned clockwise (seen from outside) by `degrees`.
Vec3 turned_clockwise(const Vec3& a, const Vec3& normal, double degrees) {
  const double angle = degrees * M_PI / 180.0;
  return std::cos(angle) * a - std::sin(angle) * normal.cross(a);
}

// The surface gradient of a piecewise-linear function with values f at the vertices,
// ∇f = Σ_k f_k (N × e_k) / |N|² per triangle (N = (p1 − p0) × (p2 − p0), e_k the edge opposite
// corner k; either winding gives the same), averaged at each vertex by area.
std::vector<Vec3> vertex_gradients(const Mesh& mesh, const std::vector<double>& f) {
  const int n = static_cast<int>(mesh.positions.size());
  std::vector<Vec3> gradient(n, Vec3::Zero());
  std::vector<double> weight(n, 0.0);
  for (const Vec3i& t : mesh.triangles) {
    const Vec3 p[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
    const Vec3 normal = (p[1] - p[0]).cross(p[2] - p[0]);
    const double n2 = normal.squaredNorm();
    if (!(n2 > 0.0)) continue;
    Vec3 g = Vec3::Zero();
    for (int k = 0; k < 3; ++k) g += f[t[k]] * normal.cross(p[(k + 2) % 3] - p[(k + 1) % 3]);
    g /= n2;
    const double area = 0.5 * std::sqrt(n2);
    for (int k = 0; k < 3; ++k) {
      gradient[t[k]] += area * g;
      weight[t[k]] += area;
    }
  }
  for (int i = 0; i < n; ++i)
    if (weight[i] > 0.0) gradient[i] /= weight[i];
  return gradient;
}

}  // namespace

std::vector<double> vertex_thickness(const ScalpChart& ch, const ThicknessField& thickness, int threads) {
  std::vector<double> values(ch.mesh.positions.size());
  parallel_for(static_cast<int>(values.size()), threads, [&](int i) { values[i] = thickness(ch.mesh.positions[i]).value; });
  return values;
}

std::vector<double> layer_end_distance(const ScalpChart& ch, const std::vector<double>& thickness,
                                       const ThicknessField& field, double probe, bool from_rim_only) {
  const Mesh& mesh = ch.mesh;
  const int n = static_cast<int>(mesh.positions.size());
  std::vector<char> end(n, 0);
  for (int i = 0; i < n; ++i) end[i] = !(thickness[i] > 0.0);
  const std::vector<std::vector<int>> neighbours = vertex_neighbours(mesh);
  const int loop = static_cast<int>(ch.boundary.size());
  for (int k = 0; k < loop; ++k) {
    const int v = ch.boundary[k];
    const Vec3& p = mesh.positions[v];
    const Vec3& normal = ch.vertex_normals[v];
    const Vec3 along = mesh.positions[ch.boundary[(k + 1) % loop]] - mesh.positions[ch.boundary[(k + loop - 1) % loop]];
    Vec3 inward = Vec3::Zero();
    for (int j : neighbours[v]) inward += mesh.positions[j];
    inward = inward / std::max<std::size_t>(1, neighbours[v].size()) - p;
    Vec3 out = -(inward - inward.dot(normal) * normal);
    if (along.norm() > 0.0) out -= out.dot(along.normalized()) * along.normalized();
    if (!(out.norm() > 1e-12)) continue;
    out.normalize();
    // Just beyond the hairline, a little off the skin: outside the hull, the layer ends here.
    if (!(field(p + probe * out + 0.25 * probe * normal).value > 0.0)) end[v] = 1;
  }
  if (from_rim_only) {  // keep the ends joined to the rim through ends: a groove's or a field's speck is no end
    std::vector<char> kept(n, 0);
    std::vector<int> stack;
    for (int v : ch.boundary)
      if (end[v] && !kept[v]) kept[v] = 1, stack.push_back(v);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int j : neighbours[v])
        if (end[j] && !kept[j]) kept[j] = 1, stack.push_back(j);
    }
    end = std::move(kept);
  }
  std::vector<int> sources;
  for (int i = 0; i < n; ++i)
    if (end[i]) sources.push_back(i);
  return edge_distances(mesh, neighbours, sources);
}

namespace {

// The direction away from the nearest point of a polyline (one point: away from it), in the
// tangent plane at p with this normal, and that point's distance; zero direction on the line.
Vec3 away_from(const std::vector<Vec3>& line, const Vec3& p, const Vec3& normal, double& distance) {
  Vec3 nearest = line.front();
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const Vec3 e = line[k + 1] - line[k];
    const double t = e.squaredNorm() > 0.0 ? std::clamp((p - line[k]).dot(e) / e.squaredNorm(), 0.0, 1.0) : 0.0;
    const Vec3 q = line[k] + t * e;
    if ((p - q).squaredNorm() < (p - nearest).squaredNorm()) nearest = q;
  }
  distance = (p - nearest).norm();
  Vec3 a = p - nearest;
  a -= a.dot(normal) * normal;
  return a.norm() > 1e-12 ? Vec3(a.normalized()) : Vec3::Zero();
}

}  // namespace

void add_declared_style(const ScalpChart& ch, const RootOptions& o, std::vector<Vec3>& guidance) {
  const Mesh& mesh = ch.mesh;
  auto on_scalp = [&](const Vec2& chart_point) { return surface_position(ch, locate_in_chart(ch, chart_point)); };
  std::vector<std::pair<std::vector<Vec3>, double>> features;  // polyline, radius (cm)
  if (o.whorl_radius > 0.0) features.push_back({{on_scalp(o.whorl)}, o.whorl_radius});
  if (o.parting_radius > 0.0) {
    std::vector<Vec3> line;
    constexpr int kSteps = 32;
    for (int k = 0; k <= kSteps; ++k) line.push_back(on_scalp(o.parting + (o.whorl - o.parting) * (double(k) / kSteps)));
    features.push_back({line, o.parting_radius});
  }
  for (std::size_t f = 0; f < features.size(); ++f)
    for (int i = 0; i < static_cast<int>(mesh.positions.size()); ++i) {
      const Vec3& normal = ch.vertex_normals[i];
      double d = 0.0;
      Vec3 a = away_from(features[f].first, mesh.positions[i], normal, d);
      if (a.isZero(0.0)) continue;
      if (f == 0 && o.whorl_radius > 0.0) a = turned_clockwise(a, normal, o.swirl);  // the whorl spirals
      const double sure = std::exp(-(d * d) / (features[f].second * features[f].second));
      guidance[i] = sure * a + (1.0 - sure) * guidance[i];
    }
}

DirectionField make_growth_field(const ScalpChart& ch, const RootInputs& in, const RootOptions& o, const Exec& exec) {
  const Mesh& mesh = ch.mesh;
  const int n = static_cast<int>(mesh.positions.size());
  const std::vector<double> thickness =
      o.tilt_toward != TiltToward::down ? vertex_thickness(ch, in.thickness, exec.threads) : std::vector<double>(n, 0.0);
  std::vector<Vec3> guidance(n);
  if (o.comb == Comb::from_crown) {  // combed from the crown: down, and back across the top
    for (int i = 0; i < n; ++i) guidance[i] = down_guidance(ch.vertex_normals[i], ch.down, ch.front);
  } else if (o.tilt_toward == TiltToward::down) {
    for (int i = 0; i < n; ++i) guidance[i] = growth_guidance(ch.vertex_normals[i], Vec3::Zero(), o, ch.down, ch.front);
  } else {
    const std::vector<Vec3> gradient = vertex_gradients(mesh, thickness);
    // Where the layer ends within a hair's length, the hair has to grow away from that end: the
    // gradient of the distance to it takes over, fully at the end, not at all a length away.
    const std::vector<double> reach = layer_end_distance(ch, thickness, in.thickness, kLayerEndProbe);
    const std::vector<Vec3> away = vertex_gradients(mesh, reach);
    const double hair = longest_hair(in, o);
    for (int i = 0; i < n; ++i) {
      const Vec3& normal = ch.vertex_normals[i];
      Vec3 local = growth_guidance(normal, gradient[i], o, ch.down, ch.front);
      double hanging = 0.0;
      if (o.tilt_toward == TiltToward::hanging) {  // where hair hangs, toward down
        hanging = in.vertex_hang_weights.empty() ? hang_weight(in.hangs[i], hair) : in.vertex_hang_weights[i];
        local = hanging * down_guidance(normal, ch.down, ch.front) + (1.0 - hanging) * local;
      }
      const Vec3 a = turned_clockwise(away[i] - away[i].dot(normal) * normal, normal, o.swirl);
      // A root with a hair's length of layer below it falls there: it need not turn away from
      // where the layer ends elsewhere (MakeHuman short04's temples then fall over the sideburns).
      const double length = in.vertex_lengths.empty() ? o.length : in.vertex_lengths[i];
      const double urgency = (std::isfinite(reach[i]) ? smoothstep(1.0 - reach[i] / length) : 0.0) * (1.0 - hanging);
      guidance[i] = a.norm() > 1e-12 ? Vec3(urgency * a.normalized() + (1.0 - urgency) * local) : local;
    }
  }
  // The hull's grain steers it where it is sure: a line, turned to agree with the guidance so far
  // (combed from the crown: with the tangent toward down, which the guidance is only where it is sure).
  if (o.flow == FlowModel::relief && in.grain.size() == guidance.size())
    for (int i = 0; i < n; ++i) {
      const Vec3& g = in.grain[i];
      const double sure = std::min(1.0, g.norm());
      if (!(sure > 0.0)) continue;
      const Vec3 sign = o.comb == Comb::from_crown ? tangent_toward_down(ch.vertex_normals[i], ch.down, ch.front)
                                                   : guidance[i];
      const Vec3 along = g.dot(sign) < 0.0 ? Vec3(-g / g.norm()) : Vec3(g / g.norm());
      guidance[i] = sure * along + (1.0 - sure) * guidance[i];
    }
  add_declared_style(ch, o, guidance);
  DirectionFieldOptions field;
  field.smoothing = o.flow_smoothing;
  return smoothest_aligned_field(mesh, ch.vertex_normals, guidance, field);
}

}  // namespace hairfit
