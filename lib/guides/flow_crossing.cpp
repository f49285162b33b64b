#include "guides/flow_crossing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/parallel.h"
#include "core/point_grid.h"
#include "core/random.h"

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

// The bin of the angle whose cosine is c: k with c in (cos((k + 1)·δ), cos(k·δ)], found by
// comparing c with the bins' edges (no acos per pair): a table over c ∈ [−1, 1] in steps finer
// than the narrowest bin gives the first candidate, and the edges settle it.
class AngleBins {
 public:
  AngleBins() : edges_(kBins + 1), first_(kTable + 1) {
    for (int k = 0; k <= kBins; ++k) edges_[k] = std::cos(k * (M_PI / kBins));
    edges_[0] = 1.0, edges_[kBins] = -1.0;
    // first_[s]: the bin of the largest c in table step s, c = 1 − 2s/kTable (bins run from c = 1).
    int k = 0;
    for (int s = 0; s <= kTable; ++s) {
      const double c = 1.0 - 2.0 * s / kTable;
      while (k < kBins - 1 && c <= edges_[k + 1]) ++k;
      first_[s] = k;
    }
  }
  int operator()(double c) const {
    const int s = std::clamp(static_cast<int>((1.0 - c) * (0.5 * kTable)), 0, kTable);
    int k = first_[s];
    while (k < kBins - 1 && c <= edges_[k + 1]) ++k;
    return k;
  }

 private:
  static constexpr int kTable = 1 << 16;
  std::vector<double> edges_;  // edges_[k] = cos(k·δ), descending from 1 to −1
  std::vector<int> first_;
};

}  // namespace

FlowCrossing flow_crossing(const Curves& curves, const FlowCrossingOptions& o) {
  if (!(o.near >= 0.0) || !(o.far > o.near) || !(o.angle >= 0.0 && o.angle <= 180.0))
    throw std::invalid_argument("flow_crossing: needs 0 ≤ near < far and an angle in [0°, 180°]");
  FlowCrossing result;
  const std::vector<Vec3> tangents = point_tangents(curves);
  // The points that take part (a tangent), with their curves, in the grid's cell order, so that
  // the pair loops read memory contiguously.
  std::vector<Vec3> points, directions;
  std::vector<int> curve_of;
  for (std::size_t c = 0; c < curves.count(); ++c)
    for (std::size_t k = curves.offsets[c]; k < curves.offsets[c + 1]; ++k)
      if (!tangents[k].isZero(0.0)) {
        points.push_back(curves.points[k]);
        directions.push_back(tangents[k]);
        curve_of.push_back(static_cast<int>(c));
      }
  if (points.empty()) return result;
  const PointGrid grid(points, o.far, /*keep_points=*/false);  // the points in its order are `at` below
  const int count = static_cast<int>(points.size());
  std::vector<Vec3> at(count), along(count);
  std::vector<int> curve(count);
  for (int k = 0; k < count; ++k) {
    const int i = grid.order()[k];
    at[k] = points[i], along[k] = directions[i], curve[k] = curve_of[i];
  }
  const double near2 = o.near * o.near, far2 = o.far * o.far;
  const double cos_limit = std::cos(o.angle * M_PI / 180.0);
  const AngleBins bin_of;

  // Exact: each pair is counted once, within a cell and between a cell and each neighbouring cell
  // that comes after it. Sampled: every pair of a query point (one in `stride`, by a hash of its
  // index: an even sample would follow the curves' node pattern) is counted from it. Histograms
  // per block of cells, summed in block order (integers: the totals do not depend on the thread
  // count).
  const int stride = o.max_points > 0 && count > o.max_points ? (count + o.max_points - 1) / o.max_points : 1;
  std::vector<char> query(count, 1);
  if (stride > 1)
    for (int k = 0; k < count; ++k) query[k] = mix64(static_cast<std::uint64_t>(grid.order()[k])) % stride == 0;
  const int cells = grid.cell_count();
  constexpr int kBlock = 64;
  const int blocks = (cells + kBlock - 1) / kBlock;
  std::vector<std::vector<std::int64_t>> histograms(blocks);
  std::vector<std::int64_t> crossing(blocks, 0);
  parallel_for(blocks, o.threads, [&](int b) {
    std::vector<std::int64_t>& h = histograms[b];
    h.assign(kBins, 0);
    std::int64_t crossed = 0;
    // Point i against points [from, to) (never i itself): the cosines of the pairs that count are
    // gathered without a branch on the distance (half the tests fail it, at random), then binned.
    std::vector<double> cosines;
    auto pairs_of = [&](int i, int from, int to) {
      cosines.resize(static_cast<std::size_t>(std::max(0, to - from)));
      const Vec3 p = at[i], t = along[i];
      const int own = curve[i];
      int kept = 0;
      for (int j = from; j < to; ++j) {
        const double dx = at[j].x() - p.x(), dy = at[j].y() - p.y(), dz = at[j].z() - p.z();
        const double d2 = dx * dx + dy * dy + dz * dz;
        cosines[kept] = along[j].x() * t.x() + along[j].y() * t.y() + along[j].z() * t.z();
        kept += (d2 >= near2) & (d2 <= far2) & (curve[j] != own) & (j != i);
      }
      for (int k = 0; k < kept; ++k) {
        const double c = std::clamp(cosines[k], -1.0, 1.0);
        crossed += c < cos_limit;
        ++h[bin_of(c)];
      }
    };
    std::vector<PointGrid::CellRange> near_cells;
    for (int cell = b * kBlock; cell < std::min(cells, (b + 1) * kBlock); ++cell) {
      const int begin = grid.cell_begin(cell), end = grid.cell_begin(cell + 1);
      grid.neighbourhood(cell, 1, near_cells);
      for (const PointGrid::CellRange& other : near_cells) {
        if (stride == 1) {
          if (other.begin < begin) continue;
          for (int i = begin; i < end; ++i) pairs_of(i, other.begin == begin ? i + 1 : other.begin, other.end);
        } else {
          for (int i = begin; i < end; ++i)
            if (query[i]) pairs_of(i, other.begin, other.end);
        }
      }
    }
    crossing[b] = crossed;
  });
  std::vector<std::int64_t> total(kBins, 0);
  std::int64_t crossings = 0;
  for (int b = 0; b < blocks; ++b) {
    for (int k = 0; k < kBins; ++k) total[k] += histograms[b][k];
    crossings += crossing[b];
  }
  std::int64_t counted = 0;
  for (std::int64_t n : total) counted += n;
  result.sampled_points = stride > 1 ? static_cast<int>(std::count(query.begin(), query.end(), 1)) : 0;
  // Sampled, each pair is seen from each of its ends that is a query point: 2·sampled / count
  // times on average.
  result.pairs = stride > 1 && result.sampled_points > 0
                     ? static_cast<std::int64_t>(std::llround(0.5 * static_cast<double>(counted) * count / result.sampled_points))
                     : counted;
  if (counted == 0) return result;
  result.crossing_share = static_cast<double>(crossings) / static_cast<double>(counted);
  // The median: the bin holding the middle pair, read at its centre.
  std::int64_t seen = 0;
  for (int k = 0; k < kBins; ++k) {
    seen += total[k];
    if (2 * seen >= counted) {
      result.median_degrees = (k + 0.5) * (180.0 / kBins);
      break;
    }
  }
  return result;
}

}  // namespace hairfit
