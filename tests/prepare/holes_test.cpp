// Filling a surface's holes (prepare/holes.h) on a level set with a hole of known size: the zero
// set of a plane's field clipped where a "thickness" falls below its clip level, as the level-set
// scalp is (scalp_level_set.cpp), here on a square with a round hole in it.
#include <doctest/doctest.h>

#include <cmath>

#include "prepare/holes.h"
#include "prepare/level_set_clip.h"
#include "prepare/marching_tetrahedra.h"

using namespace hairfit;

namespace {

// The plane z = 0.011 over the grid [−1, 1]³ (h = 0.05), kept where the square |x|, |y| ≤ 0.9
// holds it and outside the circle of `radius` about (0.1, −0.05).
Mesh square_with_round_hole(double radius) {
  SampleGrid grid;
  grid.spacing = 0.05;
  grid.dims = Vec3i(41, 41, 41);
  grid.origin = Vec3::Constant(-1.0);
  std::vector<double> values(grid.nodes());
  for (int k = 0; k < 41; ++k)
    for (int j = 0; j < 41; ++j)
      for (int i = 0; i < 41; ++i) values[grid.node(i, j, k)] = grid.position(i, j, k).z() - 0.011;
  const ZeroSet zero = marching_tetrahedra(grid, values);
  SelectionField keep;
  for (const Vec3& p : zero.mesh.positions) {
    const double in_square = 0.9 - std::max(std::abs(p.x()), std::abs(p.y()));
    const double off_hole = (p.head<2>() - Eigen::Vector2d(0.1, -0.05)).norm() - radius;
    keep.values.push_back(std::min(in_square, off_hole));
  }
  ClipOptions exact;
  exact.snap = 0.0;
  return clip_at_level_set(zero.mesh, keep, exact).mesh;
}

// The area a closed loop encloses in the plane z = const (shoelace).
double enclosed_area(const Mesh& mesh, const std::vector<int>& loop) {
  double twice = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec3 &a = mesh.positions[loop[i]], &b = mesh.positions[loop[(i + 1) % loop.size()]];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return std::abs(0.5 * twice);
}

}  // namespace

TEST_CASE("a level set with a round hole is filled into a disk: one loop, Euler characteristic 1, the hole's area added") {
  const double radius = 0.2;
  Mesh mesh = square_with_round_hole(radius);
  const MeshTopology before = analyse_topology(mesh);
  REQUIRE(before.boundary_loops.size() == 2);
  CHECK(before.euler_characteristic == 0);
  const double area_before = surface_area(mesh);
  const FilledHoles holes = fill_holes(mesh, before, 0.25);
  CHECK(holes.filled == 1);
  CHECK(holes.open == 0);
  CHECK(holes.rim_length == doctest::Approx(4 * 1.8).epsilon(0.01));  // the corners cut across a cell
  CHECK(holes.longest_filled == doctest::Approx(2 * M_PI * radius).epsilon(0.01));
  REQUIRE(holes.loops.size() == 1);
  CHECK(holes.centres[0] >= 0);
  const MeshTopology after = analyse_topology(mesh);
  CHECK(after.is_disk());
  CHECK(after.euler_characteristic == 1);
  CHECK(after.boundary_loops.size() == 1);
  CHECK(after.orientation_consistent);
  // The fan covers the hole's polygon exactly; the polygon is the circle to second order in h.
  const double hole = enclosed_area(mesh, holes.loops[0]);
  CHECK(surface_area(mesh) - area_before == doctest::Approx(hole).epsilon(1e-12));
  CHECK(hole == doctest::Approx(M_PI * radius * radius).epsilon(0.01));
  CHECK(surface_area(mesh) == doctest::Approx(1.8 * 1.8).epsilon(1e-3));
  // The fan's centre is the loop's centroid: on the plane, inside the circle.
  const Vec3& centre = mesh.positions[holes.centres[0]];
  CHECK(centre.z() == doctest::Approx(0.011).epsilon(1e-12));
  CHECK((centre.head<2>() - Eigen::Vector2d(0.1, -0.05)).norm() < 0.01);
}

TEST_CASE("a hole longer than the share of the rim is left open and reported") {
  Mesh mesh = square_with_round_hole(0.35);  // 2.2 against a rim of 7.2: 31 %
  const std::size_t triangles = mesh.triangles.size();
  const FilledHoles holes = fill_holes(mesh, analyse_topology(mesh), 0.25);
  CHECK(holes.filled == 0);
  CHECK(holes.open == 1);
  CHECK(holes.longest_open == doctest::Approx(2 * M_PI * 0.35).epsilon(0.01));
  CHECK((holes.open_at.head<2>() - Eigen::Vector2d(0.1, -0.05)).norm() < 0.01);
  CHECK(mesh.triangles.size() == triangles);
  CHECK(fill_holes(mesh, analyse_topology(mesh), 0.35).filled == 1);
}
