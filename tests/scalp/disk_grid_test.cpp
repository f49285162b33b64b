#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "core/random.h"
#include "scalp/disk_grid.h"

using namespace hairfit;

namespace {

int brute_nearest(const std::vector<Vec2>& points, const Vec2& p) {
  int best = -1;
  double best_d2 = INFINITY;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const double dx = points[i].x() - p.x(), dy = points[i].y() - p.y();
    const double d2 = dx * dx + dy * dy;
    if (d2 < best_d2) best = i, best_d2 = d2;  // the first of equals: the lowest index
  }
  return best;
}

}  // namespace

TEST_CASE("disk grid: nearest and within-radius queries equal brute force, ties to the lower index") {
  Random rng(3, RandomStage::test, 0);
  std::vector<Vec2> points;
  while (points.size() < 2000) {
    const Vec2 p(rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (p.norm() <= 1) points.push_back(p);
  }
  // Exact ties: repeated points and a lattice row at equal distances from the query below.
  points.push_back(points[17]);
  const int row = static_cast<int>(points.size());
  for (int k = 0; k < 5; ++k) points.emplace_back(0.25 + 0.125 * k, -1.25);  // dyadic: distances exact
  for (const double cell : {0.01, 0.05, 0.3, 5.0}) {
    const DiskGrid grid(points, cell);
    for (int q = 0; q < 400; ++q) {
      // Queries inside and well outside the points' box.
      const Vec2 p(rng.uniform(-1.6, 1.6), rng.uniform(-1.6, 1.6));
      CHECK(grid.nearest(p) == brute_nearest(points, p));
      const double radius = rng.uniform(0.0, 0.4);
      std::vector<int> found;
      grid.for_each_within(p, radius, [&](int i) { found.push_back(i); });
      std::sort(found.begin(), found.end());
      std::vector<int> expected;
      for (int i = 0; i < static_cast<int>(points.size()); ++i) {
        const double dx = points[i].x() - p.x(), dy = points[i].y() - p.y();
        if (dx * dx + dy * dy <= radius * radius) expected.push_back(i);
      }
      CHECK(found == expected);
    }
    CHECK(grid.nearest(points[17]) == 17);              // a point and its copy: the lower index
    CHECK(grid.nearest(Vec2(0.3125, -1.25)) == row);  // halfway between two row points: the first
  }
  CHECK(DiskGrid({}, 0.1).nearest(Vec2(0, 0)) == -1);
}
