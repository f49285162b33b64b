// The geometric primitives of `hairfit prepare` against answers known by construction.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>

#include "core/shapes.h"
#include "io/obj_mesh.h"
#include "prepare/surface_checks.h"
#include "prepare/weld.h"
#include "../support/scratch.h"

using namespace hairfit;

TEST_CASE("triangle pairs: crossing, apart, touching at a point, coplanar overlapping and coplanar apart") {
  const Vec3 a0(0, 0, 0), a1(2, 0, 0), a2(0, 2, 0);
  // A vertical triangle piercing the first through its interior.
  CHECK(triangles_intersect(a0, a1, a2, Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), Vec3(0.6, 0.4, 1)));
  // The same, shifted beyond the hypotenuse x + y = 2: it crosses the plane but not the triangle.
  CHECK_FALSE(triangles_intersect(a0, a1, a2, Vec3(1.5, 1.5, -1), Vec3(1.5, 1.5, 1), Vec3(1.6, 1.4, 1)));
  // Entirely above the plane.
  CHECK_FALSE(triangles_intersect(a0, a1, a2, Vec3(0, 0, 0.1), Vec3(1, 0, 0.2), Vec3(0, 1, 0.3)));
  // Touching the plane in one vertex that lies inside the first triangle: they share that point.
  CHECK(triangles_intersect(a0, a1, a2, Vec3(0.5, 0.5, 0), Vec3(1, 0.5, 1), Vec3(0.5, 1, 1)));
  // Coplanar: overlapping, one inside the other, and apart.
  CHECK(triangles_intersect(a0, a1, a2, Vec3(1, 1, 0), Vec3(3, 1, 0), Vec3(1, 3, 0)));
  CHECK(triangles_intersect(a0, a1, a2, Vec3(0.2, 0.2, 0), Vec3(0.5, 0.2, 0), Vec3(0.2, 0.5, 0)));
  CHECK_FALSE(triangles_intersect(a0, a1, a2, Vec3(3, 3, 0), Vec3(4, 3, 0), Vec3(3, 4, 0)));
}

TEST_CASE("self-intersections: none on a sphere, found where two spheres interpenetrate") {
  const Mesh sphere = icosphere(3, 2.0);
  CHECK(self_intersections(sphere).empty());
  Mesh two = sphere;
  const Mesh other = icosphere(3, 2.0, Vec3(1.0, 0.3, 0.2));
  const int offset = static_cast<int>(two.positions.size());
  two.positions.insert(two.positions.end(), other.positions.begin(), other.positions.end());
  for (const Vec3i& t : other.triangles) two.triangles.push_back(t + Vec3i::Constant(offset));
  const auto pairs = self_intersections(two, 1000000);
  REQUIRE_FALSE(pairs.empty());
  const int first = static_cast<int>(sphere.triangles.size());
  for (const auto& [s, t] : pairs) CHECK((s < first) != (t < first));  // one triangle of each sphere
  // Apart by more than their diameters: none.
  Mesh apart = sphere;
  for (const Vec3i& t : other.triangles) apart.triangles.push_back(t + Vec3i::Constant(offset));
  apart.positions.insert(apart.positions.end(), other.positions.begin(), other.positions.end());
  for (int i = offset; i < static_cast<int>(apart.positions.size()); ++i) apart.positions[i] += Vec3(10, 0, 0);
  CHECK(self_intersections(apart).empty());
}

TEST_CASE("mean curvature of a sphere of radius 5 is 1/5") {
  const Mesh sphere = icosphere(4, 5.0);
  for (double h : mean_curvature(sphere)) CHECK(h == doctest::Approx(0.2).epsilon(0.03));
}

TEST_CASE("inward triangles: none on an outward sphere about its centre, all when turned inside out") {
  Mesh sphere = icosphere(2, 1.0, Vec3(3, 1, 2));
  CHECK(inward_triangles(sphere, Vec3(3, 1, 2)).empty());
  for (Vec3i& t : sphere.triangles) std::swap(t[1], t[2]);
  CHECK(inward_triangles(sphere, Vec3(3, 1, 2)).size() == sphere.triangles.size());
}

TEST_CASE("welding merges vertices repeated within the tolerance and nothing farther") {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1 + 1e-7, 1e-7, 0}, {1, 1, 0}, {1e-7, 1, 0}, {5, 5, 5}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 1, 6}};
  const Welded w = weld_vertices(m, 1e-6);
  CHECK(w.merged_vertices == 2);
  CHECK(w.mesh.positions.size() == 5);
  CHECK(w.old_to_new[3] == w.old_to_new[1]);
  CHECK(w.old_to_new[5] == w.old_to_new[2]);
  CHECK(w.mesh.triangles.size() == 3);
  // A tolerance below the offsets merges nothing.
  CHECK(weld_vertices(m, 1e-8).merged_vertices == 0);
}

TEST_CASE("OBJ vertex colours are read when every vertex has them and written back") {
  const std::filesystem::path dir = hairfit::testing::fresh_scratch_folder("prepare-colours");
  Mesh m = icosphere(1);
  std::vector<Vec3> colours;
  for (std::size_t i = 0; i < m.positions.size(); ++i) colours.emplace_back(i % 2, 0.25, 0.5);
  write_obj_mesh(dir / "coloured.obj", m, {}, colours);
  const LoadedMesh back = load_obj_mesh(dir / "coloured.obj");
  REQUIRE(back.colors.size() == m.positions.size());
  for (std::size_t i = 0; i < colours.size(); ++i) CHECK((back.colors[i] - colours[i]).norm() < 1e-6);
  write_obj_mesh(dir / "plain.obj", m);
  CHECK(load_obj_mesh(dir / "plain.obj").colors.empty());
  std::filesystem::remove_all(dir);
}
