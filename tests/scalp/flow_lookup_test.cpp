// The growth field read near the scalp (scalp/flow_lookup.h): exact on a uniform field, the
// Gaussian-weighted vertex mean it stands for within its gathering's error, and the same on a fine
// and a coarse mesh of one surface.
#include <doctest/doctest.h>

#include <cmath>

#include "scalp/flow_lookup.h"
#include "tests/scalp/scalp_meshes.h"

using namespace hairfit;
using hairfit::test::flat_disk;

namespace {

// A field on the plane y = 0 that turns with x: (cos(x/5), 0, sin(x/5)).
DirectionField turning_field(const Mesh& m) {
  DirectionField f;
  for (const Vec3& p : m.positions) f.directions.push_back(Vec3(std::cos(p.x() / 5.0), 0.0, std::sin(p.x() / 5.0)));
  f.magnitude.assign(m.positions.size(), 1.0);
  return f;
}

// The Gaussian-weighted mean over every vertex, as the lookup defines it before gathering.
Vec3 direct_mean(const Mesh& m, const DirectionField& f, const Vec3& p, double radius) {
  Vec3 sum = Vec3::Zero();
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const double d2 = (m.positions[v] - p).squaredNorm();
    if (d2 > radius * radius) continue;
    sum += (std::exp(-d2 / (0.25 * radius * radius)) - std::exp(-4.0)) * f.directions[v];
  }
  sum.y() = 0.0;
  return sum.normalized();
}

}  // namespace

TEST_CASE("flow lookup: a uniform field is read back exactly, with the plane's normal") {
  const Mesh m = flat_disk(30, 10.0, 0.3);
  const std::vector<Vec3> normals(m.positions.size(), Vec3(0, 1, 0));
  DirectionField f;
  f.directions.assign(m.positions.size(), Vec3(0.6, 0.0, 0.8));
  f.magnitude.assign(m.positions.size(), 1.0);
  const FlowLookup lookup(m, normals, f, kFlowLookupRadius);
  for (const Vec3& p : {Vec3(0, 0.3, 0), Vec3(4.1, -0.5, -2.7), Vec3(-7.5, 1.0, 3.3)}) {
    Vec3 n;
    const Vec3 d = lookup.at(p, &n);
    CHECK((d - Vec3(0.6, 0.0, 0.8)).norm() < 1e-12);
    CHECK((n - Vec3(0, 1, 0)).norm() < 1e-12);
  }
  CHECK(lookup.at(Vec3(0, 5.0, 0)) == Vec3::Zero());  // no vertex within the radius
}

TEST_CASE("flow lookup: the Gaussian vertex mean, gathered, and the field itself on a fine and a coarse mesh") {
  const Mesh fine = flat_disk(120, 10.0, 0.3), coarse = flat_disk(12, 10.0, 0.3);
  const std::vector<Vec3> fine_normals(fine.positions.size(), Vec3(0, 1, 0)),
      coarse_normals(coarse.positions.size(), Vec3(0, 1, 0));
  const DirectionField fine_field = turning_field(fine), coarse_field = turning_field(coarse);
  const FlowLookup on_fine(fine, fine_normals, fine_field, kFlowLookupRadius);
  const FlowLookup on_coarse(coarse, coarse_normals, coarse_field, kFlowLookupRadius);
  const double degree = M_PI / 180.0;
  for (double x = -7.0; x <= 7.0; x += 1.75)
    for (double z : {-5.0, 0.0, 4.5}) {
      const Vec3 p(x, 0.2, z);
      INFO("at " << x << ", " << z);
      const Vec3 exact(std::cos(x / 5.0), 0.0, std::sin(x / 5.0));
      // Gathering changes the vertex mean by far less than a degree on the fine mesh.
      CHECK(std::acos(std::min(1.0, on_fine.at(p).dot(direct_mean(fine, fine_field, p, kFlowLookupRadius)))) < 0.2 * degree);
      // Either mesh gives the field at p, to within the average's own smoothing: a degree on the
      // fine mesh, two on the coarse one, whose jittered vertices (0.8 cm apart) weigh unevenly.
      CHECK(std::acos(std::min(1.0, on_fine.at(p).dot(exact))) < degree);
      CHECK(std::acos(std::min(1.0, on_coarse.at(p).dot(exact))) < 2.0 * degree);
    }
}
