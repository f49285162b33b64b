// strand_coverage and area_samples against exact areas.
#include <doctest/doctest.h>

#include "strands/coverage.h"

using namespace hairfit;

namespace {

// The unit square [0, 1]² at z = 0 as two triangles, and a 3 × 1 rectangle beside it.
Mesh two_pieces() {
  Mesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                 Vec3(2, 0, 0), Vec3(5, 0, 0), Vec3(5, 1, 0), Vec3(2, 1, 0)};
  m.triangles = {Vec3i(0, 1, 2), Vec3i(0, 2, 3), Vec3i(4, 5, 6), Vec3i(4, 6, 7)};
  return m;
}

}  // namespace

TEST_CASE("area samples fall on each piece in proportion to its area, inside its triangles") {
  const std::vector<Vec3> s = area_samples(two_pieces(), 4000);
  REQUIRE(s.size() == 4000);
  int square = 0;
  for (const Vec3& p : s) {
    CHECK(p.z() == 0.0);
    const bool in_square = p.x() >= 0 && p.x() <= 1 && p.y() >= 0 && p.y() <= 1;
    const bool in_rect = p.x() >= 2 && p.x() <= 5 && p.y() >= 0 && p.y() <= 1;
    CHECK((in_square || in_rect));
    square += in_square;
  }
  CHECK(square == 1000);  // stratified: exactly ¼ of the samples on ¼ of the area
}

TEST_CASE("coverage: points over the square cover exactly its share; uncounted samples are left out") {
  std::vector<Vec3> strands;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) strands.push_back(Vec3(i * 0.05, j * 0.05, 0.0));
  CoverageOptions o;
  o.radius = 0.2;  // reaches 0.2 beyond the square, never the rectangle 1 away
  o.samples = 4000;
  const auto all = [](const Vec3&) { return true; };
  const Coverage c = strand_coverage(two_pieces(), strands, all, o);
  CHECK(c.samples == 4000);
  CHECK(c.covered == 1000);
  CHECK(c.share == doctest::Approx(0.25));
  const Coverage square_only = strand_coverage(two_pieces(), strands, [](const Vec3& p) { return p.x() < 1.5; }, o);
  CHECK(square_only.samples == 1000);
  CHECK(square_only.share == 1.0);
  CHECK(strand_coverage(two_pieces(), {}, all, o).share == 0.0);
}
