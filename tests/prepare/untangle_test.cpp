// Untangling a scan that crosses itself (prepare/untangle.h), and lowering a level-set strip that
// crosses the hull (prepare/level_set_strip.h), on meshes whose answers are known by construction.
#include <doctest/doctest.h>

#include <cmath>

#include "core/shapes.h"
#include "prepare/level_set_strip.h"
#include "prepare/surface_checks.h"
#include "prepare/untangle.h"

using namespace hairfit;

TEST_CASE("untangling: a sphere is left as it is; a vertex folded over its neighbours is smoothed back, nothing far moves") {
  Mesh sphere = icosphere(3, 2.0);
  const Mesh clean = sphere;
  const Untangled none = untangle_self_intersections(sphere, 2);
  CHECK(none.pairs_found == 0);
  CHECK(none.rounds == 0);
  CHECK(sphere.positions == clean.positions);

  // Vertex 0 pushed along the surface past its whole ring (1.5 edges beyond a neighbour): its fan
  // folds over the neighbouring triangles.
  const std::vector<std::vector<int>> next = vertex_neighbours(sphere);
  const int v = 0, w = next[0][0];
  const Vec3 along = sphere.positions[w] - sphere.positions[v];
  sphere.positions[v] += 2.5 * along;
  sphere.positions[v] *= 2.0 / sphere.positions[v].norm();
  REQUIRE_FALSE(self_intersections(sphere, 1000).empty());
  const Untangled u = untangle_self_intersections(sphere, 2);
  CHECK(u.pairs_found > 0);
  CHECK(u.pairs_left == 0);
  CHECK(self_intersections(sphere, 1000).empty());
  CHECK(u.rounds >= 1);
  CHECK(u.vertices_moved > 0);
  CHECK(u.largest_move <= 3.0 * along.norm());
  // The folded vertex is back among its neighbours, near the sphere (a neighbourhood's mean lies
  // a little inside it).
  CHECK(sphere.positions[v].norm() == doctest::Approx(2.0).epsilon(0.05));
  // Vertices more than (rounds + 1) rings from the fold's triangles did not move: the far pole.
  int farthest = 0;
  for (int k = 0; k < static_cast<int>(clean.positions.size()); ++k)
    if (clean.positions[k].dot(clean.positions[v]) < clean.positions[farthest].dot(clean.positions[v])) farthest = k;
  CHECK(sphere.positions[farthest] == clean.positions[farthest]);
  int moved = 0;
  for (std::size_t k = 0; k < clean.positions.size(); ++k) moved += sphere.positions[k] != clean.positions[k] && k != 0;
  CHECK(moved + 1 == u.vertices_moved);
  // The same for any thread count.
  Mesh again = clean;
  again.positions[v] = clean.positions[v] + 2.5 * along;
  again.positions[v] *= 2.0 / again.positions[v].norm();
  untangle_self_intersections(again, 1);
  CHECK(again.positions == sphere.positions);
}

namespace {

// A flat hull on z = 0 over [−4, 4]² with a square hole [−2, 2]² (its hairline, counter-clockwise
// seen from +z, 4 vertices a side), and a sheet whose piece is the square [−1, 1]² at z = −1 (its
// boundary, 4 vertices a side too) zipped to that hairline: the strip runs down and in at 45°.
struct FlatCase {
  Mesh hull;
  std::vector<int> hairline;
  LevelSetSheet sheet;
};

std::vector<Vec3> square_loop(double half, double z) {
  std::vector<Vec3> loop;
  const Vec3 corners[4] = {Vec3(-half, -half, z), Vec3(half, -half, z), Vec3(half, half, z), Vec3(-half, half, z)};
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < 4; ++k) loop.push_back(corners[side] + (corners[(side + 1) % 4] - corners[side]) * (k / 4.0));
  return loop;
}

FlatCase flat_case() {
  FlatCase c;
  const std::vector<Vec3> rim = square_loop(2.0, 0.0), edge = square_loop(4.0, 0.0);
  const int n = static_cast<int>(rim.size());
  c.hull.positions = rim;
  c.hull.positions.insert(c.hull.positions.end(), edge.begin(), edge.end());
  // The ring between the two squares: its normal faces +z, the hairline runs counter-clockwise.
  for (int j = 0; j < n; ++j) {
    const int k = (j + 1) % n;
    c.hull.triangles.emplace_back(k, j, n + j);
    c.hull.triangles.emplace_back(k, n + j, n + k);
  }
  for (int j = 0; j < n; ++j) c.hairline.push_back(j);
  // The piece: a fan over the inner square's centre, then the loop's copy, as sheet() lays them out.
  LevelSetSheet& s = c.sheet;
  const std::vector<Vec3> inner = square_loop(1.0, -1.0);
  s.mesh.positions = inner;
  s.mesh.positions.push_back(Vec3(0, 0, -1));
  for (int j = 0; j < n; ++j) s.mesh.triangles.emplace_back(j, (j + 1) % n, n);
  for (int j = 0; j < n; ++j) s.inner.push_back(j);
  s.thickness.assign(s.mesh.positions.size(), 1.0);
  s.piece_vertices = s.mesh.positions.size();
  for (int j = 0; j < n; ++j) {
    s.outer.push_back(static_cast<int>(s.mesh.positions.size()));
    s.mesh.positions.push_back(rim[j]);
    s.thickness.push_back(0.0);
  }
  s.strip_begin = s.mesh.triangles.size();
  for (int j = 0; j <= n; ++j) s.inner_at.push_back(j / double(n)), s.outer_at.push_back(j / double(n));
  zip_strip(s, std::vector<double>(n, 0.0), std::vector<Vec3>(n, Vec3::Zero()));
  return c;
}

}  // namespace

TEST_CASE("a level-set strip: zipped under a flat hull it crosses nothing; a dip in the hull crosses it, feet clear it") {
  FlatCase c = flat_case();
  const int n = static_cast<int>(c.hairline.size());
  // Zipped: 2 triangles a pair of loop edges, the sheet a disk with the hairline as its boundary.
  CHECK(c.sheet.mesh.triangles.size() - c.sheet.strip_begin == static_cast<std::size_t>(2 * n));
  const MeshTopology zipped = analyse_topology(c.sheet.mesh);
  CHECK(zipped.is_disk());
  CHECK(zipped.orientation_consistent);
  CHECK(strip_crossings(c.sheet, c.hull, c.hairline, 2).empty());

  // A flap of hull hanging from just above the strip near the hairline vertices 1 and 2 (on the
  // side y = −2, where the strip lies at z = −(y + 2)) to 0.3 below it: it dips through the strip.
  Mesh dipped = c.hull;
  const int dip = static_cast<int>(dipped.positions.size());
  dipped.positions.push_back(Vec3(-0.8, -1.9, 0.1));
  dipped.positions.push_back(Vec3(-0.2, -1.9, 0.1));
  dipped.positions.push_back(Vec3(-0.5, -1.5, -0.8));
  dipped.triangles.emplace_back(dip, dip + 1, dip + 2);
  const std::vector<int> crossing = strip_crossings(c.sheet, dipped, c.hairline, 2);
  REQUIRE_FALSE(crossing.empty());
  for (int j : crossing) CHECK((j >= 0 && j <= 3));

  // Feet 0.9 straight down under those hairline vertices: the strip leaves the hairline vertically
  // and runs on below the dip.
  std::vector<double> depth(n, 0.0);
  for (int j = 0; j <= 3; ++j) depth[j] = 0.9;
  zip_strip(c.sheet, depth, std::vector<Vec3>(n, Vec3(0, 0, -1)));
  CHECK(strip_crossings(c.sheet, dipped, c.hairline, 2).empty());
  for (int j = 0; j < n; ++j) {
    CHECK((c.sheet.feet[j] == c.sheet.outer[j]) == (depth[j] == 0.0));
    if (depth[j] > 0.0) CHECK(c.sheet.mesh.positions[c.sheet.feet[j]] == c.sheet.mesh.positions[c.sheet.outer[j]] - Vec3(0, 0, 0.9));
  }
  const MeshTopology lowered = analyse_topology(c.sheet.mesh);
  CHECK(lowered.is_disk());
  CHECK(lowered.orientation_consistent);
  CHECK(lowered.boundary_loops.size() == 1);
  CHECK(lowered.boundary_loops[0].size() == static_cast<std::size_t>(n));
  // Rebuilt without feet, it is the zipped strip again.
  zip_strip(c.sheet, std::vector<double>(n, 0.0), std::vector<Vec3>(n, Vec3::Zero()));
  CHECK(c.sheet.mesh.positions.size() == c.sheet.piece_vertices + n);
  CHECK(c.sheet.mesh.triangles.size() - c.sheet.strip_begin == static_cast<std::size_t>(2 * n));
}
