#include "guides/flow_crossing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/parallel.h"
#include "core/point_grid.h"

namespace hairfit {

namespace {

constexpr int kBins = 3600;  // 0.05° each over [0°, 180°]

// Unit tangent of every point: central differences, one-sided at the ends; zero where a curve's
// points coincide (such points take part in no pair).
std::vector<Vec3> point_tangents(const Curves& curves) {
  std::vector<Vec3> tangents(curves.points.size(), Vec3::Zero());
  for (std::size_t c = 0; c < curves.count(); ++c) {
    const std::size_t begin = curves.offsets[c], end = curves.offsets[c + 1];
    if (end - begin < 2) continue;
    for (std::size_t k = begin; k < end; ++k) {
      const Vec3 d = curves.points[std::min(k + 1, end - 1)] - curves.points[k > begin ? k - 1 : begin];
      const double n = d.norm();
      if (n > 0.0 && std::isfinite(n)) tangents[k] = d / n;
    }
  }
  return tangents;
}

}  // namespace

FlowCrossing flow_crossing(const Curves& curves, const FlowCrossingOptions& o) {
  if (!(o.near >= 0.0) || !(o.far > o.near) || !(o.angle >= 0.0 && o.angle <= 180.0))
    throw std::invalid_argument("flow_crossing: needs 0 ≤ near < far and an angle in [0°, 180°]");
  FlowCrossing result;
  const std::vector<Vec3>& points = curves.points;
  if (points.empty()) return result;
  const std::vector<Vec3> tangents = point_tangents(curves);
  std::vector<int> curve_of(points.size());
  for (std::size_t c = 0; c < curves.count(); ++c)
    std::fill(curve_of.begin() + curves.offsets[c], curve_of.begin() + curves.offsets[c + 1], static_cast<int>(c));
  const PointGrid grid(points, o.far);
  const double near2 = o.near * o.near;
  const double cos_limit = std::cos(o.angle * M_PI / 180.0);

  // Each pair is counted once, from its lower index; histograms per block of points, summed in
  // block order (integers: the totals do not depend on the thread count).
  const int count = static_cast<int>(points.size());
  constexpr int kBlock = 1024;
  const int blocks = (count + kBlock - 1) / kBlock;
  std::vector<std::vector<std::int64_t>> histograms(blocks);
  std::vector<std::int64_t> crossing(blocks, 0);
  parallel_for(blocks, o.threads, [&](int b) {
    std::vector<std::int64_t>& h = histograms[b];
    h.assign(kBins, 0);
    for (int i = b * kBlock; i < std::min(count, (b + 1) * kBlock); ++i) {
      if (tangents[i].isZero(0.0)) continue;
      grid.for_each_within(points[i], o.far, [&](int j, double d2) {
        if (j <= i || d2 < near2 || curve_of[j] == curve_of[i] || tangents[j].isZero(0.0)) return;
        const double c = std::clamp(tangents[i].dot(tangents[j]), -1.0, 1.0);
        crossing[b] += c < cos_limit;
        const int bin = std::min(kBins - 1, static_cast<int>(std::acos(c) * (180.0 / M_PI) * (kBins / 180.0)));
        ++h[bin];
      });
    }
  });
  std::vector<std::int64_t> total(kBins, 0);
  std::int64_t crossings = 0;
  for (int b = 0; b < blocks; ++b) {
    for (int k = 0; k < kBins; ++k) total[k] += histograms[b][k];
    crossings += crossing[b];
  }
  for (std::int64_t n : total) result.pairs += n;
  if (result.pairs == 0) return result;
  result.crossing_share = static_cast<double>(crossings) / static_cast<double>(result.pairs);
  // The median: the bin holding the middle pair, read at its centre.
  std::int64_t seen = 0;
  for (int k = 0; k < kBins; ++k) {
    seen += total[k];
    if (2 * seen >= result.pairs) {
      result.median_degrees = (k + 0.5) * (180.0 / kBins);
      break;
    }
  }
  return result;
}

}  // namespace hairfit
