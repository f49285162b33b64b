// Amanatides–Woo traversal against an independent reference: the parameters where the segment
// meets any grid plane, sorted; each interval's midpoint names its cell.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "core/random.h"
#include "density/grid.h"
#include "density/traversal.h"

using namespace hairfit;

namespace {

GridGeometry small_grid(double h = 0.25) {
  GridGeometry g;
  g.origin = Vec3(-1.0, -0.5, 0.25);
  g.voxel = h;
  g.dims = Vec3i(12, 9, 10);
  return g;
}

// Reference per-cell lengths: every plane crossing splits the segment; a piece's cell is where
// its midpoint lies. Pieces outside the box are dropped (the documented clipping).
std::map<int64_t, double> reference_lengths(const GridGeometry& g, const Vec3& a, const Vec3& b) {
  std::vector<double> ts = {0.0, 1.0};
  const Vec3 d = b - a;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) continue;
    for (int i = 0; i <= g.dims[k]; ++i) {
      const double t = (g.origin[k] + g.voxel * i - a[k]) / d[k];
      if (t > 0.0 && t < 1.0) ts.push_back(t);
    }
  }
  std::sort(ts.begin(), ts.end());
  std::map<int64_t, double> out;
  for (size_t s = 0; s + 1 < ts.size(); ++s) {
    if (ts[s + 1] <= ts[s]) continue;
    const Vec3 mid = a + 0.5 * (ts[s] + ts[s + 1]) * d;
    const Vec3 q = (mid - g.origin) / g.voxel;
    const Vec3i c(int(std::floor(q.x())), int(std::floor(q.y())), int(std::floor(q.z())));
    if (!g.contains(c.x(), c.y(), c.z())) continue;
    out[g.index(c.x(), c.y(), c.z())] += (ts[s + 1] - ts[s]) * d.norm();
  }
  return out;
}

double total(const std::vector<CellCrossing>& cs) {
  double s = 0.0;
  for (const CellCrossing& c : cs) s += c.length;
  return s;
}

bool face_neighbours(const Vec3i& a, const Vec3i& b) { return (a - b).cwiseAbs().sum() == 1; }

}  // namespace

TEST_CASE("random segments inside the grid: cells and lengths match the plane-crossing reference") {
  const GridGeometry g = small_grid();
  for (int item = 0; item < 500; ++item) {
    Random rng(11, RandomStage::test, item);
    const Vec3 lo = g.origin, hi = g.upper();
    auto point = [&] {
      return Vec3(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()), rng.uniform(lo.z(), hi.z()));
    };
    const Vec3 a = point();
    // Mix long segments, short ones and ones within one cell.
    const double scale = item % 3 == 0 ? 1.0 : (item % 3 == 1 ? 0.1 : 1e-4);
    const Vec3 b = a + scale * (point() - a);
    const std::vector<CellCrossing> cs = traverse_segment(g, a, b);
    const double L = (b - a).norm();
    CHECK(std::abs(total(cs) - L) <= 1e-12 * L);
    const std::map<int64_t, double> ref = reference_lengths(g, a, b);
    REQUIRE(cs.size() == ref.size());
    for (size_t c = 0; c < cs.size(); ++c) {
      const int64_t idx = g.index(cs[c].cell.x(), cs[c].cell.y(), cs[c].cell.z());
      REQUIRE(ref.count(idx) == 1);
      CHECK(std::abs(cs[c].length - ref.at(idx)) <= 1e-12 * std::max(L, g.voxel));
      CHECK(cs[c].length > 0.0);
      if (c > 0) CHECK(face_neighbours(cs[c - 1].cell, cs[c].cell));
    }
  }
}

TEST_CASE("segments partly outside the grid are clipped to the box") {
  const GridGeometry g = small_grid();
  const Vec3 lo = g.origin, hi = g.upper();
  SUBCASE("through the whole grid along x") {
    const Vec3 a(lo.x() - 3.0, lo.y() + 0.3, lo.z() + 0.6), b(hi.x() + 2.0, lo.y() + 0.3, lo.z() + 0.6);
    const auto cs = traverse_segment(g, a, b);
    CHECK(cs.size() == size_t(g.dims.x()));
    CHECK(std::abs(total(cs) - (hi.x() - lo.x())) <= 1e-12);
    for (const CellCrossing& c : cs) CHECK(std::abs(c.length - g.voxel) <= 1e-12);
  }
  SUBCASE("oblique, both ends outside") {
    for (int item = 0; item < 200; ++item) {
      Random rng(12, RandomStage::test, item);
      const Vec3 a(rng.uniform(lo.x() - 2, hi.x() + 2), rng.uniform(lo.y() - 2, hi.y() + 2), rng.uniform(lo.z() - 2, hi.z() + 2));
      const Vec3 b(rng.uniform(lo.x() - 2, hi.x() + 2), rng.uniform(lo.y() - 2, hi.y() + 2), rng.uniform(lo.z() - 2, hi.z() + 2));
      const auto cs = traverse_segment(g, a, b);
      double expected = 0.0;
      for (const auto& kv : reference_lengths(g, a, b)) expected += kv.second;
      CHECK(std::abs(total(cs) - expected) <= 1e-12 * (b - a).norm());
    }
  }
  SUBCASE("entirely outside") {
    CHECK(traverse_segment(g, lo - Vec3(1, 1, 1), lo - Vec3(0.1, 2, 0.5)).empty());
    CHECK(traverse_segment(g, Vec3(lo.x() - 1, lo.y() - 0.01, lo.z() + 1), Vec3(hi.x() + 1, lo.y() - 0.01, lo.z() + 1)).empty());
  }
}

TEST_CASE("degenerate segments: zero length, on grid planes, through corners") {
  const GridGeometry g = small_grid();
  const double h = g.voxel;
  SUBCASE("zero length and non-finite give nothing") {
    const Vec3 p = g.cell_centre(3, 4, 5);
    CHECK(traverse_segment(g, p, p).empty());
    CHECK(traverse_segment(g, p, Vec3(NAN, 0, 0)).empty());
  }
  SUBCASE("very short segment stays in its cell") {
    const Vec3 p = g.cell_centre(3, 4, 5);
    const Vec3 q = p + Vec3(1e-13, -2e-13, 3e-13);
    const auto cs = traverse_segment(g, p, q);
    REQUIRE(cs.size() == 1);
    CHECK(cs[0].cell == Vec3i(3, 4, 5));
    CHECK(std::abs(cs[0].length - (q - p).norm()) <= 1e-12 * (q - p).norm());
  }
  SUBCASE("along a grid line (edge shared by four cells): one cell per step, upper side") {
    const Vec3 a = g.node(2, 3, 1), b = g.node(2, 3, 7);
    const auto cs = traverse_segment(g, a, b);
    REQUIRE(cs.size() == 6);
    for (int s = 0; s < 6; ++s) {
      CHECK(cs[s].cell == Vec3i(2, 3, 1 + s));
      CHECK(std::abs(cs[s].length - h) <= 1e-12);
    }
    // Downwards along the same line the length still adds up.
    CHECK(std::abs(total(traverse_segment(g, b, a)) - 6 * h) <= 1e-12);
  }
  SUBCASE("on the grid's upper face stays in the last layer") {
    const Vec3 a(g.origin.x() + 0.3 * h, g.upper().y(), g.origin.z() + 0.5 * h);
    const auto cs = traverse_segment(g, a, a + Vec3(2.0 * h, 0, 0));
    REQUIRE(!cs.empty());
    for (const auto& c : cs) CHECK(c.cell.y() == g.dims.y() - 1);
    CHECK(std::abs(total(cs) - 2.0 * h) <= 1e-12);
  }
  SUBCASE("diagonals through cell corners skip the zero-length cells") {
    for (int dir = 0; dir < 8; ++dir) {
      const Vec3 s((dir & 1) ? 1 : -1, (dir & 2) ? 1 : -1, (dir & 4) ? 1 : -1);
      const Vec3 centre = g.node(6, 4, 5);  // a grid node
      const Vec3 a = centre - 3.0 * h * s, b = centre + 3.0 * h * s;
      const auto cs = traverse_segment(g, a, b);
      CHECK(cs.size() == 6);  // only the cells the diagonal passes through, h√3 each
      for (const auto& c : cs) CHECK(std::abs(c.length - h * std::sqrt(3.0)) <= 1e-12);
      CHECK(std::abs(total(cs) - (b - a).norm()) <= 1e-12 * (b - a).norm());
    }
  }
  SUBCASE("in a face plane at 45°: through edges") {
    const Vec3 a = g.node(1, 1, 3), b = g.node(7, 7, 3);
    const auto cs = traverse_segment(g, a, b);
    CHECK(cs.size() == 6);
    CHECK(std::abs(total(cs) - (b - a).norm()) <= 1e-12 * (b - a).norm());
  }
}

TEST_CASE("a walk over some layers finds the full walk's crossings in them, bit for bit") {
  const GridGeometry g = small_grid();
  Random rng(77, RandomStage::test, 0);
  const Vec3 lo = g.origin, hi = g.upper();
  int compared = 0, skipped_ahead = 0;
  for (int n = 0; n < 20000; ++n) {
    auto point = [&] {
      Vec3 p(rng.uniform(lo.x() - 0.3, hi.x() + 0.3), rng.uniform(lo.y() - 0.3, hi.y() + 0.3),
             rng.uniform(lo.z() - 0.3, hi.z() + 0.3));
      // Some on grid planes and some sharing a coordinate (axis-parallel segments, ties).
      if (n % 7 == 0) p.z() = lo.z() + g.voxel * std::floor(rng.uniform(0, g.dims.z() + 1));
      if (n % 11 == 0) p.x() = lo.x() + g.voxel * std::floor(rng.uniform(0, g.dims.x() + 1));
      return p;
    };
    Vec3 a = point();
    Vec3 b = point();
    if (n % 13 == 0) b.z() = a.z();
    if (n % 5 == 0) {  // from a grid node by whole cells: through edges and corners, exact ties
      Vec3i node, cells;
      for (int k = 0; k < 3; ++k) {
        node[k] = static_cast<int>(rng.uniform(0, g.dims[k] + 1));
        cells[k] = static_cast<int>(rng.uniform(-4, 5));
      }
      a = lo + g.voxel * node.cast<double>();
      b = a + g.voxel * cells.cast<double>();
    }
    const int k_begin = static_cast<int>(rng.uniform(0, g.dims.z()));
    const int k_end = k_begin + 1 + static_cast<int>(rng.uniform(0, g.dims.z() - k_begin));
    std::vector<CellCrossing> expected;
    for (const CellCrossing& c : traverse_segment(g, a, b))
      if (c.cell.z() >= k_begin && c.cell.z() < k_end) expected.push_back(c);
    std::vector<CellCrossing> got;
    for_each_cell_crossing(
        g, a, b, [&](const Vec3i& cell, double length) { got.push_back({cell, length}); }, k_begin, k_end);
    REQUIRE(got.size() == expected.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      CHECK(got[i].cell == expected[i].cell);
      CHECK(got[i].length == expected[i].length);
    }
    compared += !expected.empty();
    // How often the walk starts outside the layers (the skip ahead is exercised).
    const std::vector<CellCrossing> all = traverse_segment(g, a, b);
    skipped_ahead += !all.empty() && !expected.empty() && (all[0].cell.z() < k_begin || all[0].cell.z() >= k_end);
  }
  CHECK(compared > 5000);
  CHECK(skipped_ahead > 1000);
}
