// closed_winding_number (ray crossings) against winding_number (solid angles) on closed meshes,
// at random points, points near the surface and points level with vertices and edges.
#include <doctest/doctest.h>

#include <cmath>

#include "core/mesh.h"
#include "core/random.h"
#include "core/shapes.h"
#include "pipeline/winding.h"

using namespace hairfit;

namespace {

// Two spheres' union is not closed-manifold; a sphere with a smaller one inside, turned inward,
// is: a hollow shell (winding 1 between them, 0 inside the small one and outside).
Mesh shell() {
  Mesh outer = icosphere(3, 2.0, Vec3(0.1, -0.2, 0.05));
  const Mesh inner = icosphere(2, 1.0, Vec3(0.3, 0.0, 0.1));
  const int base = static_cast<int>(outer.positions.size());
  outer.positions.insert(outer.positions.end(), inner.positions.begin(), inner.positions.end());
  for (const Vec3i& t : inner.triangles) outer.triangles.push_back(Vec3i(base + t[0], base + t[2], base + t[1]));
  return outer;
}

Mesh inverted(Mesh m) {
  for (Vec3i& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

}  // namespace

TEST_CASE("closed_winding_number counts what the solid angles sum to, on closed meshes") {
  Random r(21, RandomStage::test, 0);
  int fast = 0, fallback = 0, inside = 0;
  for (const Mesh& mesh : {icosphere(2, 1.5), shell(), inverted(shell())}) {
    for (int n = 0; n < 3000; ++n) {
      Vec3 p(r.uniform(-2.5, 2.5), r.uniform(-2.5, 2.5), r.uniform(-2.5, 2.5));
      if (n % 5 == 1) {  // level with a vertex along y and z: the ray meets vertices and edges
        const Vec3& v = mesh.positions[static_cast<std::size_t>(r.uniform(0, mesh.positions.size()))];
        p.y() = v.y(), p.z() = v.z();
      }
      if (n % 5 == 2) {  // a hair's breadth off a vertex
        const Vec3& v = mesh.positions[static_cast<std::size_t>(r.uniform(0, mesh.positions.size()))];
        p = v + 1e-7 * Vec3(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
      }
      const double slow = winding_number(mesh, p), quick = closed_winding_number(mesh, p);
      if (quick == slow) {
        ++fallback;
      } else {
        CHECK(quick == std::round(quick));
        CHECK(std::fabs(slow - quick) < 1e-6);
        ++fast;
      }
      inside += std::fabs(quick) > 0.5;
    }
  }
  CHECK(fast > 5000);    // the ray decides wherever it passes clear of edges (3 points in 5 here)
  CHECK(fallback > 10);  // and the vertex-level points exercise the fallback
  CHECK(inside > 1000);
}
