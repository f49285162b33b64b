// The geometric primitives of `hairfit prepare` against answers known by construction.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>

#include "core/fast_winding.h"
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

namespace {

// A prism along y (0 to 1) over the polygon, in (x, z), P0 (−1, 0), P1 (−w, 0), P2 (0, 0),
// P3 (−0.005, 0.025), P4 (1, 0.025), P5 (1, 1), P6 (−1, 1), outward: a layer whose floor is a
// step. The riser P2–P3 leans over the strip P1–P2 of width w = 1e-4 (an inside angle of 78.7° at
// P2), as the level-set scalp's strip leans where the hairline zigzags. `floor` gets the faces over
// P0…P4 turned to face into the prism, as a scalp faces the hair layer; `sliver` their indices in
// `floor` over P1–P2.
Mesh stepped_layer(Mesh& floor, std::vector<int>& sliver) {
  const double w = 1e-4;
  const std::vector<Vec2> polygon{{-1, 0}, {-w, 0}, {0, 0}, {-0.005, 0.025}, {1, 0.025}, {1, 1}, {-1, 1}};
  const int n = static_cast<int>(polygon.size());
  Mesh solid;
  for (double y : {0.0, 1.0})
    for (const Vec2& p : polygon) solid.positions.emplace_back(p.x(), y, p.y());
  // Each side a quad; the caps fans from (−0.5, 0.5), which sees every corner.
  for (int k = 0; k < n; ++k) {
    const int a = k, b = (k + 1) % n;
    solid.triangles.emplace_back(a, b + n, b);
    solid.triangles.emplace_back(a, a + n, b + n);
  }
  for (int cap = 0; cap < 2; ++cap) {
    const int centre = static_cast<int>(solid.positions.size());
    solid.positions.emplace_back(-0.5, cap, 0.5);
    for (int k = 0; k < n; ++k) {
      const int a = k + cap * n, b = (k + 1) % n + cap * n;
      solid.triangles.push_back(cap == 0 ? Vec3i(centre, a, b) : Vec3i(centre, b, a));
    }
  }
  REQUIRE(winding_number(solid, Vec3(-0.5, 0.5, 0.5)) == doctest::Approx(1.0));
  floor.positions = solid.positions;
  for (int k = 0; k < 4; ++k)
    for (int half = 0; half < 2; ++half) {
      const Vec3i& t = solid.triangles[2 * k + half];
      if (k == 1) sliver.push_back(static_cast<int>(floor.triangles.size()));
      floor.triangles.emplace_back(t[0], t[2], t[1]);
    }
  return solid;
}

}  // namespace

TEST_CASE("facing: a sliver in a concave step faces its layer, judged at a step shorter than its width") {
  Mesh floor;
  std::vector<int> sliver;
  const Mesh solid = stepped_layer(floor, sliver);
  const FastWindingNumber layer(solid, 2.0);
  // A fixed step of kFacingStep in front of the sliver's centroids crosses the leaning riser and
  // lands under the upper floor, outside the layer: the fixed step would list both (the dressed
  // scan-like bust's level-set scalp at 0.5 cm was refused so).
  REQUIRE(sliver.size() == 2);
  for (int t : sliver) {
    CHECK(winding_number(solid, triangle_centroid(floor, t) + kFacingStep * triangle_normal(floor, t)) < 0.5);
    CHECK(winding_number(solid, triangle_centroid(floor, t) + 1e-6 * triangle_normal(floor, t)) > 0.5);
  }
  CHECK(facing_out_of(floor, layer).empty());
  CHECK(facing_out_of(floor, layer, 3).empty());
  // A triangle turned over (in the floor only: the layer stays closed) and one without area are
  // listed, and only they.
  Mesh wrong = floor;
  std::swap(wrong.triangles[6][1], wrong.triangles[6][2]);
  wrong.triangles.emplace_back(0, 1, 2);  // P0, P1, P2 on one line
  CHECK(facing_out_of(wrong, layer) == std::vector<int>{6, static_cast<int>(wrong.triangles.size()) - 1});
}
