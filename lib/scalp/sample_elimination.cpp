#include "scalp/sample_elimination.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

#include "core/parallel.h"
#include "scalp/point_grid.h"

namespace hairfit {

namespace {

// Yuksel's weight of a pair at squared distance d2 whose smaller radius is r. The scan adds it to
// both points' sums, and the elimination subtracts it again, recomputed from the same inputs by
// the same expression (bit for bit the value added): cheaper than storing a weight per list entry
// (24 MB of fresh pages for the pores, each page fault costing more than the few recomputations).
// |b − a|², summed in the order Eigen's squaredNorm sums a Vec3, ((x² + y²) + z²), so that the
// weights are those the elimination has always used; written out because Eigen's packet code for
// three coordinates made this the scan's most expensive line.
inline double squared_distance(const Vec3& a, const Vec3& b) {
  const double dx = b.x() - a.x(), dy = b.y() - a.y(), dz = b.z() - a.z();
  return (dx * dx + dy * dy) + dz * dz;
}

struct PairWeight {
  double limit;  // r_min / r
  double operator()(double r, double d2) const {
    const double d = std::max(std::sqrt(d2), limit * r);
    const double x = 1.0 - d / (2.0 * r);
    const double x2 = x * x, x4 = x2 * x2;
    return x4 * x4;
  }
};

// The greedy order of elimination: the alive candidate with the largest key (weight, −index)
// first. Weights only decrease, so the largest key never grows during a run; the queue exploits
// this with buckets of weight ranges, highest first, and a small binary heap over the members of
// the current bucket. A member whose weight fell is refreshed lazily: when it reaches the heap's
// top it is re-sifted with its current weight, or moved to the lower bucket its weight now falls
// in. Every entry's weight is at least its candidate's current weight, and a lower bucket holds
// only smaller weights, so a top whose weight is current is the largest key of all. The order
// (weight, −index) is total, so this pops exactly the sequence a single heap over all candidates
// pops, while the heap stays small enough to live in the cache.
class CrowdingQueue {
 public:
  // weight[s] and index[s] per slot s; `weight` is read again by pop() as it changes.
  CrowdingQueue(const std::vector<double>& weight, const std::vector<int>& index)
      : weight_(weight), index_(index), next_(weight.size()) {
    const int m = static_cast<int>(weight.size());
    // About 16 candidates per bucket on average: loading a bucket is one random access per
    // member, its heap a few cache lines.
    buckets_ = std::max(1, m / 16);
    const double top = m ? *std::max_element(weight.begin(), weight.end()) : 0.0;
    scale_ = top > 0 ? buckets_ / top : 0.0;
    head_.assign(buckets_, -1);
    for (int s = m - 1; s >= 0; --s) file(s, bucket(weight[s]));
    current_ = buckets_ - 1;
  }

  // Removes and returns the slot with the largest current key; at least one must remain.
  int pop() {
    for (;;) {
      if (heap_.empty()) {
        load_next_bucket();
        continue;
      }
      const Entry top = heap_.front();
      const double w = weight_[top.slot];
      if (w == top.weight) {
        remove_top();
        return top.slot;
      }
      const int b = bucket(w);
      if (b < current_) {
        remove_top();
        file(top.slot, b);
      } else {
        heap_.front().weight = w;
        sift_down(0);
      }
    }
  }

 private:
  struct Entry {
    double weight;  // the slot's weight when last looked at (≥ its current weight)
    int index;      // the candidate's, for ties
    int slot;
  };

  // Monotone in w (a product with a positive scale, truncated, clamped): a lower bucket never
  // holds a larger weight. Round-off can leave a weight slightly below 0: bucket 0.
  int bucket(double w) const {
    if (!(w > 0)) return 0;
    const double x = w * scale_;
    return x >= buckets_ - 1 ? buckets_ - 1 : static_cast<int>(x);
  }
  void file(int slot, int b) {
    next_[slot] = head_[b];
    head_[b] = slot;
  }
  // The highest non-empty bucket's members into the heap, with their current weights; members
  // whose weight has fallen below the bucket move down instead.
  void load_next_bucket() {
    while (head_[current_] < 0) --current_;
    int s = head_[current_];
    head_[current_] = -1;
    while (s >= 0) {
      const int next = next_[s];
      const double w = weight_[s];
      const int b = bucket(w);
      if (b < current_) file(s, b);
      else heap_.push_back({w, index_[s], s});
      s = next;
    }
    for (std::size_t k = heap_.size() / 2; k-- > 0;) sift_down(k);
  }

  static bool before(const Entry& a, const Entry& b) { return a.weight > b.weight || (a.weight == b.weight && a.index < b.index); }
  void remove_top() {
    heap_.front() = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) sift_down(0);
  }
  void sift_down(std::size_t k) {
    const std::size_t n = heap_.size();
    const Entry moving = heap_[k];
    for (;;) {
      std::size_t child = 2 * k + 1;
      if (child >= n) break;
      if (child + 1 < n && before(heap_[child + 1], heap_[child])) ++child;
      if (!before(heap_[child], moving)) break;
      heap_[k] = heap_[child];
      k = child;
    }
    heap_[k] = moving;
  }

  const std::vector<double>& weight_;
  const std::vector<int>& index_;
  int buckets_ = 1;
  double scale_ = 0.0;
  std::vector<int> head_;  // first slot of each bucket's list, −1 for none
  std::vector<int> next_;  // next slot in the same bucket's list
  int current_ = 0;        // the bucket the heap holds; every higher bucket is empty
  std::vector<Entry> heap_;
};

// Partner lists of consecutive points, one after the other, in an array that is written through
// a raw pointer: std::vector::push_back reloads its end pointer around every store of the scan's
// inner loop. Memory reserved but never written costs nothing (the pages are never touched).
class PartnerLists {
 public:
  PartnerLists() = default;
  explicit PartnerLists(std::size_t capacity) : data_(new int[capacity]), capacity_(capacity) {}
  const int* data() const { return data_.get(); }
  // Room for n more entries; write them, then commit the end of what was written.
  int* room(std::size_t n) {
    if (size_ + n > capacity_) grow(size_ + n);
    return data_.get() + size_;
  }
  void commit(const int* end) { size_ = static_cast<std::size_t>(end - data_.get()); }
  std::size_t size() const { return size_; }

 private:
  void grow(std::size_t needed) {
    capacity_ = std::max(needed, 2 * capacity_);
    std::unique_ptr<int[]> bigger(new int[capacity_]);
    std::copy(data_.get(), data_.get() + size_, bigger.get());
    data_ = std::move(bigger);
  }
  std::unique_ptr<int[]> data_;
  std::size_t size_ = 0, capacity_ = 0;
};

// The partners (grid positions, ascending) of every point of cells [first, last), their weight
// sums into weight[k] and their counts into list_size[k]; `radius` is in grid order.
PartnerLists scan_cells(const PointGrid& grid, const double* radius, const PairWeight& pair_weight, int first,
                        int last, double* weight, int* list_size) {
  const Vec3* points = grid.sorted().data();
  // Room for the lists without regrowth in most cases: a point has about 11 partners at the
  // default oversampling.
  constexpr int kReservedPerPoint = 16;
  PartnerLists lists(static_cast<std::size_t>(kReservedPerPoint) * (grid.cell_begin(last) - grid.cell_begin(first)));
  std::vector<PointGrid::CellRange> ranges;
  struct Near {  // a neighbouring cell: its points, and its lower corner in cell units
    int begin, end;
    double corner[3];
  };
  std::vector<Near> near;
  for (int cell = first; cell < last; ++cell) {
    double reach_radius = 0.0;
    for (int k = grid.cell_begin(cell); k < grid.cell_begin(cell + 1); ++k) reach_radius = std::max(reach_radius, radius[k]);
    grid.neighbourhood(cell, static_cast<int>(std::ceil(2.0 * reach_radius / grid.cell())), ranges);
    near.clear();
    for (const PointGrid::CellRange& r : ranges)
      near.push_back({r.begin, r.end, {static_cast<double>(r.coords.x()), static_cast<double>(r.coords.y()), static_cast<double>(r.coords.z())}});
    for (int k = grid.cell_begin(cell); k < grid.cell_begin(cell + 1); ++k) {
      const Vec3 p = points[k];
      const double r_k = radius[k];
      // A neighbouring cell whose box lies farther than 2·r_k from p holds no partner (a pair
      // interacts within 2·min(r_k, r_j)); skipping it saves most distance tests. The margin
      // keeps the test conservative against round-off in the cell coordinates.
      const Vec3 u = grid.in_cells(p);
      const double reach_cells = 2.0 * r_k / grid.cell() * (1.0 + 1e-9) + 1e-9;
      const double reach2 = reach_cells * reach_cells;
      const std::size_t before = lists.size();
      double sum = 0.0;
      for (const Near& c : near) {
        const double gx = std::max(0.0, std::max(c.corner[0] - u.x(), u.x() - (c.corner[0] + 1.0)));
        const double gy = std::max(0.0, std::max(c.corner[1] - u.y(), u.y() - (c.corner[1] + 1.0)));
        const double gz = std::max(0.0, std::max(c.corner[2] - u.z(), u.z() - (c.corner[2] + 1.0)));
        if (gx * gx + gy * gy + gz * gz > reach2) continue;
        int* out = lists.room(c.end - c.begin);
        for (int q = c.begin; q < c.end; ++q) {
          const double r = std::min(r_k, radius[q]);
          const double d2 = squared_distance(p, points[q]);
          if (!(d2 < 4.0 * r * r) || q == k) continue;
          *out++ = q;
          sum += pair_weight(r, d2);
        }
        lists.commit(out);
      }
      weight[k] = sum;
      list_size[k] = static_cast<int>(lists.size() - before);
    }
  }
  return lists;
}

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
  const PairWeight pair_weight{0.65 * (1.0 - std::pow(static_cast<double>(target) / m, 1.5))};

  // From here on candidates are named by their position in the grid's order (cell key, then
  // index): candidates near in space are near in memory, for the scan and the elimination alike.
  //
  // Neighbour lists and weight sums, in one pass over blocks of cells: each neighbouring cell is
  // looked up once per cell, and points and radii are read in the grid's order, so the scan walks
  // memory contiguously. A point's list is in the grid's fixed order, so its weight sum does not
  // depend on the thread count. Each block of cells keeps its lists (no copy into one array:
  // fresh pages are expensive); list_begin points into them.
  const std::vector<int>& order = grid.order();
  const std::vector<Vec3>& sorted = grid.sorted();
  std::vector<double> sorted_radius(m);
  for (int k = 0; k < m; ++k) sorted_radius[k] = radius[order[k]];
  constexpr int kCellsPerBlock = 64;
  const int cells = grid.cell_count();
  std::vector<PartnerLists> block_lists((cells + kCellsPerBlock - 1) / kCellsPerBlock);
  std::vector<int> list_size(m);
  std::vector<double> weight(m);
  parallel_for(static_cast<int>(block_lists.size()), threads, [&](int b) {
    const int first = b * kCellsPerBlock, last = std::min(cells, first + kCellsPerBlock);
    block_lists[b] = scan_cells(grid, sorted_radius.data(), pair_weight, first, last, weight.data(), list_size.data());
  });
  std::vector<const int*> list_begin(m);
  parallel_for(static_cast<int>(block_lists.size()), threads, [&](int b) {
    const int* at = block_lists[b].data();
    const int end = grid.cell_begin(std::min(cells, (b + 1) * kCellsPerBlock));
    for (int k = grid.cell_begin(b * kCellsPerBlock); k < end; ++k) {
      list_begin[k] = at;
      at += list_size[k];
    }
  });

  // Greedy elimination of the most crowded candidate (the queue's order is that of one global
  // heap, ties to the lower index), each elimination lowering its alive neighbours' weights.
  CrowdingQueue queue(weight, order);
  std::vector<char> alive(m, 1);
  for (int remaining = m; remaining > target; --remaining) {
    const int k = queue.pop();
    alive[k] = 0;
    const Vec3& p = sorted[k];
    const double r_k = sorted_radius[k];
    const int* list = list_begin[k];
    for (int e = 0; e < list_size[k]; ++e) {
      const int j = list[e];
      if (!alive[j]) continue;
      // As the scan computed it for the pair (j, k): same operands, same order.
      const double r = std::min(r_k, sorted_radius[j]);
      weight[j] -= pair_weight(r, squared_distance(p, sorted[j]));
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
