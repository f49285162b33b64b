#include "scalp/sample_elimination.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

#include "core/parallel.h"
#include "scalp/point_grid.h"

namespace hairfit {

namespace {

// A binary max-heap of candidates under the order: larger weight first, then lower index; the
// keys of the entries only ever decrease, so a changed top sifts down. Candidates are named by
// their grid position (`slot`); the order breaks ties by their index.
class ElimHeap {
 public:
  ElimHeap(const std::vector<double>& weight, const std::vector<int>& index) : entries_(weight.size()) {
    for (std::size_t k = 0; k < weight.size(); ++k) entries_[k] = {weight[k], index[k], static_cast<int>(k)};
    for (std::size_t k = entries_.size() / 2; k-- > 0;) sift_down(k);
  }
  int top() const { return entries_.front().slot; }
  double top_weight() const { return entries_.front().weight; }
  void refresh_top(double weight) {
    entries_.front().weight = weight;
    sift_down(0);
  }
  void pop() {
    entries_.front() = entries_.back();
    entries_.pop_back();
    if (!entries_.empty()) sift_down(0);
  }

 private:
  struct Entry {
    double weight;
    int index;  // the candidate's, for ties
    int slot;   // its grid position
  };
  static bool before(const Entry& a, const Entry& b) { return a.weight > b.weight || (a.weight == b.weight && a.index < b.index); }
  void sift_down(std::size_t k) {
    const std::size_t n = entries_.size();
    const Entry moving = entries_[k];
    for (;;) {
      std::size_t child = 2 * k + 1;
      if (child >= n) break;
      if (child + 1 < n && before(entries_[child + 1], entries_[child])) ++child;
      if (!before(entries_[child], moving)) break;
      entries_[k] = entries_[child];
      k = child;
    }
    entries_[k] = moving;
  }
  std::vector<Entry> entries_;
};

}  // namespace

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
  // Weight of a pair at squared distance d2 whose smaller radius is r (symmetric in the pair, so
  // stored once per list entry and subtracted as is when a neighbour goes).
  auto pair_weight = [limit](double r, double d2) {
    const double d = std::max(std::sqrt(d2), limit * r);
    const double x = 1.0 - d / (2.0 * r);
    const double x2 = x * x, x4 = x2 * x2;
    return x4 * x4;
  };

  // From here on candidates are named by their position in the grid's order (cell key, then
  // index): candidates near in space are near in memory, for the scan and the elimination alike.
  //
  // Neighbour lists (CSR) with each pair's weight, built in one pass over blocks of cells: each
  // neighbouring cell is looked up once per cell, and points and radii are read in the grid's
  // order, so the scan walks memory contiguously. A point's list is in the grid's fixed order,
  // so the weight sums do not depend on the thread count. Blocks hold consecutive grid
  // positions, so their lists laid end to end are the CSR arrays.
  const std::vector<int>& order = grid.order();
  const std::vector<Vec3>& sorted = grid.sorted();
  std::vector<double> sorted_radius(m);
  for (int k = 0; k < m; ++k) sorted_radius[k] = radius[order[k]];
  struct Block {
    std::vector<int> count;       // neighbours of each point of the block's cells, in grid order
    std::vector<int> neighbour;   // their grid positions, point after point
    std::vector<double> weight;   // pair weights, alongside
  };
  constexpr int kCellsPerBlock = 64;
  // Room for the lists of a block without regrowth in most cases (a point has about 11 partners
  // at the default oversampling); memory reserved but never written costs nothing.
  constexpr int kReservedPerPoint = 16;
  const int cells = grid.cell_count();
  std::vector<Block> blocks((cells + kCellsPerBlock - 1) / kCellsPerBlock);
  std::vector<double> weight(m);
  parallel_for(static_cast<int>(blocks.size()), threads, [&](int b) {
    Block& block = blocks[b];
    const int first = b * kCellsPerBlock, last = std::min(cells, first + kCellsPerBlock);
    const int points_in_block = grid.cell_begin(last) - grid.cell_begin(first);
    block.count.reserve(points_in_block);
    block.neighbour.reserve(static_cast<std::size_t>(kReservedPerPoint) * points_in_block);
    block.weight.reserve(static_cast<std::size_t>(kReservedPerPoint) * points_in_block);
    for (int cell = first; cell < last; ++cell) {
      double reach_radius = 0.0;
      for (int k = grid.cell_begin(cell); k < grid.cell_begin(cell + 1); ++k) reach_radius = std::max(reach_radius, sorted_radius[k]);
      const auto ranges = grid.neighbourhood(cell, static_cast<int>(std::ceil(2.0 * reach_radius / grid.cell())));
      for (int k = grid.cell_begin(cell); k < grid.cell_begin(cell + 1); ++k) {
        const Vec3& p = sorted[k];
        const double r_i = sorted_radius[k];
        const std::size_t before = block.neighbour.size();
        // A neighbouring cell whose box lies farther than 2·r_i from p holds no partner (a pair
        // interacts within 2·min(r_i, r_j)); skipping it saves most distance tests. The margin
        // keeps the test conservative against round-off in the cell coordinates.
        const Vec3 u = grid.in_cells(p);
        const double reach_cells = 2.0 * r_i / grid.cell() * (1.0 + 1e-9) + 1e-9;
        double sum = 0.0;
        for (const PointGrid::CellRange& range : ranges) {
          double gap2 = 0.0;
          for (int a = 0; a < 3; ++a) {
            const double gap = std::max({0.0, range.coords[a] - u[a], u[a] - (range.coords[a] + 1)});
            gap2 += gap * gap;
          }
          if (gap2 > reach_cells * reach_cells) continue;
          for (int q = range.begin; q < range.end; ++q) {
            const double r = std::min(r_i, sorted_radius[q]);
            const double d2 = (sorted[q] - p).squaredNorm();
            if (q == k || !(d2 < 4.0 * r * r)) continue;
            const double w = pair_weight(r, d2);
            block.neighbour.push_back(q);
            block.weight.push_back(w);
            sum += w;
          }
        }
        weight[k] = sum;
        block.count.push_back(static_cast<int>(block.neighbour.size() - before));
      }
    }
  });
  std::vector<int> start(m + 1);
  start[0] = 0;
  {
    int k = 0;
    for (const Block& block : blocks)
      for (int c : block.count) {
        start[k + 1] = start[k] + c;
        ++k;
      }
  }
  // Filled block by block on all threads; not zeroed first (every entry is written).
  const std::unique_ptr<int[]> neighbours(new int[start[m]]);
  const std::unique_ptr<double[]> neighbour_weight(new double[start[m]]);
  parallel_for(static_cast<int>(blocks.size()), threads, [&](int b) {
    Block& block = blocks[b];
    const int at = start[grid.cell_begin(b * kCellsPerBlock)];
    std::copy(block.neighbour.begin(), block.neighbour.end(), neighbours.get() + at);
    std::copy(block.weight.begin(), block.weight.end(), neighbour_weight.get() + at);
    block = Block();  // free early
  });

  // Greedy elimination of the most crowded candidate. Weights only decrease, so a lazy max-heap
  // works: an entry whose weight is out of date is refreshed with its current weight when it
  // reaches the top. Ties go to the lower index. Entries are ordered by (weight, −index), a strict
  // total order, so the top is always the same entry whatever the heap's layout, and so is the
  // whole sequence of eliminations. A stale top is refreshed in place by one sift-down (not a pop
  // and a push): every alive candidate keeps exactly one entry.
  ElimHeap heap(weight, order);
  std::vector<char> alive(m, 1);
  for (int remaining = m; remaining > target;) {
    const int k = heap.top();
    if (heap.top_weight() != weight[k]) {
      heap.refresh_top(weight[k]);
      continue;
    }
    heap.pop();
    alive[k] = 0;
    --remaining;
    for (int e = start[k]; e < start[k + 1]; ++e) {
      const int j = neighbours[e];
      if (alive[j]) weight[j] -= neighbour_weight[e];
    }
  }
  std::vector<char> kept_index(m, 0);
  for (int k = 0; k < m; ++k) kept_index[order[k]] = alive[k];
  kept.reserve(target);
  for (int i = 0; i < m; ++i)
    if (kept_index[i]) kept.push_back(i);
  return kept;
}

}  // namespace hairfit
