#include "scalp/sample_elimination.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

#include "core/huge_pages.h"
#include "core/parallel.h"
#include "core/point_grid.h"

namespace hairfit {

namespace {

// A candidate as the scan and the elimination read it: position and radius in one 32-byte
// record (two to a cache line), in the grid's order.
struct Candidate {
  double x, y, z, r;
};

// |b − a|², summed in the order Eigen's squaredNorm sums a Vec3, ((x² + y²) + z²), so that the
// weights are those the elimination has always used.
inline double squared_distance(const Candidate& a, const Candidate& b) {
  const double dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
  return (dx * dx + dy * dy) + dz * dz;
}

// Yuksel's weight of a pair at squared distance d2 whose smaller radius is r. The scan adds it to
// both points' sums, and the elimination subtracts it again, recomputed from the same inputs by
// the same expression (bit for bit the value added): cheaper than storing a weight per list entry
// (24 MB of fresh pages for the pores, each page fault costing more than the few recomputations).
struct PairWeight {
  double limit;  // r_min / r
  double operator()(double r, double d2) const {
    const double d = std::max(std::sqrt(d2), limit * r);
    const double x = 1.0 - d / (2.0 * r);
    const double x2 = x * x, x4 = x2 * x2;
    return x4 * x4;
  }
};

// Two lanes of doubles (GCC/Clang vector extension; SSE2 on x86-64, NEON on ARM): the distance
// tests run two candidates at a time. Each lane does exactly the scalar operations, so the
// squared distances and radii are bit for bit the scalar ones.
typedef double Lanes __attribute__((vector_size(16)));
typedef long long LaneMask __attribute__((vector_size(16)));

// Appends the partners of candidate k (p) among grid positions [begin, end) to `out`, adding
// their pair weights to `sum` in that order.
inline int* test_run(const Candidate* points, const PairWeight& pair_weight, int k, const Candidate& p, int begin,
                     int end, int* out, double& sum) {
  const Lanes px = {p.x, p.x}, py = {p.y, p.y}, pz = {p.z, p.z}, rp = {p.r, p.r};
  int q = begin;
  for (; q + 1 < end; q += 2) {
    const Candidate& a = points[q];
    const Candidate& b = points[q + 1];
    const Lanes dx = Lanes{a.x, b.x} - px, dy = Lanes{a.y, b.y} - py, dz = Lanes{a.z, b.z} - pz;
    const Lanes d2 = (dx * dx + dy * dy) + dz * dz;
    const Lanes rq = {a.r, b.r};
    const LaneMask smaller = rq < rp;  // std::min(r_p, r_q), lane by lane
    const Lanes r = reinterpret_cast<Lanes>((smaller & reinterpret_cast<LaneMask>(rq)) | (~smaller & reinterpret_cast<LaneMask>(rp)));
    const LaneMask hit = d2 < (4.0 * r) * r;
    if (hit[0] && q != k) {
      *out++ = q;
      sum += pair_weight(r[0], d2[0]);
    }
    if (hit[1] && q + 1 != k) {
      *out++ = q + 1;
      sum += pair_weight(r[1], d2[1]);
    }
  }
  if (q < end) {
    const double r = std::min(p.r, points[q].r);
    const double d2 = squared_distance(p, points[q]);
    if (d2 < 4.0 * r * r && q != k) {
      *out++ = q;
      sum += pair_weight(r, d2);
    }
  }
  return out;
}

// Partner lists of consecutive candidates, one after the other, each as its length followed by
// its partners, written through a raw pointer (std::vector::push_back reloads its end pointer
// around every store of the scan's inner loop). A block's lists go to its own region of a shared
// buffer, sized for the usual number of partners; a block that needs more moves to memory of its
// own. Space reserved but never written costs nothing: its pages are never touched.
class PartnerLists {
 public:
  PartnerLists() = default;
  PartnerLists(int* region, std::size_t capacity) : data_(region), capacity_(capacity) {}
  const int* data() const { return data_; }
  // Room for n more entries; write them, then commit the end of what was written.
  int* room(std::size_t n) {
    if (size_ + n > capacity_) grow(size_ + n);
    return data_ + size_;
  }
  void commit(const int* end) { size_ = static_cast<std::size_t>(end - data_); }
  std::size_t size() const { return size_; }
  int& operator[](std::size_t i) { return data_[i]; }

 private:
  void grow(std::size_t needed) {
    capacity_ = std::max(needed, 2 * capacity_);
    std::unique_ptr<int[]> bigger(new int[capacity_]);
    std::copy(data_, data_ + size_, bigger.get());
    own_ = std::move(bigger);
    data_ = own_.get();
  }
  int* data_ = nullptr;
  std::size_t size_ = 0, capacity_ = 0;
  std::unique_ptr<int[]> own_;  // after outgrowing the region
};

// The partner list (grid positions, ascending) of every candidate of cells [first, last), and
// its weight sum into weight[k].
void scan_cells(const PointGrid& grid, const Candidate* points, const PairWeight& pair_weight, int first, int last,
                double* weight, PartnerLists& lists) {
  std::vector<PointGrid::CellRange> ranges;
  struct Near {  // a neighbouring cell: its points, and its offset from the cell (+ reach) per axis
    int begin, end;
    int offset[3];
  };
  std::vector<Near> near;
  std::vector<double> gap2;  // per axis and offset: the squared gap from the point to that slab of cells
  for (int cell = first; cell < last; ++cell) {
    double reach_radius = 0.0;
    for (int k = grid.cell_begin(cell); k < grid.cell_begin(cell + 1); ++k) reach_radius = std::max(reach_radius, points[k].r);
    const int reach = static_cast<int>(std::ceil(2.0 * reach_radius / grid.cell()));
    const int span = 2 * reach + 1;
    grid.neighbourhood(cell, reach, ranges);
    const Vec3i at = grid.cell_coords(cell);
    near.clear();
    for (const PointGrid::CellRange& r : ranges) {
      const Vec3i d = r.coords - at + Vec3i::Constant(reach);
      near.push_back({r.begin, r.end, {d.x(), span + d.y(), 2 * span + d.z()}});
    }
    gap2.resize(3 * span);
    for (int k = grid.cell_begin(cell); k < grid.cell_begin(cell + 1); ++k) {
      const Candidate p = points[k];
      // A neighbouring cell whose box lies farther than 2·r_k from p holds no partner (a pair
      // interacts within 2·min(r_k, r_j)); skipping it saves most distance tests. The gap to a
      // cell is the sum over the axes of the gap to its slab, tabulated per offset from p's
      // cell (p at fraction f of its own cell). The margin keeps the test conservative against
      // round-off in the cell coordinates.
      const Vec3 f = grid.in_cells(Vec3(p.x, p.y, p.z)) - at.cast<double>();
      for (int a = 0; a < 3; ++a)
        for (int d = -reach; d <= reach; ++d) {
          const double gap = d > 0 ? d - f[a] : d < 0 ? f[a] - (d + 1) : 0.0;
          gap2[a * span + d + reach] = gap > 0 ? gap * gap : 0.0;
        }
      const double reach_cells = 2.0 * p.r / grid.cell() * (1.0 + 1e-9) + 1e-9;
      const double reach2 = reach_cells * reach_cells;
      const std::size_t length_at = lists.size();
      lists.commit(lists.room(1) + 1);  // the list's length, filled in below
      double sum = 0.0;
      // Cells that pass, merged into runs where they lie next to each other in the grid's order
      // (x-neighbours), so the tests run over longer stretches.
      int run_begin = 0, run_end = 0;
      for (const Near& c : near) {
        if (gap2[c.offset[0]] + gap2[c.offset[1]] + gap2[c.offset[2]] > reach2) continue;
        if (c.begin != run_end) {
          if (run_end > run_begin)
            lists.commit(test_run(points, pair_weight, k, p, run_begin, run_end, lists.room(run_end - run_begin), sum));
          run_begin = c.begin;
        }
        run_end = c.end;
      }
      if (run_end > run_begin)
        lists.commit(test_run(points, pair_weight, k, p, run_begin, run_end, lists.room(run_end - run_begin), sum));
      weight[k] = sum;
      lists[length_at] = static_cast<int>(lists.size() - length_at - 1);
    }
  }
}

// The greedy order of elimination: the alive candidate with the largest key (weight, −index)
// first. Weights only decrease, so the largest key never grows during a run; the queue exploits
// this with buckets of weight ranges, highest first, and a small binary heap over the members of
// the current bucket. A member whose weight fell is refreshed lazily: when it reaches the heap's
// top it is re-sifted with its current weight, or moved to the lower bucket its weight now falls
// in. Every entry's weight is at least its candidate's current weight, and a lower bucket holds
// only smaller weights, so a top whose weight is current is the largest key of all. The order
// (weight, −index) is total, so this pops exactly the sequence a single heap over all candidates
// pops, while the heap stays small enough to live in the cache. The pops are the serial part of
// sample elimination and jump around memory, so the queue is laid out for few cache misses:
// bucket members in 64-byte chunks, and indices (for ties only) looked up only on ties.
class CrowdingQueue {
 public:
  // weight[s] and index[s] per slot s < m; `weight` is read again by pop() as it changes.
  CrowdingQueue(const double* weight, const int* index, int m) : weight_(weight), index_(index) {
    // About 16 candidates per bucket on average: a bucket's heap stays a few cache lines.
    buckets_ = std::max(1, m / 16);
    const double top = m ? *std::max_element(weight, weight + m) : 0.0;
    scale_ = top > 0 ? buckets_ / top : 0.0;
    head_.assign(buckets_, -1);
    pool_.reserve(static_cast<std::size_t>(m / (kChunkSlots / 2) + buckets_ / 8 + 1));
    for (int s = 0; s < m; ++s) file(s, bucket(weight[s]));
    current_ = buckets_ - 1;
  }

  // The slot pop() would return if no weight changed before it (−1 if not known yet): its data
  // can be fetched while the current elimination is done.
  int peek() const { return heap_.empty() ? -1 : heap_.front().slot; }

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
  static constexpr int kChunkSlots = 14;
  struct Chunk {  // one cache line of a bucket's member list
    int count;
    int next;  // the bucket's next chunk, −1 for none
    int slot[kChunkSlots];
  };
  struct Entry {
    double weight;  // the slot's weight when last looked at (≥ its current weight)
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
    int c = head_[b];
    if (c < 0 || pool_[c].count == kChunkSlots) {
      const int fresh = new_chunk();
      pool_[fresh].count = 0;
      pool_[fresh].next = c;
      head_[b] = c = fresh;
    }
    Chunk& chunk = pool_[c];
    chunk.slot[chunk.count++] = slot;
  }
  int new_chunk() {
    if (!free_.empty()) {
      const int c = free_.back();
      free_.pop_back();
      return c;
    }
    pool_.emplace_back();
    return static_cast<int>(pool_.size()) - 1;
  }
  // The highest non-empty bucket's members into the heap, with their current weights; members
  // whose weight has fallen below the bucket move down instead.
  void load_next_bucket() {
    while (head_[current_] < 0) --current_;
    int c = head_[current_];
    head_[current_] = -1;
    while (c >= 0) {
      const Chunk chunk = pool_[c];  // a copy: filing below may reuse or move the pool's chunks
      free_.push_back(c);
      for (int i = 0; i < chunk.count; ++i) __builtin_prefetch(&weight_[chunk.slot[i]]);
      for (int i = 0; i < chunk.count; ++i) {
        const int s = chunk.slot[i];
        const double w = weight_[s];
        const int b = bucket(w);
        if (b < current_) file(s, b);
        else heap_.push_back({w, s});
      }
      c = chunk.next;
    }
    for (std::size_t k = heap_.size() / 2; k-- > 0;) sift_down(k);
  }

  bool before(const Entry& a, const Entry& b) const {
    return a.weight > b.weight || (a.weight == b.weight && index_[a.slot] < index_[b.slot]);
  }
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

  const double* weight_;
  const int* index_;
  int buckets_ = 1;
  double scale_ = 0.0;
  std::vector<int> head_;  // first chunk of each bucket's member list, −1 for none
  std::vector<Chunk> pool_;
  std::vector<int> free_;  // chunks of loaded buckets, for reuse
  int current_ = 0;        // the bucket the heap holds; every higher bucket is empty
  std::vector<Entry> heap_;
};

}  // namespace

std::vector<int> eliminate_samples(const Vec3* points, const double* radius, int m, int target, int threads) {
  std::vector<int> kept;
  if (target >= m) {
    kept.resize(m);
    std::iota(kept.begin(), kept.end(), 0);
    return kept;
  }
  if (target <= 0) return kept;

  // From here on candidates are named by their position in the grid's order (cell key, then
  // index): candidates near in space are near in memory, for the scan and the elimination alike.
  const double smallest = *std::min_element(radius, radius + m);
  const PointGrid grid(points, m, 3.0 * smallest, /*keep_points=*/false);
  const HugeVector<int>& order = grid.order();
  // Candidate-sized arrays live in huge pages (core/huge_pages.h): fresh memory is expensive.
  HugeVector<Candidate> candidates(m);
  parallel_for(m, threads, [&](int k) {
    const Vec3& p = points[order[k]];
    candidates[k] = {p.x(), p.y(), p.z(), radius[order[k]]};
  });
  const PairWeight pair_weight{0.65 * (1.0 - std::pow(static_cast<double>(target) / m, 1.5))};

  // Partner lists and weight sums, in one pass over blocks of cells: each neighbouring cell is
  // looked up once per cell, and candidates are read in the grid's order, so the scan walks
  // memory contiguously. A candidate's list is in the grid's fixed order, so its weight sum does
  // not depend on the thread count. Each block of cells keeps its lists (no copy into one array:
  // fresh pages are expensive); list[k] points to k's length and partners.
  constexpr int kCellsPerBlock = 64;
  // Room per candidate for its length and the usual number of partners (about 11 at the
  // default oversampling), so that a block rarely outgrows its region.
  constexpr std::size_t kReservedPerPoint = 17;
  const HugeBuffer<int> storage(kReservedPerPoint * m);
  const int cells = grid.cell_count();
  std::vector<PartnerLists> block_lists((cells + kCellsPerBlock - 1) / kCellsPerBlock);
  HugeVector<double> weight(m);
  parallel_for(static_cast<int>(block_lists.size()), threads, [&](int b) {
    const int first = b * kCellsPerBlock, last = std::min(cells, first + kCellsPerBlock);
    const std::size_t begin = grid.cell_begin(first), end = grid.cell_begin(last);
    block_lists[b] = PartnerLists(storage.data() + kReservedPerPoint * begin, kReservedPerPoint * (end - begin));
    scan_cells(grid, candidates.data(), pair_weight, first, last, weight.data(), block_lists[b]);
  });
  HugeVector<const int*> list(m);
  parallel_for(static_cast<int>(block_lists.size()), threads, [&](int b) {
    const int* at = block_lists[b].data();
    const int end = grid.cell_begin(std::min(cells, (b + 1) * kCellsPerBlock));
    for (int k = grid.cell_begin(b * kCellsPerBlock); k < end; ++k) {
      list[k] = at;
      at += 1 + *at;
    }
  });

  // Greedy elimination of the most crowded candidate (the queue's order is that of one global
  // heap, ties to the lower index), each elimination lowering its alive neighbours' weights. An
  // eliminated candidate's weight becomes −∞ (a weight is otherwise finite): one array read tells
  // a neighbour's state and weight. The neighbours' records are prefetched together, so their
  // cache misses overlap instead of following one another.
  constexpr double kEliminated = -std::numeric_limits<double>::infinity();
  CrowdingQueue queue(weight.data(), order.data(), m);
  for (int remaining = m; remaining > target; --remaining) {
    const int k = queue.pop();
    weight[k] = kEliminated;
    // The likely next candidate's records, fetched while this one is done: its list pointer
    // now, the list it points to after the updates below (by then the pointer has arrived).
    const int next = queue.peek();
    if (next >= 0) {
      __builtin_prefetch(&list[next]);
      __builtin_prefetch(&candidates[next]);
      __builtin_prefetch(&weight[next]);
    }
    const Candidate p = candidates[k];
    const int count = list[k][0];
    const int* partners = list[k] + 1;
    for (int e = 0; e < count; ++e) {
      __builtin_prefetch(&weight[partners[e]]);
      __builtin_prefetch(&candidates[partners[e]]);
    }
    for (int e = 0; e < count; ++e) {
      const int j = partners[e];
      if (weight[j] == kEliminated) continue;
      // The weight the scan added for this pair: same operands, same expression, same bits.
      const double r = std::min(p.r, candidates[j].r);
      weight[j] -= pair_weight(r, squared_distance(p, candidates[j]));
    }
    if (next >= 0) __builtin_prefetch(list[next]);
  }
  std::vector<char> kept_index(m, 0);
  for (int k = 0; k < m; ++k) kept_index[order[k]] = weight[k] != kEliminated;
  kept.reserve(target);
  for (int i = 0; i < m; ++i)
    if (kept_index[i]) kept.push_back(i);
  return kept;
}

}  // namespace hairfit
