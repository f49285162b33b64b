#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <queue>
#include <tuple>

#include "core/random.h"
#include "core/point_grid.h"
#include "scalp/sample_elimination.h"

using namespace hairfit;

namespace {

// Weighted sample elimination the plain way, to check the fast one against: all pairs tested,
// one global lazy heap. Each point's weight is summed over its neighbours in the grid order that
// eliminate_samples documents (cell key, then index; PointGrid with cells of 3·r_min), so the
// floating-point sums, and hence the whole elimination, must agree bit for bit.
std::vector<int> reference_elimination(const std::vector<Vec3>& points, const std::vector<double>& radius, int target) {
  const int m = static_cast<int>(points.size());
  const double smallest = *std::min_element(radius.begin(), radius.end());
  const PointGrid grid(points, 3.0 * smallest);
  std::vector<int> position(m);
  for (int k = 0; k < m; ++k) position[grid.order()[k]] = k;
  const double limit = 0.65 * (1.0 - std::pow(static_cast<double>(target) / m, 1.5));
  auto pair_weight = [&](int i, int j) {
    const double r = std::min(radius[i], radius[j]);
    const double d2 = (points[j] - points[i]).squaredNorm();
    if (!(d2 < 4.0 * r * r)) return -1.0;  // not a pair
    const double d = std::max(std::sqrt(d2), limit * r);
    const double x = 1.0 - d / (2.0 * r);
    const double x2 = x * x, x4 = x2 * x2;  // x⁸ as the library forms it, not std::pow's rounding
    return x4 * x4;
  };
  std::vector<std::vector<std::pair<int, double>>> neighbours(m);  // (neighbour, weight)
  std::vector<double> weight(m, 0.0);
  for (int i = 0; i < m; ++i) {
    std::vector<int> partners;
    for (int j = 0; j < m; ++j)
      if (j != i && pair_weight(i, j) >= 0) partners.push_back(j);
    std::sort(partners.begin(), partners.end(), [&](int a, int b) { return position[a] < position[b]; });
    for (int j : partners) {
      neighbours[i].push_back({j, pair_weight(i, j)});
      weight[i] += neighbours[i].back().second;
    }
  }
  // Largest weight first, ties to the lower index; stale entries are pushed again.
  std::priority_queue<std::tuple<double, int>> heap;
  for (int i = 0; i < m; ++i) heap.push({weight[i], -i});
  std::vector<char> alive(m, 1);
  for (int remaining = m; remaining > target;) {
    const auto [w, negative_index] = heap.top();
    heap.pop();
    const int i = -negative_index;
    if (w != weight[i]) {
      heap.push({weight[i], -i});
      continue;
    }
    alive[i] = 0;
    --remaining;
    for (const auto& [j, wj] : neighbours[i])
      if (alive[j]) weight[j] -= wj;
  }
  std::vector<int> kept;
  for (int i = 0; i < m; ++i)
    if (alive[i]) kept.push_back(i);
  return kept;
}

// Points on a unit sphere's cap with radii for a density that varies fourfold across it.
void sphere_cap(int m, std::uint64_t seed, std::vector<Vec3>& points, std::vector<double>& radius) {
  Random rng(seed, RandomStage::test, 0);
  points.clear();
  radius.clear();
  const double r_dense = 0.03;
  while (static_cast<int>(points.size()) < m) {
    const Vec3 p(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (p.norm() > 1 || p.norm() < 1e-3 || p.z() < 0.2) continue;
    points.push_back(p.normalized());
    radius.push_back(r_dense * (1.0 + 0.5 * (1.0 + points.back().x())));  // r_dense … 2·r_dense
  }
}

}  // namespace

TEST_CASE("sample elimination: equals a brute-force elimination with one global heap, for any thread count") {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    std::vector<Vec3> points;
    std::vector<double> radius;
    sphere_cap(2500, seed, points, radius);
    for (const int target : {1, 400, 833, 2000, 2499}) {
      const std::vector<int> expected = reference_elimination(points, radius, target);
      REQUIRE(static_cast<int>(expected.size()) == target);
      for (const int threads : {1, 2, 3}) {
        CAPTURE(seed);
        CAPTURE(target);
        CAPTURE(threads);
        CHECK(eliminate_samples(points, radius, target, threads) == expected);
      }
    }
  }
}

TEST_CASE("sample elimination: ties (a lattice, coincident points) go to the lower index, as in one global heap") {
  // A square lattice: interior points have equal weights, so the order rests on the tie rule.
  std::vector<Vec3> points;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 30; ++x) points.emplace_back(0.1 * x, 0.1 * y, 0.0);
  points.push_back(points[437]);  // a coincident pair
  points.push_back(points[437]);
  const std::vector<double> radius(points.size(), 0.08);
  for (const int target : {1, 100, 300, 450, 901}) {
    CAPTURE(target);
    const std::vector<int> expected = reference_elimination(points, radius, target);
    CHECK(eliminate_samples(points, radius, target, 1) == expected);
    CHECK(eliminate_samples(points, radius, target, 2) == expected);
  }
}

TEST_CASE("sample elimination: isolated points (no partners, weight 0) and trivial targets") {
  std::vector<Vec3> points{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0.01, 0, 0}, {20, 20, 20}};
  const std::vector<double> radius(points.size(), 0.1);
  for (int target = 0; target <= 6; ++target) {
    CAPTURE(target);
    const std::vector<int> kept = eliminate_samples(points, radius, target, 2);
    if (target >= 5) {
      CHECK(kept == std::vector<int>{0, 1, 2, 3, 4});
    } else if (target == 0) {
      CHECK(kept.empty());
    } else {
      CHECK(kept == reference_elimination(points, radius, target));
    }
  }
  // The crowded pair goes first: the lower index of two equal weights.
  CHECK(eliminate_samples(points, radius, 4, 1) == std::vector<int>{1, 2, 3, 4});
}
