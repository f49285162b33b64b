// Segment–triangle crossings against exact answers, and the triangle grid's first crossing
// against a brute-force scan of every triangle.
#include <doctest/doctest.h>

#include <cmath>

#include "core/random.h"
#include "core/segment_triangle.h"
#include "core/shapes.h"
#include "core/triangle_grid.h"

using namespace hairfit;

TEST_CASE("segment_triangle_parameter: the exact share of the way, and no crossing where there is none") {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  CHECK(segment_triangle_parameter(Vec3(0.25, 0.25, -1), Vec3(0.25, 0.25, 3), a, b, c) == doctest::Approx(0.25).epsilon(1e-15));
  CHECK(segment_triangle_parameter(Vec3(0.25, 0.25, 3), Vec3(0.25, 0.25, -1), a, b, c) == doctest::Approx(0.75).epsilon(1e-15));
  CHECK(std::isnan(segment_triangle_parameter(Vec3(0.6, 0.6, -1), Vec3(0.6, 0.6, 1), a, b, c)));    // beside the hypotenuse
  CHECK(std::isnan(segment_triangle_parameter(Vec3(0.2, 0.2, 0.5), Vec3(0.2, 0.2, 2), a, b, c)));   // stops short of it
  CHECK(std::isnan(segment_triangle_parameter(Vec3(-1, 0.2, 0), Vec3(2, 0.2, 0), a, b, c)));        // in its plane
  CHECK(std::isnan(segment_triangle_parameter(Vec3(0.2, 0.2, 0), Vec3(0.2, 0.2, 1), a, b, c)));     // starts on it
  CHECK(std::isnan(segment_triangle_parameter(Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), a, a, c)));    // degenerate
  // With slack: a segment a hair beside an edge, and one that starts on the triangle.
  CHECK(std::isnan(segment_triangle_parameter(Vec3(-1e-8, 0.5, -1), Vec3(-1e-8, 0.5, 1), a, b, c)));
  CHECK(segment_triangle_parameter(Vec3(-1e-8, 0.5, -1), Vec3(-1e-8, 0.5, 1), a, b, c, 1e-6) == doctest::Approx(0.5));
  CHECK(segment_triangle_parameter(Vec3(0.2, 0.2, 0), Vec3(0.2, 0.2, 1), a, b, c, 1e-6, -1e-6, 1 + 1e-6) == 0.0);
}

TEST_CASE("TriangleGrid: the first crossing is the brute-force scan's, for segments of every length") {
  const Mesh sphere = uv_sphere(Vec3(0.3, -0.2, 0.1), 2.0, 24, 48);
  const TriangleGrid grid(sphere);
  Random r(3, RandomStage::test, 0);
  int crossing = 0;
  for (int k = 0; k < 3000; ++k) {
    const Vec3 p(r.uniform(-3, 3), r.uniform(-3, 3), r.uniform(-3, 3));
    const double length = k % 3 == 0 ? r.uniform(0.01, 0.2) : k % 3 == 1 ? r.uniform(0.2, 1.5) : r.uniform(1.5, 8.0);
    const Vec3 q = p + length * Vec3(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)).normalized();
    SegmentHit brute;
    for (int t = 0; t < static_cast<int>(sphere.triangles.size()); ++t) {
      const Vec3i& f = sphere.triangles[t];
      const double s = segment_triangle_parameter(p, q, sphere.positions[f[0]], sphere.positions[f[1]], sphere.positions[f[2]]);
      if (!std::isnan(s) && (!brute.found() || s < brute.t)) brute = {s, t};
    }
    const SegmentHit hit = grid.first_crossing(p, q);
    CHECK(hit.triangle == brute.triangle);
    if (hit.found()) CHECK(hit.t == brute.t);
    crossing += hit.found();
  }
  CHECK(crossing > 200);
  CHECK(!grid.first_crossing(Vec3(10, 10, 10), Vec3(11, 10, 10)).found());  // beyond the grid
  const Mesh empty;
  CHECK(!TriangleGrid(empty).first_crossing(Vec3(0, 0, 0), Vec3(1, 0, 0)).found());
}
