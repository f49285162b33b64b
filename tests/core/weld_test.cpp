#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "core/weld.h"

using namespace hairfit;

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
