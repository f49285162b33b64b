#include "scalp/hanging.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "core/smoothstep.h"

namespace hairfit {

namespace {

// Whether the probe may stand at p: in the hull's region and not in the head. `distance` and
// `gradient` receive the skin's field there.
bool in_layer(const HangProbe& probe, const Vec3& p, double& distance, Vec3& gradient) {
  if (!probe.in_volume(p)) return false;
  probe.skin(p, distance, gradient);
  return distance >= 0.0;  // false in the head, and where the field says nothing (NaN)
}

constexpr int kExitBisections = 20;  // the last step's exit, to 2⁻²⁰ of a step

}  // namespace

double hang_length(const HangProbe& probe, const Vec3& root, const Vec3& normal, double cap) {
  if (!(cap > 0.0) || !(probe.step > 0.0)) return 0.0;
  Vec3 p = root + kHangStart * normal;
  double distance = 0.0, travelled = 0.0;
  Vec3 gradient = Vec3::Zero();
  if (!in_layer(probe, p, distance, gradient)) return 0.0;
  while (travelled < cap) {
    const double step = std::min(probe.step, cap - travelled);
    // On the skull: down along the skin's level surface, which vanishes at the crown (the hair has
    // nowhere to fall). Heavy hair leaves the skull where it turns under (the skin faces down) and
    // hangs free, as a chain does; weightless hair keeps to a skin facing down.
    Vec3 along = probe.down;
    if (distance < kHangHug && !(probe.falls_free && gradient.dot(probe.down) > 0.0)) {
      const double g = gradient.norm();
      if (g > 1e-9) along -= along.dot(gradient / g) * (gradient / g);
      const double a = along.norm();
      if (!(a > 1e-3)) break;
      along /= a;
    }
    if (in_layer(probe, p + step * along, distance, gradient)) {
      p += step * along;
      travelled += step;
      continue;
    }
    // The layer ends within this step: where, by bisection on the step.
    double inside = 0.0, outside = step;
    for (int k = 0; k < kExitBisections; ++k) {
      const double mid = 0.5 * (inside + outside);
      double d = 0.0;
      Vec3 g;
      (in_layer(probe, p + mid * along, d, g) ? inside : outside) = mid;
    }
    travelled += inside;
    break;
  }
  return std::min(travelled, cap);
}

std::vector<double> vertex_hangs(const ScalpChart& chart, const HangProbe& probe, double cap, int threads,
                                 double margin) {
  const int n = static_cast<int>(chart.mesh.positions.size());
  std::vector<double> hangs(n, 0.0);
  parallel_for(n, threads, [&](int v) {
    const double hang = hang_length(probe, chart.mesh.positions[v], chart.vertex_normals[v], cap + margin);
    hangs[v] = std::max(0.0, hang - margin);  // hang ≥ 0, so exactly the hang without a margin
  });
  return hangs;
}

double hang_weight(double hang, double length) { return length > 0.0 ? smoothstep(hang / length) : 0.0; }

double downness(const Vec3& direction, const Vec3& normal, const Vec3& down) {
  const Vec3 toward_down = down.normalized() - down.normalized().dot(normal) * normal;  // |…| = |down × normal|
  Vec3 along = direction - direction.dot(normal) * normal;
  const double a = along.norm();
  if (!(a > 1e-12)) return 0.0;
  return std::max(0.0, (along / a).dot(toward_down));
}

double hanging_length(double length, double hang, double weight) {
  const double shortest = std::min(length, kShortestHangingHair);
  return std::max(shortest, length - std::clamp(weight, 0.0, 1.0) * std::max(0.0, length - hang));
}

double hang_at(const ScalpChart& chart, const std::vector<double>& hangs, const SurfacePoint& point) {
  const Vec3i& t = chart.mesh.triangles[point.triangle];
  return point.barycentric[0] * hangs[t[0]] + point.barycentric[1] * hangs[t[1]] + point.barycentric[2] * hangs[t[2]];
}

}  // namespace hairfit
