// The direction field against exact answers: constant fields on flat patches, parallel fields on a
// developable one, Poincaré–Hopf on the sphere, and the guidance recovered far from a change.
#include <doctest/doctest.h>

#include <cmath>

#include "core/random.h"
#include "core/shapes.h"
#include "scalp/direction_field.h"

using namespace hairfit;

namespace {

// An n × n grid of squares over [0, size]², each split along a random diagonal, its interior
// vertices jittered: irregular but flat.
Mesh jittered_grid(int n, double size) {
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      Random r(7, RandomStage::test, j * (n + 1) + i);
      const bool interior = i > 0 && j > 0 && i < n && j < n;
      const double jx = interior ? r.uniform(-0.3, 0.3) : 0.0, jy = interior ? r.uniform(-0.3, 0.3) : 0.0;
      m.positions.push_back(Vec3((i + jx) * size / n, (j + jy) * size / n, 0.0));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      if (Random(8, RandomStage::test, j * n + i).uniform() < 0.5) {
        m.triangles.push_back(Vec3i(a, b, c));
        m.triangles.push_back(Vec3i(a, c, d));
      } else {
        m.triangles.push_back(Vec3i(a, b, d));
        m.triangles.push_back(Vec3i(b, c, d));
      }
    }
  return m;
}

// A cylinder of radius R about z, open at both ends.
Mesh cylinder(int around, int along, double radius, double height, std::vector<Vec3>& normals) {
  Mesh m;
  for (int j = 0; j <= along; ++j)
    for (int i = 0; i < around; ++i) {
      const double a = 2.0 * M_PI * i / around;
      m.positions.push_back(Vec3(radius * std::cos(a), radius * std::sin(a), height * j / along));
      normals.push_back(Vec3(std::cos(a), std::sin(a), 0.0));
    }
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around;
      m.triangles.push_back(Vec3i(a, b, b + around));
      m.triangles.push_back(Vec3i(a, b + around, a + around));
    }
  return m;
}

}  // namespace

TEST_CASE("on a flat irregular patch a constant guidance on a few vertices gives that constant everywhere") {
  const Mesh m = jittered_grid(12, 6.0);
  const std::vector<Vec3> normals(m.positions.size(), Vec3::UnitZ());
  const Vec3 d = Vec3(0.6, 0.8, 0.0);
  std::vector<Vec3> guidance(m.positions.size(), Vec3::Zero());
  for (std::size_t i = 0; i < guidance.size(); i += 17) guidance[i] = 0.5 * d;  // confidence ½
  const DirectionField f = smoothest_aligned_field(m, normals, guidance);
  for (const Vec3& v : f.directions) CHECK((v - d).norm() < 1e-9);
  for (int index : field_indices(m, normals, f)) CHECK(index == 0);
}

TEST_CASE("on a cylinder the axial and the circumferential fields are parallel, so both are reproduced exactly") {
  std::vector<Vec3> normals;
  const Mesh m = cylinder(40, 10, 3.0, 8.0, normals);
  std::vector<Vec3> axial(m.positions.size(), Vec3::Zero()), around(m.positions.size(), Vec3::Zero());
  axial[5] = Vec3::UnitZ();
  around[5] = normals[5].cross(Vec3::UnitZ()) * -1.0;  // the tangent turning with the angle
  const DirectionField fa = smoothest_aligned_field(m, normals, axial);
  const DirectionField fc = smoothest_aligned_field(m, normals, around);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    CHECK((fa.directions[i] - Vec3::UnitZ()).norm() < 1e-8);
    CHECK((fc.directions[i] - Vec3::UnitZ().cross(normals[i])).norm() < 1e-8);
  }
}

TEST_CASE("on a sphere the indices of any field sum to its Euler characteristic, 2") {
  const Mesh m = icosphere(3, 5.0);
  std::vector<Vec3> normals;
  for (const Vec3& p : m.positions) normals.push_back(p.normalized());
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<Vec3> guidance(m.positions.size(), Vec3::Zero());
    for (std::size_t i = 0; i < guidance.size(); ++i) {
      Random r(trial, RandomStage::test, i);
      guidance[i] = trial == 0 ? Vec3(0.05, 0.02, -1) : Vec3(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
    }
    DirectionFieldOptions o;
    o.smoothing = 1.0 + trial;
    const DirectionField f = smoothest_aligned_field(m, normals, guidance, o);
    int total = 0, singular = 0;
    for (int index : field_indices(m, normals, f)) {
      total += index;
      singular += index != 0;
    }
    CHECK(total == 2);
    if (trial == 0) CHECK(singular == 2);  // "down" (tilted off the vertices at the poles): a source at the top, a sink below
  }
}

TEST_CASE("far from where the guidance turns, the field is the guidance; near it, it turns over about ℓ") {
  const Mesh m = jittered_grid(40, 20.0);
  const std::vector<Vec3> normals(m.positions.size(), Vec3::UnitZ());
  std::vector<Vec3> guidance;
  for (const Vec3& p : m.positions) guidance.push_back(p.x() < 10.0 ? Vec3::UnitX() : Vec3::UnitY());
  DirectionFieldOptions o;
  o.smoothing = 1.0;
  const DirectionField f = smoothest_aligned_field(m, normals, guidance, o);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const double x = m.positions[i].x();
    const Vec3& v = f.directions[i];
    if (x < 4.0) CHECK(v.dot(Vec3::UnitX()) > std::cos(M_PI / 180.0));
    if (x > 16.0) CHECK(v.dot(Vec3::UnitY()) > std::cos(M_PI / 180.0));
    if (std::fabs(x - 10.0) < 0.25) CHECK(std::fabs(std::atan2(v.y(), v.x()) - M_PI / 4) < 0.3);  // halfway, up to the jitter
    CHECK(std::fabs(v.norm() - 1.0) < 1e-12);
  }
}

TEST_CASE("bad input is refused") {
  const Mesh m = jittered_grid(2, 1.0);
  const std::vector<Vec3> normals(m.positions.size(), Vec3::UnitZ());
  CHECK_THROWS_AS(smoothest_aligned_field(m, normals, {}), std::invalid_argument);
  DirectionFieldOptions o;
  o.smoothing = 0.0;
  CHECK_THROWS_AS(smoothest_aligned_field(m, normals, normals, o), std::invalid_argument);
}
