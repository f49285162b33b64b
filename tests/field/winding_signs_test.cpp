// The robust sign's exact machinery against independent answers: the jumps on grid edges against
// rounded direct winding-number sums on closed meshes (also with faces on grid planes and vertices
// on nodes, where only the symbolic displacement decides), the rims' gradient bound against the
// Biot–Savart field summed finely and against the winding number's actual change, and the
// decisions against the direct sums.
#include <doctest/doctest.h>

#include <cmath>

#include "core/fast_winding.h"
#include "core/random.h"
#include "core/triangle_closest.h"
#include "field/distance_field.h"
#include "field/hair_region.h"
#include "field/winding_signs.h"
#include "test_meshes.h"

using namespace hairfit;
using namespace hairfit::field;

namespace {

// The grid a field of `m` would take at this voxel and margin.
GridGeometry grid_around(const Mesh& m, double voxel, double margin) {
  const FieldGridPlan plan = plan_field_grid(m, test::spec_for(voxel, 3, margin));
  return GridGeometry{plan.origin, voxel, plan.dims};
}

// Every node off the surface: the direct winding number, rounded, is the sum of the jumps from
// the grid's corner node (outside, w = 0).
int jump_mismatches(const Mesh& mesh, const GridGeometry& grid) {
  const GridCrossings crossings({{&mesh, 1}}, grid, 2);
  const FastWindingNumber winding(mesh);
  int wrong = 0, checked = 0;
  for (int k = 0; k < grid.dims.z(); ++k)
    for (int j = 0; j < grid.dims.y(); ++j)
      for (int i = 0; i < grid.dims.x(); ++i) {
        const Vec3 p = grid.node(i, j, k);
        const double w = winding.direct(p);
        if (std::abs(w - std::round(w)) > 1e-6) continue;  // on the surface (or within round-off of it)
        ++checked;
        wrong += std::lround(w) != crossings.path(Vec3i::Zero(), Vec3i(i, j, k));
      }
  CHECK(checked > 1000);
  return wrong;
}

}  // namespace

TEST_CASE("grid jumps: a closed sphere's winding number is the sum of the jumps from outside") {
  const Mesh sphere = test::icosphere(3, 1.0);
  CHECK(jump_mismatches(sphere, grid_around(sphere, 0.07, 0.2)) == 0);
}

TEST_CASE("grid jumps: faces on grid planes and vertices on nodes decide by the symbolic displacement") {
  // A cube of side 1 on a grid of spacing 0.125: every face lies on a grid plane, every vertex on a
  // node, every edge along a grid line. Two nested cubes (the inner reversed) make a shell.
  Mesh shell = test::cube(0.5);
  Mesh inner = test::cube(0.25);
  const int base = int(shell.positions.size());
  for (const Vec3& p : inner.positions) shell.positions.push_back(p);
  for (const Vec3i& t : inner.triangles) shell.triangles.push_back({t[0] + base, t[2] + base, t[1] + base});
  GridGeometry grid;
  grid.voxel = 0.125;
  grid.origin = Vec3::Constant(-1.0);
  grid.dims = Vec3i::Constant(17);
  const GridCrossings crossings({{&shell, 1}}, grid, 1);
  const FastWindingNumber winding(shell);
  int checked = 0, wrong = 0;
  for (int k = 0; k < 17; ++k)
    for (int j = 0; j < 17; ++j)
      for (int i = 0; i < 17; ++i) {
        const Vec3 p = grid.node(i, j, k);
        // Off the surface: strictly inside or outside each cube's box.
        auto strictly = [&](double s) { return p.cwiseAbs().maxCoeff() != s; };
        if (!strictly(0.5) || !strictly(0.25)) continue;
        ++checked;
        const int expected = p.cwiseAbs().maxCoeff() < 0.5 && p.cwiseAbs().maxCoeff() > 0.25;
        wrong += crossings.path(Vec3i::Zero(), Vec3i(i, j, k)) != expected;
        wrong += std::lround(winding.direct(p)) != expected;
      }
  CHECK(checked > 4000);
  CHECK(wrong == 0);
  // Every path between two nodes counts the same jumps: from the far corner as from the centre.
  const Vec3i centre = Vec3i::Constant(8), corner = Vec3i::Constant(16);
  for (int k = 0; k < 17; ++k)
    for (int j = 0; j < 17; ++j)
      for (int i = 0; i < 17; ++i) {
        const Vec3i v(i, j, k);
        CHECK(crossings.path(Vec3i::Zero(), v) ==
              crossings.path(Vec3i::Zero(), corner) + crossings.path(corner, v));
        CHECK(crossings.path(centre, v) == -crossings.path(v, centre));
      }
}

TEST_CASE("grid jumps and rim bound: a raw soup (hole, flipped patch, duplicates) changes as they say") {
  // Between adjacent nodes, w(b) − w(a) − J(a → b) is the smooth part, which the rims bound:
  // |w(b) − w(a) − J| ≤ G · h, with G over the edge's box (infinite beside a rim).
  const Mesh soup = test::messy_sphere(3, 1.0);
  const GridGeometry grid = grid_around(soup, 0.09, 0.2);
  const GridCrossings crossings({{&soup, 1}}, grid, 2);
  const RimBound rims({{&soup, 1}});
  const FastWindingNumber winding(soup);
  int jumps = 0, bounded = 0, wrong = 0;
  for (int k = 0; k + 1 < grid.dims.z(); ++k)
    for (int j = 0; j < grid.dims.y(); ++j)
      for (int i = 0; i < grid.dims.x(); ++i) {
        const Vec3 a = grid.node(i, j, k), b = grid.node(i, j, k + 1);
        const double change = winding.direct(b) - winding.direct(a);
        const int jump = crossings.along(2, crossings.line(2, i, j, 0), k, k + 1);
        const double g = rims.gradient(a, b);
        jumps += jump != 0;
        if (!std::isfinite(g)) continue;
        ++bounded;
        wrong += std::abs(change - jump) > g * grid.voxel + 1e-9;
      }
  CHECK(jumps > 300);
  CHECK(bounded > 10000);
  CHECK(wrong == 0);
}

TEST_CASE("rim bound: zero for a closed surface, above the exact Biot-Savart field elsewhere") {
  const Mesh sphere = test::icosphere(2, 1.0);
  CHECK(RimBound({{&sphere, 1}}).rims() == 0);
  CHECK(RimBound({{&sphere, 1}}).gradient(Vec3::Constant(-0.1), Vec3::Constant(0.1)) == 0.0);
  // A sphere and the same sphere reversed cancel; so do a hull and a reversed copy of its scalp.
  CHECK(RimBound({{&sphere, 1}, {&sphere, -1}}).rims() == 0);

  const Mesh cap = test::open_cap(3, 1.0, 0.3);
  const RimBound bound({{&cap, 1}});
  CHECK(bound.rims() > 10);
  const FastWindingNumber winding(cap);
  Random rng(7, RandomStage::test, 0);
  int boxes = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 centre(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(-1.0, 2.0));
    const double half = rng.uniform(0.02, 0.2);
    const Vec3 lo = centre - Vec3::Constant(half), hi = centre + Vec3::Constant(half);
    const double g = bound.gradient(lo, hi);
    if (!std::isfinite(g)) continue;
    ++boxes;
    // The winding number's change between the box's corners, where no triangle lies between:
    // |Δw| ≤ g · |Δx|₁ along the box's edges (checked where the direct sums show no jump).
    for (int q = 1; q < 8; ++q) {
      const Vec3 a = lo, b(q & 1 ? hi.x() : lo.x(), q & 2 ? hi.y() : lo.y(), q & 4 ? hi.z() : lo.z());
      const double dw = std::abs(winding.direct(b) - winding.direct(a));
      if (dw > 0.5) continue;  // a sheet between them
      CHECK(dw <= g * (b - a).lpNorm<1>() + 1e-12);
    }
  }
  CHECK(boxes > 50);
}

TEST_CASE("grid winding signs: the direct sums' decisions, and a closed surface settled by references alone") {
  for (const Mesh& mesh : {test::open_cap(3, 1.0, 0.3), test::messy_sphere(3, 1.0), test::icosphere(3, 1.0)})
  for (bool box_estimates : {false, true}) {
    CAPTURE(box_estimates);
    const GridGeometry grid = grid_around(mesh, 0.05, 0.3);
    const FastWindingNumber winding(mesh);
    WindingSoup soup = winding_soup(mesh, winding);  // estimates at β = 4, the certified test
    if (!box_estimates) soup.estimate_box = nullptr;  // every undecided node asked by itself
    const GridWindingSigns signs(soup, grid, 2);
    std::vector<int64_t> nodes;
    std::vector<double> distance;
    // Every fifth node, with its distance to the mesh (brute force).
    for (int64_t n = 0; n < grid.count(); n += 5) {
      const Vec3 p = grid.node(n);
      double d2 = 1e300;
      for (const Vec3i& t : mesh.triangles) {
        const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
        const Vec3 w = closest_barycentric(p, a, b, c);
        d2 = std::min(d2, (w[0] * a + w[1] * b + w[2] * c - p).squaredNorm());
      }
      nodes.push_back(n), distance.push_back(std::sqrt(d2));
    }
    GridWindingSigns::Counts counts;
    const std::vector<std::uint8_t> inside = signs.decide(nodes, distance, 3, &counts);
    CHECK(counts.nodes == int64_t(nodes.size()));
    int wrong = 0;
    for (std::size_t q = 0; q < nodes.size(); ++q) {
      const double w = winding.direct(grid.node(nodes[q]));
      if (std::abs(w - 0.5) < 1e-3) continue;  // on the fence: either answer
      wrong += (w > 0.5) != bool(inside[q]);
    }
    CHECK(wrong == 0);
    if (signs.rims().rims() == 0) {
      CHECK(counts.asked == 0);
      CHECK(counts.references < int64_t(nodes.size()) / 100);
    } else if (box_estimates) {
      CHECK(counts.boxes > 0);
    } else {
      CHECK(counts.boxes == 0);
    }
  }
}
