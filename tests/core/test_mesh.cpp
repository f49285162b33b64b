#include <doctest/doctest.h>

#include <cmath>

#include "core/mesh.h"

using namespace hairfit;

namespace {

// A regular n×n grid of unit squares in the plane z = 0, two triangles each, counter-clockwise
// seen from +z.
Mesh grid(int n) {
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.emplace_back(i, j, 0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.triangles.emplace_back(a, b, d);
      m.triangles.emplace_back(a, d, c);
    }
  return m;
}

Mesh cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  // Outward-facing quads, each split into two triangles.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.emplace_back(q[0], q[1], q[2]);
    m.triangles.emplace_back(q[0], q[2], q[3]);
  }
  return m;
}

}  // namespace

TEST_CASE("a grid is a disk with one boundary loop of 4n vertices") {
  const MeshTopology t = analyse_topology(grid(5));
  CHECK(t.is_disk());
  CHECK(t.euler_characteristic == 1);
  REQUIRE(t.boundary_loops.size() == 1);
  CHECK(t.boundary_loops[0].size() == 20);
  CHECK(t.orientation_consistent);
  CHECK(surface_area(grid(5)) == doctest::Approx(25.0));
}

TEST_CASE("a cube is closed with Euler characteristic 2") {
  const MeshTopology t = analyse_topology(cube());
  CHECK(t.closed());
  CHECK_FALSE(t.is_disk());
  CHECK(t.euler_characteristic == 2);
  CHECK(t.components == 1);
  CHECK(surface_area(cube()) == doctest::Approx(6.0));
}

TEST_CASE("a hole gives a second boundary loop; a fin gives non-manifold vertices") {
  Mesh holed = grid(3);
  holed.triangles.erase(holed.triangles.begin() + 8, holed.triangles.begin() + 10);  // centre square
  const MeshTopology t = analyse_topology(holed);
  CHECK(t.boundary_loops.size() == 2);
  CHECK_FALSE(t.is_disk());

  Mesh fin = grid(1);
  fin.positions.emplace_back(0, 0, 1);
  fin.triangles.emplace_back(0, 3, 4);  // a third triangle on the diagonal edge 0–3
  const MeshTopology f = analyse_topology(fin);
  CHECK(f.nonmanifold_vertices == std::vector<int>{0, 3});
}

TEST_CASE("a flipped triangle breaks orientation consistency") {
  Mesh m = grid(2);
  std::swap(m.triangles[3][1], m.triangles[3][2]);
  CHECK_FALSE(analyse_topology(m).orientation_consistent);
}

TEST_CASE("winding number: 1 inside a closed mesh, 0 outside, ½ on a flat cap's axis far away") {
  const Mesh c = cube();
  CHECK(winding_number(c, Vec3(0.5, 0.5, 0.5)) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(winding_number(c, Vec3(0.2, 0.9, 0.1)) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(std::fabs(winding_number(c, Vec3(1.5, 0.5, 0.5))) < 1e-12);
  // Seen from just above its centre, a big square subtends almost a hemisphere: w → −½ (facing +z).
  Mesh g = grid(40);
  for (Vec3& p : g.positions) p -= Vec3(20, 20, 0);
  CHECK(winding_number(g, Vec3(0, 0, 1e-3)) == doctest::Approx(-0.5).epsilon(1e-3));
}

TEST_CASE("normals and bounds") {
  const Mesh g = grid(2);
  CHECK(triangle_normal(g, 0).isApprox(Vec3(0, 0, 1)));
  const auto [lo, hi] = bounding_box(g);
  CHECK(lo.isApprox(Vec3(0, 0, 0)));
  CHECK(hi.isApprox(Vec3(2, 2, 0)));
}
