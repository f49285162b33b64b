#include "guides/fall_rest.h"

#include <algorithm>
#include <cmath>

#include "guides/preguides.h"

namespace hairfit {

FallRegion fall_region(const Boundary& boundary, const Vec3& down, const Vec3& front) {
  FallRegion region;
  region.skin = [scalp = boundary.scalp](const Vec3& p, double& value, Vec3& gradient) {
    const FieldValueGradient v = scalp->value_and_gradient(p);
    value = v.value, gradient = v.gradient;
  };
  region.hull = [volume = boundary.volume](const Vec3& p, double& value, Vec3& gradient) {
    const FieldValueGradient v = volume->value_and_gradient(p);
    value = v.value, gradient = v.gradient;
  };
  region.down = down.normalized();
  region.front = front.normalized();
  region.step = 0.5 * boundary.volume->voxel();
  region.floor_past_hairline = boundary.floor_past_hairline;
  return region;
}

namespace {

// The point at arc length s along a polyline with cumulative lengths `arc`; past its end, on
// along its last chord.
Vec3 along_polyline(const std::vector<Vec3>& nodes, const std::vector<double>& arc, double s) {
  const std::size_t n = nodes.size();
  if (n == 1 || s <= 0.0) return nodes[0];
  if (s >= arc.back()) {
    const Vec3 last = nodes[n - 1] - nodes[n - 2];
    const double span = last.norm();
    return span > 0.0 ? Vec3(nodes[n - 1] + (s - arc.back()) / span * last) : nodes[n - 1];
  }
  const std::size_t k = std::upper_bound(arc.begin(), arc.end(), s) - arc.begin() - 1;  // arc[k] ≤ s < arc[k + 1]
  return nodes[k] + (s - arc[k]) / (arc[k + 1] - arc[k]) * (nodes[k + 1] - nodes[k]);
}

}  // namespace

StyledPath fall_rest_path(const FallRegion& region, const Vec3& root, const Vec3& normal, const Vec3& direction,
                          double length, double target, int segments) {
  const Fall fall = fall_from(region, RimHeights{}, root, normal, length + kFallLookAhead, target, true);
  const double h = length / segments;
  const double share = 1.0 - std::exp(-h / kFallRelaxation);
  std::vector<double> arc(fall.nodes.size(), 0.0);
  for (std::size_t k = 1; k < fall.nodes.size(); ++k) arc[k] = arc[k - 1] + (fall.nodes[k] - fall.nodes[k - 1]).norm();
  StyledPath path;
  Vec3 p = root, t = direction.normalized();
  path.nodes.push_back(p);
  path.tangents.push_back(t);
  for (int k = 0; k < segments; ++k) {
    Vec3 next = t;
    if (fall.nodes.size() > 1) {
      const Vec3 aim = along_polyline(fall.nodes, arc, (k * h) + kFallLookAhead) - p;
      if (aim.norm() > 1e-9) next = ((1.0 - share) * t + share * aim.normalized()).normalized();
    }
    p += h * (t + next).normalized();
    t = next;
    path.nodes.push_back(p);
    path.tangents.push_back(t);
  }
  return path;
}

std::vector<Vec3> fall_rest(const FallRegion& region, const Vec3& root, const Vec3& normal, const Mat3& root_frame,
                            double length, double target, int segments) {
  return rest_curvature(fall_rest_path(region, root, normal, root_frame.col(2), length, target, segments), root_frame);
}

}  // namespace hairfit
