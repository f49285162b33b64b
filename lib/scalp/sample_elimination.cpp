#include "scalp/sample_elimination.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/parallel.h"
#include "scalp/point_grid.h"

namespace hairfit {

std::vector<int> eliminate_samples(const std::vector<Vec3>& points, const std::vector<double>& radius, int target,
                                   int threads) {
  const int m = static_cast<int>(points.size());
  std::vector<int> kept;
  if (target >= m) {
    kept.resize(m);
    std::iota(kept.begin(), kept.end(), 0);
    return kept;
  }
  if (target <= 0) return kept;

  const double smallest = *std::min_element(radius.begin(), radius.end());
  const PointGrid grid(points, 3.0 * smallest);
  const double limit = 0.65 * (1.0 - std::pow(static_cast<double>(target) / m, 1.5));
  auto pair_weight = [&](int i, int j, double d2) {
    const double r = std::min(radius[i], radius[j]);
    const double d = std::max(std::sqrt(d2), limit * r);
    const double x = 1.0 - d / (2.0 * r);
    const double x2 = x * x, x4 = x2 * x2;
    return x4 * x4;
  };
  auto interacts = [&](int i, int j, double d2) {
    const double r = std::min(radius[i], radius[j]);
    return j != i && d2 < 4.0 * r * r;
  };

  // Neighbour lists (CSR), built cell by cell so each neighbouring cell is looked up once per
  // cell; a point's list is in the grid's fixed order, so weights are thread-independent.
  const std::vector<int>& order = grid.order();
  auto scan_cell = [&](int cell, auto&& emit) {
    double reach_radius = 0.0;
    for (int k = grid.cell_begin(cell); k < grid.cell_begin(cell + 1); ++k) reach_radius = std::max(reach_radius, radius[order[k]]);
    const auto ranges = grid.neighbourhood(cell, static_cast<int>(std::ceil(2.0 * reach_radius / grid.cell())));
    for (int k = grid.cell_begin(cell); k < grid.cell_begin(cell + 1); ++k) {
      const int i = order[k];
      for (const auto& [begin, end] : ranges)
        for (int q = begin; q < end; ++q) {
          const int j = order[q];
          const double d2 = (points[j] - points[i]).squaredNorm();
          if (interacts(i, j, d2)) emit(i, j, d2);
        }
    }
  };
  std::vector<int> start(m + 1, 0);
  parallel_for(grid.cell_count(), threads, [&](int cell) { scan_cell(cell, [&](int i, int, double) { ++start[i + 1]; }); });
  for (int i = 0; i < m; ++i) start[i + 1] += start[i];
  std::vector<int> neighbours(start[m]);
  std::vector<double> weight(m, 0.0);
  std::vector<int> fill(start.begin(), start.end() - 1);
  parallel_for(grid.cell_count(), threads, [&](int cell) {
    scan_cell(cell, [&](int i, int j, double d2) {
      neighbours[fill[i]++] = j;
      weight[i] += pair_weight(i, j, d2);
    });
  });

  // Greedy elimination of the most crowded candidate. Weights only decrease, so a lazy max-heap
  // works: an entry whose weight is out of date is pushed back with its current weight when it
  // reaches the top. Ties go to the lower index.
  using Entry = std::pair<double, int>;
  auto lower = [](const Entry& a, const Entry& b) { return a.first < b.first || (a.first == b.first && a.second > b.second); };
  std::vector<Entry> heap(m);
  for (int i = 0; i < m; ++i) heap[i] = {weight[i], i};
  std::make_heap(heap.begin(), heap.end(), lower);
  std::vector<char> alive(m, 1);
  for (int remaining = m; remaining > target;) {
    std::pop_heap(heap.begin(), heap.end(), lower);
    const auto [w, i] = heap.back();
    heap.pop_back();
    if (!alive[i]) continue;
    if (w != weight[i]) {
      heap.push_back({weight[i], i});
      std::push_heap(heap.begin(), heap.end(), lower);
      continue;
    }
    alive[i] = 0;
    --remaining;
    for (int k = start[i]; k < start[i + 1]; ++k) {
      const int j = neighbours[k];
      if (alive[j]) weight[j] -= pair_weight(i, j, (points[i] - points[j]).squaredNorm());
    }
  }
  kept.reserve(target);
  for (int i = 0; i < m; ++i)
    if (alive[i]) kept.push_back(i);
  return kept;
}

}  // namespace hairfit
