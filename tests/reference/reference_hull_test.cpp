// The hull voxelised from reference hair: closed, the hair and the scalp within it, the dilation
// where the hull lies, and the hollow of a thick strand filled.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/shapes.h"
#include "reference/reference_hull.h"

using namespace hairfit;

namespace {

// A 10 cm square card in the plane z = 0, and a small scalp triangle 20 cm below it.
Mesh square_card() {
  Mesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(10, 10, 0), Vec3(0, 10, 0)};
  m.triangles = {Vec3i(0, 1, 2), Vec3i(0, 2, 3)};
  return m;
}

Mesh small_scalp() {
  Mesh m;
  m.positions = {Vec3(0, 0, -20), Vec3(2, 0, -20), Vec3(0, 2, -20)};
  m.triangles = {Vec3i(0, 1, 2)};
  return m;
}

}  // namespace

TEST_CASE("a card's hull: closed, the card and the scalp inside, the surface a dilation away") {
  ReferenceHullOptions o;
  o.voxel = 0.5;
  o.dilation = 1.0;
  const ReferenceHull hull = reference_hull(square_card(), small_scalp(), o);
  const MeshTopology topology = analyse_topology(hull.mesh);
  CHECK(topology.closed());
  CHECK(topology.components == 2);  // around the card, around the scalp
  CHECK(hull.filled_nodes == 0);
  CHECK(winding_number(hull.mesh, Vec3(5, 5, 0)) == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(winding_number(hull.mesh, Vec3(5, 5, 0.7)) == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(winding_number(hull.mesh, Vec3(5, 5, -1.4)) == doctest::Approx(0.0).epsilon(1e-9));
  CHECK(winding_number(hull.mesh, Vec3(11.4, 5, 0)) == doctest::Approx(0.0).epsilon(1e-9));
  CHECK(winding_number(hull.mesh, Vec3(0.5, 0.5, -20)) == doctest::Approx(1.0).epsilon(1e-9));
  // The distance to the card is convex, so its linear interpolant along a grid edge never reads
  // below it: every vertex lies at most the dilation from the card, exactly at it over the card's
  // flat sides (where the distance is linear), a little nearer around its rim.
  for (const Vec3& p : hull.mesh.positions) {
    if (p.z() < -10) continue;
    const Vec3 nearest(std::clamp(p.x(), 0.0, 10.0), std::clamp(p.y(), 0.0, 10.0), 0.0);
    const double d = (p - nearest).norm();
    CHECK(d <= 1.0 + 1e-6);
    CHECK(d > 0.75);
    if (nearest.x() > 0 && nearest.x() < 10 && nearest.y() > 0 && nearest.y() < 10) CHECK(std::abs(d - 1.0) < 1e-6);
  }
}

TEST_CASE("a hollow strand's hull is solid: the enclosed nodes are filled, no inner surface is left") {
  ReferenceHullOptions o;
  o.voxel = 0.5;
  o.dilation = 1.0;
  const ReferenceHull hull = reference_hull(icosphere(3, 5.0), small_scalp(), o);
  CHECK(hull.filled_nodes > 0);
  CHECK(analyse_topology(hull.mesh).components == 2);  // no surface inside the sphere
  CHECK(winding_number(hull.mesh, Vec3::Zero()) == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(winding_number(hull.mesh, Vec3(6.8, 0, 0)) == doctest::Approx(0.0).epsilon(1e-9));
}

TEST_CASE("a hull needs a positive voxel and dilation") {
  ReferenceHullOptions o;
  o.dilation = 0.0;
  CHECK_THROWS_AS(reference_hull(square_card(), small_scalp(), o), std::invalid_argument);
}
