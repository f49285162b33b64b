#include "scalp/hull_hair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "core/smoothstep.h"
#include "scalp/growth_field.h"

namespace hairfit {

HullHair hull_hair(const std::vector<Fall>& falls, double lying_length) {
  return hull_hair(falls, std::vector<double>(falls.size(), lying_length));
}

HullHair hull_hair(const std::vector<Fall>& falls, const std::vector<double>& lying_lengths) {
  if (lying_lengths.size() != falls.size()) throw std::invalid_argument("hull_hair: one lying length per fall");
  HullHair h;
  h.hang_weights.reserve(falls.size());
  h.lengths.reserve(falls.size());
  for (std::size_t i = 0; i < falls.size(); ++i) {
    const Fall& f = falls[i];
    const double phi = smoothstep(f.below_rim / kHangRamp);
    h.hang_weights.push_back(phi);
    const double lying = lying_lengths[i];
    h.lengths.push_back(std::max(std::min(kShortestHullHair, lying), phi * (f.length - kFallTipMargin) + (1.0 - phi) * lying));
    h.hangs = h.hangs || phi > 0.0;
  }
  return h;
}

std::vector<double> combed_lengths(const ScalpChart& chart, const ThicknessField& thickness, double fallback, int threads) {
  std::vector<double> lengths = layer_end_distance(chart, vertex_thickness(chart, thickness, threads), thickness,
                                                   kLayerEndProbe, /*from_rim_only=*/true);
  for (double& l : lengths)
    l = std::isfinite(l) ? std::clamp(std::max(l - kCombedTipMargin, kCombedShareNearEnd * l), kShortestCombedHair,
                                      kLongestCombedHair)
                         : fallback;
  return lengths;
}

CombChoice comb_from_hull(const ScalpChart& chart, const ThicknessField& thickness, const std::vector<Fall>& falls) {
  const Mesh& mesh = chart.mesh;
  if (falls.size() != mesh.positions.size()) throw std::invalid_argument("comb_from_hull: one fall per scalp vertex");
  const std::vector<double> area = vertex_areas(mesh);
  double total = 0.0, up = 0.0, hanging = 0.0;
  for (std::size_t v = 0; v < area.size(); ++v) {
    const Vec3& normal = chart.vertex_normals[v];
    const Vec3 gradient = thickness(mesh.positions[v]).gradient;
    const Vec3 along = gradient - gradient.dot(normal) * normal;
    total += area[v];
    // A gradient normal to the scalp (up to round-off in the normal) points neither way.
    const bool along_scalp = along.norm() > 1e-9 * gradient.norm();
    if (along_scalp && along.dot(tangent_toward_down(normal, chart.down, chart.front)) < 0.0) up += area[v];
    if (smoothstep(falls[v].below_rim / kHangRamp) > 0.5) hanging += area[v];
  }
  CombChoice c;
  if (!(total > 0.0)) return c;
  c.thickening_up = up / total;
  c.hanging = hanging / total;
  if (c.thickening_up >= kCombedThickeningShare && c.hanging < kCombedHangingShare) c.comb = Comb::from_crown;
  return c;
}

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + m, v.end());
  return v[m];
}

}  // namespace

std::vector<HullHairRegion> hull_hair_regions(const ScalpChart& chart, const std::vector<Fall>& falls,
                                              const HullHair& hair) {
  const RimHeights rim = rim_heights(chart);
  const Vec3 front = (chart.front - chart.front.dot(rim.up) * rim.up).normalized();
  const Vec3 left = rim.up.cross(front);
  std::array<HullHairRegion, 4> regions{{{"front"}, {"left"}, {"back"}, {"right"}}};
  std::array<std::vector<double>, 4> lengths, below;
  std::array<int, 4> hanging{};
  for (std::size_t v = 0; v < falls.size(); ++v) {
    const Vec3 q = chart.mesh.positions[v] - rim.centre;
    const double angle = std::atan2(q.dot(left), q.dot(front));  // 0 front, π/2 left
    const int r = static_cast<int>(std::floor(angle / (0.5 * M_PI) + 0.5 + 4.0)) % 4;
    lengths[r].push_back(hair.lengths[v]);
    below[r].push_back(falls[v].below_rim);
    hanging[r] += hair.hang_weights[v] > 0.5;
  }
  std::vector<HullHairRegion> out;
  for (int r = 0; r < 4; ++r) {
    HullHairRegion g = regions[r];
    g.vertices = static_cast<int>(lengths[r].size());
    g.hanging_share = g.vertices ? static_cast<double>(hanging[r]) / g.vertices : 0.0;
    g.median_length = median(lengths[r]);
    g.median_below_rim = median(below[r]);
    out.push_back(g);
  }
  return out;
}

}  // namespace hairfit
