// exact_layer_run (pipeline/stage_options.h): how far a straight hair stays in the layer between a
// flat scalp and a hull over it, against the distances the geometry gives.
#include <doctest/doctest.h>

#include <cmath>

#include "pipeline/stage_options.h"

using namespace hairfit;

namespace {

// The square [−1, 1]² at height z, facing +z (`up`) or −z, as two triangles.
void add_square(Mesh& m, double z, bool up) {
  const int o = static_cast<int>(m.positions.size());
  for (const auto& [x, y] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}) m.positions.emplace_back(x, y, z);
  if (up) {
    m.triangles.emplace_back(o, o + 1, o + 2);
    m.triangles.emplace_back(o, o + 2, o + 3);
  } else {
    m.triangles.emplace_back(o, o + 2, o + 1);
    m.triangles.emplace_back(o, o + 3, o + 2);
  }
}

// The four walls of the box [−1, 1]² × [0, height], facing out.
void add_walls(Mesh& m, double height) {
  const Vec3 c[4] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  for (int k = 0; k < 4; ++k) {
    const int o = static_cast<int>(m.positions.size());
    const Vec3 a = c[k], b = c[(k + 1) % 4];
    m.positions.push_back(a);
    m.positions.push_back(b);
    m.positions.push_back(b + Vec3(0, 0, height));
    m.positions.push_back(a + Vec3(0, 0, height));
    m.triangles.emplace_back(o, o + 1, o + 2);
    m.triangles.emplace_back(o, o + 2, o + 3);
  }
}

Vec3 rising(double degrees) { return Vec3(std::cos(degrees * M_PI / 180.0), 0.0, std::sin(degrees * M_PI / 180.0)); }

}  // namespace

TEST_CASE("layer run: a closed layer ends a straight hair where it crosses the hull, exactly") {
  const double T = 0.2;
  Mesh scalp, hull;
  add_square(scalp, 0.0, true);
  add_square(hull, T, true);
  add_walls(hull, T);
  const auto run = exact_layer_run(hull, scalp, /*hull_closed=*/false);
  const Vec3 root(0.0, 0.3, 0.0);
  for (double degrees : {5.0, 10.0, 30.0, 60.0, 90.0}) {
    const Vec3 d = rising(degrees);
    const double s = std::sin(degrees * M_PI / 180.0), c = std::cos(degrees * M_PI / 180.0);
    const double to_top = T / s, to_wall = c > 1e-12 ? 1.0 / c : INFINITY;
    INFO(degrees << "° from the scalp");
    CHECK(run(root, d, 5.0) == doctest::Approx(std::min(to_top, to_wall)).epsilon(1e-12));
    CHECK(run(root, d, 0.05) == 0.05);  // within reach of neither
  }
  // Into the head: the first sample lies behind the scalp.
  CHECK(run(root, Vec3(0.6, 0.0, -0.8), 1.0) == 0.0);
}

TEST_CASE("layer run: where the hull parts from the scalp at the rim, the hair leaves between the rims") {
  // A thin slab open at its sides: no triangle is crossed, yet past the rims (x = 1) the layer's
  // winding number falls to 0; within a slab thickness of them it is ½.
  const double T = 0.05;
  Mesh scalp, hull;
  add_square(scalp, 0.0, true);
  add_square(hull, T, true);
  const auto run = exact_layer_run(hull, scalp, /*hull_closed=*/false);
  const double reach = 2.0, step = reach / kLayerRunSamples;
  const Vec3 root(0.0, 0.3, 0.0), d = rising(1.0);  // rises 0.017 over the way to the rim: stays under the hull
  const double to_rim = 1.0 / std::cos(M_PI / 180.0);
  const double r = run(root, d, reach);
  CHECK(r < reach);
  CHECK(r >= to_rim - 2 * T - step);
  CHECK(r <= to_rim + 2 * T);
  CHECK(std::fmod(r, step) == doctest::Approx(0.0));  // the last sample inside
}

TEST_CASE("layer run: under a closed hull that encloses the head, the hull's top ends the hair, and the head does at the root") {
  // The hull: the closed box [−1, 1]² × [−1, 1]; the scalp: a pyramid over the square z = 0, apex
  // at height h, facing up and out, whose floor (closed_head) closes the head under it.
  const double h = 0.5;
  Mesh scalp, hull;
  scalp.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, h}};
  for (int k = 0; k < 4; ++k) scalp.triangles.emplace_back(k, (k + 1) % 4, 4);
  add_square(hull, 1.0, true);
  add_square(hull, -1.0, false);
  add_walls(hull, 1.0);
  for (Vec3& p : hull.positions)  // the walls run down to the bottom
    if (p.z() == 0.0) p.z() = -1.0;
  const auto run = exact_layer_run(hull, scalp, /*hull_closed=*/true);
  const Vec3 root(0.0, -0.5, 0.5 * h);  // on the face over y = −1
  CHECK(run(root, Vec3(0, 0, 1), 5.0) == doctest::Approx(1.0 - 0.5 * h).epsilon(1e-12));
  CHECK(run(root, Vec3(0, 0, 1), 0.1) == 0.1);
  // Into the head, inside the hull all the way and crossing nothing past the root: the first
  // sample lies in the head.
  CHECK(run(root, Vec3(0.0, 0.6, -0.8), 1.0) == 0.0);
}
