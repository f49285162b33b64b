// SAT voxelisation of frusta against brute force: points sampled densely inside each frustum must
// all fall in marked voxels (none missed), and every marked voxel must come within a thin
// tolerance of the frustum, measured by sampling the voxel and an independent distance (none
// extra). The paper's OBB variant is checked the same way against its box.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "core/random.h"
#include "density/accumulator.h"
#include "density/voxelise.h"

using namespace hairfit;

namespace {

struct Frame {
  Vec3 u, v, w;
  double length;
};

Frame frame_of(const Frustum& f) {  // independent of the library's choice of perpendiculars
  Frame fr;
  const Vec3 d = f.b - f.a;
  fr.length = d.norm();
  fr.u = d / fr.length;
  const Vec3 helper = std::abs(fr.u.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  fr.v = (helper - helper.dot(fr.u) * fr.u).normalized();
  fr.w = fr.u.cross(fr.v);
  return fr;
}

// Distance from p to the solid frustum, written independently: the meridian section is the
// intersection of four half-planes; inside all of them → 0, else the nearest of the four edges.
double reference_distance(const Vec3& p, const Frustum& f) {
  const Frame fr = frame_of(f);
  const double t = (p - f.a).dot(fr.u);
  const double rho = ((p - f.a) - t * fr.u).norm();
  const double L = fr.length;
  const Vec2 P(t, rho), A(0, 0), B(L, 0), C(L, f.radius_b), D(0, f.radius_a);
  const double side = (C - D).x() * (P - D).y() - (C - D).y() * (P - D).x();  // ≤ 0: below the slant
  if (t >= 0 && t <= L && side <= 0) return 0.0;
  auto seg = [&](const Vec2& s, const Vec2& e) {
    const Vec2 d = e - s;
    const double lam = std::clamp((P - s).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
    return (P - (s + lam * d)).norm();
  };
  return std::min({seg(A, B), seg(B, C), seg(C, D), seg(D, A)});
}

// The OBB's square cross-section turns with its side axes, so they are part of its definition
// (voxelise.h): v = normalised u × e_m, m the axis of u's smallest component, w = u × v.
double reference_obb_distance(const Vec3& p, const Frustum& f) {
  Frame fr = frame_of(f);
  int m = 0;
  fr.u.cwiseAbs().minCoeff(&m);
  fr.v = fr.u.cross(Vec3::Unit(m)).normalized();
  fr.w = fr.u.cross(fr.v);
  const double r = std::max(f.radius_a, f.radius_b);
  const Vec3 q = p - 0.5 * (f.a + f.b);
  const Vec3 local(q.dot(fr.u), q.dot(fr.v), q.dot(fr.w));
  const Vec3 half(0.5 * fr.length, r, r);
  return (local.cwiseAbs() - half).cwiseMax(0.0).norm();
}

GridGeometry test_grid() {
  GridGeometry g;
  g.origin = Vec3(-2.0, -1.9, -2.1);
  g.voxel = 0.25;
  g.dims = Vec3i(16, 16, 17);
  return g;
}

Frustum random_frustum(int item) {
  Random rng(21, RandomStage::test, item);
  Frustum f;
  f.a = Vec3(rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6));
  Vec3 dir(rng.normal(), rng.normal(), rng.normal());
  if (item % 7 == 0) dir = Vec3::Unit(item % 3);                    // axis-aligned
  if (item % 7 == 1) dir = Vec3(1, 1, 0);                            // in a grid plane
  const double len = item % 5 == 0 ? rng.uniform(0.001, 0.05) : rng.uniform(0.05, 1.2);
  f.b = f.a + len * dir.normalized();
  f.radius_a = rng.uniform(0.3, 0.6);
  f.radius_b = item % 4 == 0 ? f.radius_a : rng.uniform(0.3, 0.6);
  if (item % 11 == 0) f.radius_b = rng.uniform(0.0, 0.1);             // a sharp taper
  return f;
}

std::set<int64_t> marked(const GridGeometry& g, const Frustum& f, OccupancyShape shape) {
  std::set<int64_t> out;
  for (const Vec3i& c : frustum_cells(g, f, shape)) out.insert(g.index(c.x(), c.y(), c.z()));
  return out;
}

int64_t cell_of(const GridGeometry& g, const Vec3& p) {
  const Vec3 q = (p - g.origin) / g.voxel;
  return g.index(int(std::floor(q.x())), int(std::floor(q.y())), int(std::floor(q.z())));
}

// Minimum of dist over a (n+1)³ lattice of the voxel, faces included.
template <class D>
double min_over_voxel(const GridGeometry& g, int64_t index, D dist, int n) {
  const Vec3 lo = g.node(index);
  double best = 1e300;
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b)
      for (int c = 0; c <= n; ++c) best = std::min(best, dist(lo + g.voxel * Vec3(a, b, c) / n));
  return best;
}

}  // namespace

TEST_CASE("frustum voxelisation: no voxel missed, none extra beyond a thin tolerance") {
  const GridGeometry g = test_grid();
  const int lattice = 12;
  // A voxel whose closest point to the frustum lies between lattice points is found within half a
  // lattice diagonal of it.
  const double tolerance = 0.5 * std::sqrt(3.0) * g.voxel / lattice + 1e-9;
  for (int item = 0; item < 120; ++item) {
    const Frustum f = random_frustum(item);
    const std::set<int64_t> cells = marked(g, f, OccupancyShape::frustum);
    const Frame fr = frame_of(f);
    Random rng(22, RandomStage::test, item);
    // Interior and surface points (the surface is where misses would hide).
    int missed = 0;
    for (int s = 0; s < 20000; ++s) {
      const double t = rng.uniform(0.0, 1.0);
      const double r = f.radius_a + (f.radius_b - f.radius_a) * t;
      const double rho = s % 2 ? r : r * std::sqrt(rng.uniform(0.0, 1.0));
      const double phi = rng.uniform(0.0, 2.0 * M_PI);
      const Vec3 p = f.a + t * fr.length * fr.u + rho * (std::cos(phi) * fr.v + std::sin(phi) * fr.w);
      missed += cells.count(cell_of(g, p)) ? 0 : 1;
    }
    CHECK_MESSAGE(missed == 0, "frustum " << item);
    int extra = 0;
    for (int64_t c : cells) {
      const double d = min_over_voxel(g, c, [&](const Vec3& p) { return reference_distance(p, f); }, lattice);
      extra += d <= tolerance ? 0 : 1;
    }
    CHECK_MESSAGE(extra == 0, "frustum " << item);
    // Exhaustive cross-check of the decision on every cell near the frustum.
    for (int k = 0; k < g.dims.z(); ++k)
      for (int j = 0; j < g.dims.y(); ++j)
        for (int i = 0; i < g.dims.x(); ++i) {
          const Vec3 centre = g.cell_centre(i, j, k);
          const double dc = reference_distance(centre, f);
          if (dc <= 0.5 * g.voxel) CHECK(cells.count(g.index(i, j, k)) == 1);
          if (dc > 0.5 * std::sqrt(3.0) * g.voxel + 1e-9) CHECK(cells.count(g.index(i, j, k)) == 0);
        }
  }
}

TEST_CASE("the paper's OBB test: covers the frustum's box and nothing beyond it") {
  const GridGeometry g = test_grid();
  const int lattice = 8;
  const double tolerance = 0.5 * std::sqrt(3.0) * g.voxel / lattice + 1e-9;
  for (int item = 0; item < 30; ++item) {
    const Frustum f = random_frustum(item);
    const std::set<int64_t> obb = marked(g, f, OccupancyShape::obb);
    const std::set<int64_t> exact = marked(g, f, OccupancyShape::frustum);
    CHECK(std::includes(obb.begin(), obb.end(), exact.begin(), exact.end()));
    Frame fr = frame_of(f);
    int m = 0;
    fr.u.cwiseAbs().minCoeff(&m);
    fr.v = fr.u.cross(Vec3::Unit(m)).normalized();
    fr.w = fr.u.cross(fr.v);
    const double r = std::max(f.radius_a, f.radius_b);
    Random rng(23, RandomStage::test, item);
    int missed = 0;
    for (int s = 0; s < 10000; ++s) {
      const Vec3 p = 0.5 * (f.a + f.b) + rng.uniform(-0.5, 0.5) * fr.length * fr.u + rng.uniform(-r, r) * fr.v +
                     rng.uniform(-r, r) * fr.w;
      missed += obb.count(cell_of(g, p)) ? 0 : 1;
    }
    CHECK(missed == 0);
    int extra = 0;
    for (int64_t c : obb)
      extra += min_over_voxel(g, c, [&](const Vec3& p) { return reference_obb_distance(p, f); }, lattice) <= tolerance ? 0 : 1;
    CHECK(extra == 0);
  }
}

TEST_CASE("box–frustum tests on hand-made cases") {
  const Frustum f{Vec3(0, 0, 0), Vec3(0, 0, 1), 0.5, 0.25};
  const double tol = 1e-9;
  // Just beyond the end cap, just beyond the lateral surface, and touching.
  CHECK_FALSE(box_intersects_frustum(Vec3(-0.1, -0.1, 1.01), Vec3(0.1, 0.1, 1.2), f, tol));
  CHECK(box_intersects_frustum(Vec3(-0.1, -0.1, 0.99), Vec3(0.1, 0.1, 1.2), f, tol));
  CHECK_FALSE(box_intersects_frustum(Vec3(0.51, -0.1, -0.05), Vec3(0.7, 0.1, 0.05), f, tol));
  CHECK(box_intersects_frustum(Vec3(0.49, -0.1, -0.05), Vec3(0.7, 0.1, 0.05), f, tol));
  // Near the slanted side at mid-height (radius 0.375): the box corner region, where the OBB
  // (half-width 0.5) says yes but the cone says no.
  const Vec3 lo(0.30, 0.30, 0.45), hi(0.45, 0.45, 0.55);  // nearest point at distance √2·0.3 = 0.424 > 0.375
  CHECK(box_intersects_obb(lo, hi, f));
  CHECK_FALSE(box_intersects_frustum(lo, hi, f, tol));
  CHECK(std::abs(distance_to_frustum(Vec3(1, 0, 0.5), f) - reference_distance(Vec3(1, 0, 0.5), f)) < 1e-12);
  CHECK(distance_to_frustum(Vec3(0.1, 0.1, 0.5), f) == 0.0);
}

TEST_CASE("tubes: cells, occupied share and the paper's δ(s_i)") {
  GridGeometry g;
  g.origin = Vec3(0, 0, 0);
  g.voxel = 0.25;
  g.dims = Vec3i(20, 8, 8);
  // A straight tube of radius 0.3 along x at the centre of the y–z cross-section (y = z = 1):
  // the cells it occupies are those whose y–z square comes within 0.3 of the axis.
  const Tube tube{{Vec3(0.6, 1.0, 1.0), Vec3(1.5, 1.0, 1.0), Vec3(2.4, 1.0, 1.0)}, {0.3, 0.3, 0.3}};
  const std::vector<int64_t> cells = tube_cells(g, tube, OccupancyShape::frustum);
  // x: cells 2..9 (0.5..2.5 touch [0.6, 2.4]); y, z: squares [0.75,1.0],[1.0,1.25] (distance 0) and
  // [0.5,0.75],[1.25,1.5] (distance 0.25 ≤ 0.3): 4 per axis, minus the 4 diagonal corners whose
  // nearest point is 0.25·√2 = 0.354 > 0.3 away → 12 per x-layer.
  CHECK(cells.size() == 8 * 12);
  CHECK(std::is_sorted(cells.begin(), cells.end()));

  DensityAccumulator acc(g);
  CHECK(occupied_share(acc.freeze(), tube) == 0.0);
  acc.occupy(tube);
  const DensityGrid full = acc.freeze();
  CHECK(occupied_share(full, tube) == 1.0);
  // Half the tube's cells: those with x < 1.5 (cells 2..5 of 2..9).
  const Tube left{{Vec3(0.6, 1.0, 1.0), Vec3(1.4, 1.0, 1.0)}, {0.3, 0.3}};
  DensityAccumulator half(g);
  half.occupy(left);
  CHECK(std::abs(occupied_share(half.freeze(), tube) - 0.5) < 1e-15);
  CHECK(segment_hits_occupied(full, Vec3(0.1, 1.1, 1.1), Vec3(0.9, 1.1, 1.1)));
  CHECK_FALSE(segment_hits_occupied(full, Vec3(0.1, 1.9, 1.9), Vec3(4.9, 1.9, 1.9)));
  // Bad tubes are internal errors, named.
  CHECK_THROWS_AS(tube_cells(g, Tube{{Vec3(0, 0, 0), Vec3(1, 0, 0)}, {0.3}}, OccupancyShape::frustum), std::invalid_argument);
  CHECK_THROWS_AS(acc.occupy(Tube{{Vec3(0, 0, 0), Vec3(1, 0, 0)}, {0.3, -1.0}}), std::invalid_argument);
  // A zero-length frustum occupies nothing.
  CHECK(frustum_cells(g, Frustum{Vec3(1, 1, 1), Vec3(1, 1, 1), 0.5, 0.5}, OccupancyShape::frustum).empty());
}

TEST_CASE("tubes: the cells not yet settled are the frustum's cells less the settled ones") {
  GridGeometry g;
  g.origin = Vec3(-1, -1, -1);
  g.voxel = 0.25;
  g.dims = Vec3i(8, 8, 8);
  for (int item = 0; item < 40; ++item) {
    const Frustum f = random_frustum(item);
    // Every third cell settled, by a pattern the frustum knows nothing of.
    std::vector<double> settled(g.count(), 0.0);
    for (int64_t c = 0; c < g.count(); ++c) settled[c] = (c * 7 + item) % 3 == 0 ? 1.0 : 0.0;
    std::set<int64_t> expected;
    for (int64_t c : marked(g, f, OccupancyShape::frustum))
      if (settled[c] == 0.0) expected.insert(c);
    std::set<int64_t> got;
    for (const Vec3i& c : frustum_cells_unsettled(g, f, OccupancyShape::frustum, settled)) got.insert(g.index(c.x(), c.y(), c.z()));
    CHECK(got == expected);
  }
  CHECK_THROWS_AS(frustum_cells_unsettled(g, random_frustum(1), OccupancyShape::frustum, std::vector<double>(3, 0.0)),
                  std::invalid_argument);
}
