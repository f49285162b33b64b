#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "core/random.h"
#include "core/weld.h"

using namespace hairfit;

namespace {

Vec3 in_box(Random& r, const Vec3& lo, const Vec3& hi) {
  return Vec3(r.uniform(lo.x(), hi.x()), r.uniform(lo.y(), hi.y()), r.uniform(lo.z(), hi.z()));
}

}  // namespace

TEST_CASE("weld_points: greedy in input order, into the lowest-indexed kept point in reach") {
  // Points 0 and 1 are 2 apart and both kept; point 2 is within 1.5 of both and joins 0; point 3
  // is within 1.5 of point 2 only, which is not kept, so it stays on its own.
  const std::vector<Vec3> points = {{0, 0, 0}, {2, 0, 0}, {1, 0.5, 0}, {1, 1.9, 0}, {2, 0, 1e-9}};
  CHECK(weld_points(points, 1.5) == std::vector<int>{0, 1, 0, 3, 1});
  CHECK(weld_points(points, 0.0) == std::vector<int>{0, 1, 2, 3, 4});
  CHECK(weld_points(points, 1e-9) == std::vector<int>{0, 1, 2, 3, 1});  // distance ≤ tolerance merges
}

TEST_CASE("weld_points: exact duplicates at any scale, and bad input") {
  const std::vector<Vec3> far = {{1e300, -1e300, 3}, {1e-300, 0, 0}, {1e300, -1e300, 3}, {-0.0, 0, 0}, {0, 0, 0}};
  CHECK(weld_points(far, 0.0) == std::vector<int>{0, 1, 0, 3, 3});
  CHECK(weld_points({}, 0.0).empty());
  CHECK_THROWS_AS(weld_points(far, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(weld_points(far, NAN), std::invalid_argument);
  CHECK_THROWS_AS(weld_points({{0, INFINITY, 0}}, 0.0), std::invalid_argument);
}

TEST_CASE("weld_points: the greedy rule by brute force, on clusters straddling the cells' borders") {
  // Clusters of points within about the tolerance of each other, spread over a box so that many
  // clusters cross the cells' borders along one, two or three axes.
  Random r(31, RandomStage::test, 0);
  for (double tolerance : {1e-3, 0.05, 0.3}) {
    std::vector<Vec3> points;
    for (int c = 0; c < 300; ++c) {
      const Vec3 centre = in_box(r, Vec3::Constant(-3.0), Vec3::Constant(3.0));
      const int members = 1 + static_cast<int>(r.uniform(0.0, 4.0));
      for (int m = 0; m < members; ++m)
        points.push_back(centre + in_box(r, Vec3::Constant(-0.8 * tolerance), Vec3::Constant(0.8 * tolerance)));
    }
    // Brute force: point i joins the lowest-indexed kept point within the tolerance.
    std::vector<int> expected(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      expected[i] = static_cast<int>(i);
      for (std::size_t k = 0; k < i; ++k)
        if (expected[k] == static_cast<int>(k) && (points[k] - points[i]).norm() <= tolerance) {
          expected[i] = static_cast<int>(k);
          break;
        }
    }
    INFO("tolerance " << tolerance);
    CHECK(weld_points(points, tolerance) == expected);
  }
}
