// The density models' fibre part (strands/density_spread.h) against closed forms: the trilinear
// deposit and the [1 2 1]/4 smoothing by hand, the gradient of a linear lattice exactly, and the
// spread itself by what it must keep (roots, segment lengths, thread count) and what it must do
// (a crowded bundle ends less crowded, counted by brute force).
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "strands/density_spread.h"

using namespace hairfit;

TEST_CASE("point_density deposits each point's trilinear weights") {
  const Vec3 lower(-1.0, -2.0, 0.5);
  const double h = 0.5;
  const Vec3i dims(4, 5, 6);
  const Vec3 p = lower + h * Vec3(1.25, 2.5, 3.75);  // fractions 0.25, 0.5, 0.75 past node (1, 2, 3)
  const PointDensity d = point_density({p}, lower, h, dims, 0);
  double total = 0.0;
  for (double v : d.values) total += v;
  CHECK(total == doctest::Approx(1.0).epsilon(1e-15));
  CHECK(d.at(1, 2, 3) == doctest::Approx(0.75 * 0.5 * 0.25));
  CHECK(d.at(2, 2, 3) == doctest::Approx(0.25 * 0.5 * 0.25));
  CHECK(d.at(1, 3, 4) == doctest::Approx(0.75 * 0.5 * 0.75));
  CHECK(d.at(2, 3, 4) == doctest::Approx(0.25 * 0.5 * 0.75));
  CHECK(d.at(0, 0, 0) == 0.0);
  // A point on a node puts all of it there.
  const PointDensity on = point_density({lower + h * Vec3(2, 1, 4)}, lower, h, dims, 0);
  CHECK(on.at(2, 1, 4) == 1.0);
  CHECK_THROWS_AS(point_density({lower - Vec3(0.1, 0, 0)}, lower, h, dims, 0), std::invalid_argument);
}

TEST_CASE("one smoothing pass spreads a node as (1 2 1)/4 along each axis") {
  const Vec3i dims(5, 5, 5);
  const PointDensity d = point_density({Vec3(2, 2, 2)}, Vec3::Zero(), 1.0, dims, 1);
  const double w[3] = {0.5, 0.25, 0.0};  // by distance 0, 1, 2 along an axis
  double total = 0.0;
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) {
        CHECK(d.at(i, j, k) == doctest::Approx(w[std::abs(i - 2)] * w[std::abs(j - 2)] * w[std::abs(k - 2)]));
        total += d.at(i, j, k);
      }
  CHECK(total == doctest::Approx(1.0));
  // At a face, what would fall beyond the lattice is lost.
  const PointDensity edge = point_density({Vec3(0, 2, 2)}, Vec3::Zero(), 1.0, dims, 1);
  double edge_total = 0.0;
  for (double v : edge.values) edge_total += v;
  CHECK(edge_total == doctest::Approx(0.75));
}

TEST_CASE("the gradient of a linear lattice is its slope everywhere, faces included") {
  PointDensity d;
  d.lower = Vec3(1.0, -1.0, 0.0);
  d.h = 0.25;
  d.dims = Vec3i(6, 7, 5);
  const Vec3 slope(2.0, -3.0, 0.5);
  d.values.resize(6 * 7 * 5);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 6; ++i)
        d.values[(k * 7 + j) * 6 + i] = 4.0 + slope.dot(d.h * Vec3(i, j, k));
  for (const Vec3& t : {Vec3(0.1, 0.2, 0.3), Vec3(0.0, 0.0, 0.0), Vec3(5.0, 6.0, 4.0), Vec3(4.9, 0.5, 3.99)}) {
    const Vec3 g = d.gradient(d.lower + d.h * t);
    for (int a = 0; a < 3; ++a) CHECK(g[a] == doctest::Approx(slope[a]).epsilon(1e-12));
  }
}

TEST_CASE("seen_density is the density an average point sees") {
  PointDensity d;
  d.values = {1.0, 3.0, 0.0};
  CHECK(seen_density(d) == doctest::Approx(2.5));  // (1·1 + 3·3) / 4
  d.values = {0.0, 0.0};
  CHECK(seen_density(d) == 0.0);
}

namespace {

// A crowded bundle: `count` straight fibres of n points along z, their roots on a 0.2 cm disc,
// their tips fanned slightly so that no two coincide.
std::vector<Vec3> bundle(int count, int n) {
  std::vector<Vec3> points;
  for (int f = 0; f < count; ++f) {
    const double a = 2.399963 * f, r = 0.2 * std::sqrt((f + 0.5) / count);
    const Vec3 root(r * std::cos(a), r * std::sin(a), 0.0);
    const Vec3 step = Vec3(0.02 * std::cos(a) * r, 0.02 * std::sin(a) * r, 0.5);
    for (int i = 0; i < n; ++i) points.push_back(root + i * step);
  }
  return points;
}

// The largest number of points past the roots (which never move) in one cell of edge `edge`
// (cells aligned at the origin), fibres of n points.
int most_in_a_cell(const std::vector<Vec3>& points, int n, double edge) {
  std::map<std::tuple<long, long, long>, int> cells;
  int most = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (k % n == 0) continue;
    const Vec3& p = points[k];
    int& c = cells[{std::lround(std::floor(p.x() / edge)), std::lround(std::floor(p.y() / edge)),
                    std::lround(std::floor(p.z() / edge))}];
    most = std::max(most, ++c);
  }
  return most;
}

}  // namespace

TEST_CASE("spread_fibres evens out a crowded bundle and keeps roots and segment lengths") {
  const int n = 12, count = 200;
  const std::vector<Vec3> grown = bundle(count, n);
  DensitySpread spread;
  spread.passes = 3;
  spread.voxel = 0.1;
  std::vector<Vec3> one = grown;
  spread_fibres(one, n, spread, 1);
  for (int f = 0; f < count; ++f) {
    CHECK(one[f * n] == grown[f * n]);
    for (int i = 1; i < n; ++i)
      CHECK((one[f * n + i] - one[f * n + i - 1]).norm() ==
            doctest::Approx((grown[f * n + i] - grown[f * n + i - 1]).norm()).epsilon(1e-12));
  }
  const int before = most_in_a_cell(grown, n, 0.1), after = most_in_a_cell(one, n, 0.1);
  CHECK(after < before);
  MESSAGE("most points in a 0.1 cm cell: ", before, " -> ", after);
  // Bit for bit the same on two threads.
  std::vector<Vec3> two = grown;
  spread_fibres(two, n, spread, 2);
  CHECK(one == two);
  // No passes: untouched; fibres that do not divide the points: refused.
  std::vector<Vec3> same = grown;
  spread.passes = 0;
  spread_fibres(same, n, spread);
  CHECK(same == grown);
  spread.passes = 1;
  CHECK_THROWS_AS(spread_fibres(same, n + 1, spread), std::invalid_argument);
}

TEST_CASE("normalise_by_region: a region filled evenly reads even up to its faces") {
  // One point on every node of the half-space x < 0.45 (h = 0.1): the deposit is the region's own
  // indicator, so after the same smoothing the density divided by the region's share is exactly 1
  // at every node where the share reaches the floor, the faces included.
  const Vec3 lower(0, 0, 0);
  const double h = 0.1;
  const Vec3i dims(10, 6, 6);
  const RegionTest region = [](const Vec3& p) { return p.x() < 0.45; };
  std::vector<Vec3> points;
  for (int k = 0; k < dims.z(); ++k)
    for (int j = 0; j < dims.y(); ++j)
      for (int i = 0; i < dims.x(); ++i)
        if (region(lower + h * Vec3(i, j, k))) points.push_back(lower + h * Vec3(i, j, k));
  PointDensity raw = point_density(points, lower, h, dims, 2);
  PointDensity even = raw;
  normalise_by_region(even, region, 2);
  int at_floor = 0;
  for (int k = 0; k < dims.z(); ++k)
    for (int j = 0; j < dims.y(); ++j)
      for (int i = 0; i < dims.x(); ++i) {
        if (raw.at(i, j, k) >= kRegionShareFloor) {
          CHECK(even.at(i, j, k) == doctest::Approx(1.0).epsilon(1e-12));
        } else {
          ++at_floor;
          CHECK(even.at(i, j, k) == doctest::Approx(raw.at(i, j, k) / kRegionShareFloor).epsilon(1e-12));
        }
      }
  CHECK(at_floor > 0);
  // Between the last two nodes before the face (x = 0.35, mid-lattice in y and z): the raw
  // density falls toward the face, the normalised one is flat.
  const Vec3 p = lower + h * Vec3(3.5, 2.5, 2.5);
  CHECK(raw.gradient(p).x() < -0.1);
  CHECK(std::abs(even.gradient(p).x()) < 1e-9);
}

TEST_CASE("spread_fibres in a thin layer moves the fibres along it, not out of it") {
  // The bundle (along z) squashed into the layer |y| ≤ 0.15: spread by space, its points are
  // pushed out through the layer's faces as well; spread by the region, far fewer are.
  const int n = 12, count = 200;
  std::vector<Vec3> grown = bundle(count, n);
  for (Vec3& p : grown) p.y() *= 0.5;
  double thickest = 0.0;
  for (const Vec3& p : grown) thickest = std::max(thickest, std::abs(p.y()));
  REQUIRE(thickest < 0.15);
  const RegionTest layer = [](const Vec3& p) { return std::abs(p.y()) <= 0.15; };
  DensitySpread spread;
  spread.passes = 3;
  spread.voxel = 0.1;
  std::vector<Vec3> by_space = grown, by_region = grown;
  spread_fibres(by_space, n, spread, 1);
  spread_fibres(by_region, n, spread, 1, layer);
  auto outside = [&](const std::vector<Vec3>& points) {
    int out = 0;
    for (const Vec3& p : points) out += !layer(p);
    return out;
  };
  MESSAGE("points out of the layer: by space ", outside(by_space), ", by region ", outside(by_region));
  CHECK(outside(by_region) < outside(by_space) / 4);
  CHECK(most_in_a_cell(by_region, n, 0.1) < most_in_a_cell(grown, n, 0.1));
}
