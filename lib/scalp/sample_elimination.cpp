#include "scalp/sample_elimination.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/parallel.h"
#include "scalp/point_grid.h"

namespace hairfit {

namespace {

// Max-heap of candidate indices keyed by weight, with positions for in-place updates. Ties go to
// the lower index, so the order of elimination is fully determined by the weights.
class WeightHeap {
 public:
  explicit WeightHeap(const std::vector<double>& weight) : weight_(weight), heap_(weight.size()), slot_(weight.size()) {
    std::iota(heap_.begin(), heap_.end(), 0);
    for (std::size_t k = 0; k < heap_.size(); ++k) slot_[k] = static_cast<int>(k);
    for (int k = static_cast<int>(heap_.size()) / 2 - 1; k >= 0; --k) sift_down(k);
  }
  int top() const { return heap_.front(); }
  void pop() {
    move(0, heap_.back());
    heap_.pop_back();
    if (!heap_.empty()) sift_down(0);
  }
  void decreased(int item) { sift_down(slot_[item]); }

 private:
  bool above(int a, int b) const { return weight_[a] > weight_[b] || (weight_[a] == weight_[b] && a < b); }
  void move(int k, int item) {
    heap_[k] = item;
    slot_[item] = k;
  }
  void sift_down(int k) {
    const int n = static_cast<int>(heap_.size());
    const int item = heap_[k];
    for (;;) {
      int child = 2 * k + 1;
      if (child >= n) break;
      if (child + 1 < n && above(heap_[child + 1], heap_[child])) ++child;
      if (!above(heap_[child], item)) break;
      move(k, heap_[child]);
      k = child;
    }
    move(k, item);
  }

  const std::vector<double>& weight_;
  std::vector<int> heap_, slot_;
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
  const PointGrid grid(points, 2.0 * smallest);
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

  // Neighbour lists (CSR), each in the grid's fixed visiting order.
  std::vector<int> start(m + 1, 0);
  parallel_for(m, threads, [&](int i) {
    int count = 0;
    grid.for_each_within(points[i], 2.0 * radius[i], [&](int j, double d2) { count += interacts(i, j, d2); });
    start[i + 1] = count;
  });
  for (int i = 0; i < m; ++i) start[i + 1] += start[i];
  std::vector<int> neighbours(start[m]);
  std::vector<double> weight(m, 0.0);
  parallel_for(m, threads, [&](int i) {
    int k = start[i];
    double w = 0.0;
    grid.for_each_within(points[i], 2.0 * radius[i], [&](int j, double d2) {
      if (!interacts(i, j, d2)) return;
      neighbours[k++] = j;
      w += pair_weight(i, j, d2);
    });
    weight[i] = w;
  });

  WeightHeap heap(weight);
  std::vector<char> alive(m, 1);
  for (int remaining = m; remaining > target; --remaining) {
    const int i = heap.top();
    heap.pop();
    alive[i] = 0;
    for (int k = start[i]; k < start[i + 1]; ++k) {
      const int j = neighbours[k];
      if (!alive[j]) continue;
      weight[j] -= pair_weight(i, j, (points[i] - points[j]).squaredNorm());
      heap.decreased(j);
    }
  }
  kept.reserve(target);
  for (int i = 0; i < m; ++i)
    if (alive[i]) kept.push_back(i);
  return kept;
}

}  // namespace hairfit
