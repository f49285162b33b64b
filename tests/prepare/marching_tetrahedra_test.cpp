// Marching tetrahedra against exact answers: a linear field's zero set is its plane to rounding; a
// sphere's is closed, of genus 0, outward, and its volume converges at second order; zero sets of
// two fields whose difference is one-signed never meet.
#include <doctest/doctest.h>

#include <cmath>

#include "prepare/marching_tetrahedra.h"
#include "prepare/surface_checks.h"

using namespace hairfit;

namespace {

template <class F>
ZeroSet extract(const F& f, double h, double half_width) {
  SampleGrid grid;
  grid.spacing = h;
  const int n = static_cast<int>(std::ceil(2.0 * half_width / h)) + 1;
  grid.dims = Vec3i(n, n, n);
  grid.origin = Vec3::Constant(-half_width) + Vec3(0.0123, -0.0071, 0.0037);  // off the symmetry planes
  std::vector<double> values(grid.nodes());
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) values[grid.node(i, j, k)] = f(grid.position(i, j, k));
  return marching_tetrahedra(grid, values);
}

double enclosed_volume(const Mesh& mesh) {
  double v = 0.0;
  for (const Vec3i& t : mesh.triangles) v += mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]]));
  return v / 6.0;
}

}  // namespace

TEST_CASE("a linear field's zero set is its plane, facing up the gradient") {
  const Vec3 normal = Vec3(0.3, -0.5, 0.81).normalized();
  const double offset = 0.17;
  const ZeroSet z = extract([&](const Vec3& p) { return normal.dot(p) - offset; }, 0.1, 1.0);
  REQUIRE(!z.mesh.triangles.empty());
  double worst = 0.0;
  for (const Vec3& p : z.mesh.positions) worst = std::max(worst, std::abs(normal.dot(p) - offset));
  CHECK(worst < 1e-12);
  for (int t = 0; t < static_cast<int>(z.mesh.triangles.size()); ++t)
    if (triangle_area(z.mesh, t) > 1e-12) CHECK(triangle_normal(z.mesh, t).dot(normal) > 1.0 - 1e-9);
  // Each vertex lies where its edge says, so any per-node quantity interpolates there.
  const SampleGrid grid{Vec3::Constant(-1.0) + Vec3(0.0123, -0.0071, 0.0037), 0.1, Vec3i(21, 21, 21)};
  for (std::size_t v = 0; v < z.at.size(); ++v) {
    const EdgePoint& e = z.at[v];
    const Vec3 expected = (1.0 - e.t) * grid.position(e.a) + e.t * grid.position(e.b);
    CHECK((expected - z.mesh.positions[v]).norm() < 1e-12);
  }
  // A disk's worth of topology: one part, one boundary loop where the plane leaves the grid.
  const MeshTopology topology = analyse_topology(z.mesh);
  CHECK(topology.is_disk());
  CHECK(topology.orientation_consistent);
}

TEST_CASE("a sphere's zero set is closed, outward, and its volume converges at second order") {
  const double r = 0.8;
  const auto sphere = [&](const Vec3& p) { return p.norm() - r; };
  const double exact = 4.0 / 3.0 * M_PI * r * r * r;
  double previous_error = 0.0;
  for (double h : {0.2, 0.1, 0.05}) {
    INFO("h = " << h);
    const ZeroSet z = extract(sphere, h, 1.0);
    const MeshTopology topology = analyse_topology(z.mesh);
    CHECK(topology.closed());
    CHECK(topology.components == 1);
    CHECK(topology.euler_characteristic == 2);
    CHECK(topology.orientation_consistent);
    CHECK(self_intersections(z.mesh).empty());
    // The interpolant is exact at the nodes and the sphere is convex: every vertex lies inside it,
    // within h²/(2r) of it (the chord error along a grid edge).
    for (const Vec3& p : z.mesh.positions) {
      CHECK(p.norm() <= r + 1e-12);
      CHECK(p.norm() >= r - h * h / (2.0 * r) - 1e-12);
    }
    const double error = exact - enclosed_volume(z.mesh);
    CHECK(error > 0.0);  // outward and inscribed
    if (previous_error > 0.0) {
      MESSAGE("volume error " << error << ", ratio to h·2: " << previous_error / error);
      CHECK(previous_error / error == doctest::Approx(4.0).epsilon(0.15));
    }
    previous_error = error;
  }
}

TEST_CASE("zero sets of two fields whose difference is one-signed do not meet") {
  // f and f − g with g > 0 everywhere: nested surfaces, here a sphere and a bumpy one inside it.
  const auto f = [](const Vec3& p) { return p.norm() - 0.8; };
  const auto g = [](const Vec3& p) { return 0.02 + 0.05 * (1.0 + std::sin(9.0 * p.x()) * std::cos(7.0 * p.y())); };
  const ZeroSet outer = extract(f, 0.05, 1.0);
  const ZeroSet inner = extract([&](const Vec3& p) { return f(p) + g(p); }, 0.05, 1.0);
  Mesh both = outer.mesh;
  const int offset = static_cast<int>(both.positions.size());
  for (const Vec3& p : inner.mesh.positions) both.positions.push_back(p);
  for (const Vec3i& t : inner.mesh.triangles) both.triangles.emplace_back(t[0] + offset, t[1] + offset, t[2] + offset);
  CHECK(self_intersections(both).empty());
  for (const Vec3& p : inner.mesh.positions) CHECK(winding_number(outer.mesh, p) > 0.5);
}
