// Growth directions toward the thicker hair layer (hair.tilt_toward = "thicker"): the formula and
// its fallbacks, then roots on a spherical cap under a shell whose thickness falls linearly with
// the polar angle, where the thickness gradient along the scalp is known: toward the pole.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "core/shapes.h"
#include "field/distance_field.h"
#include "pipeline/stage_options.h"
#include "scalp/roots.h"
#include "tests/scalp/scalp_meshes.h"

using namespace hairfit;

namespace {

double degrees_between(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

Vec3 tilted_by(const Vec3& normal, const Vec3& tangent, double degrees) {
  const double a = degrees * M_PI / 180.0;
  return std::cos(a) * normal + std::sin(a) * tangent;
}

}  // namespace

TEST_CASE("thicker: the normal tilts up the tangential thickness gradient, blends with down where flat") {
  const Vec3 n(0, 1, 0), down(0, -1, 0), front(0, 0, 1);  // at the crown: toward down is −front
  const Vec3 x(1, 0, 0);
  // Steep: the gradient's normal part is ignored, the tilt goes along its tangential part.
  for (double tilt : {0.0, 40.0, 85.0, 90.0}) {
    const Vec3 d = growth_direction_toward_thicker(n, Vec3(0.5, 0.3, 0), down, front, tilt);
    CHECK(d.norm() == doctest::Approx(1.0));
    CHECK((d - tilted_by(n, x, tilt)).norm() < 1e-12);
  }
  // Half the flat-layer slope: halfway between +x (the gradient) and −z (toward down here).
  const Vec3 half = growth_direction_toward_thicker(n, 0.5 * kFlatLayerGradient * x, down, front, 90.0);
  CHECK((half - Vec3(1, 0, -1).normalized()).norm() < 1e-12);
  // No gradient, or a NaN one (outside a field): exactly the tilt toward down.
  for (const Vec3& g : {Vec3(0, 0, 0), Vec3(0, 2, 0), Vec3(NAN, 0, 0)}) {
    const Vec3 d = growth_direction_toward_thicker(n, g, down, front, 60.0);
    CHECK(d.allFinite());
    CHECK((d - growth_direction(n, down, front, 60.0)).norm() < 1e-12);
  }
  // The two halves cancelling (gradient opposite to toward-down at half the flat slope): the
  // gradient decides.
  const Vec3 tie = growth_direction_toward_thicker(n, Vec3(0, 0, 0.5 * kFlatLayerGradient), down, front, 90.0);
  CHECK((tie - Vec3(0, 0, 1)).norm() < 1e-12);
}

TEST_CASE("thicker: roots under a shell thinning away from the pole tilt toward the pole, as its gradient says") {
  // Scalp: the cap θ ≤ 60° of the sphere of radius R about the origin, pole +y. Hair volume: the
  // shell between the star surface r = R + t(θ), t(θ) = 3 − 1.6·θ cm, and a floor sphere 4 cm
  // down (deeper than the layer is thick, so the depth at a root is its distance to the outer
  // surface). By symmetry that depth's tangential gradient points along −e_θ, toward the pole;
  // toward down it is +e_θ, away from it.
  constexpr double R = 8.0, kCap = M_PI / 3;
  auto layer = [](double theta) { return 3.0 - 1.6 * theta; };
  const Mesh cap = test::ring_disk(
      24,
      [&](double r, double phi) {
        const double theta = r * kCap;
        return Vec3(R * std::sin(theta) * std::cos(phi), R * std::cos(theta), R * std::sin(theta) * std::sin(phi));
      },
      [](const Vec3& p) { return p; });
  Mesh volume = icosphere(5, 1.0);
  for (Vec3& p : volume.positions) p *= R + layer(std::acos(std::clamp(p.y(), -1.0, 1.0)));
  const Mesh floor = icosphere(4, R - 4.0);
  const int offset = static_cast<int>(volume.positions.size());
  volume.positions.insert(volume.positions.end(), floor.positions.begin(), floor.positions.end());
  for (const Vec3i& t : floor.triangles) volume.triangles.emplace_back(t[0] + offset, t[2] + offset, t[1] + offset);
  FieldSpec spec;
  spec.voxel = 0.2;
  spec.band = 16.0;  // 3.2 cm: exact distances over the whole layer
  const DistanceField field = make_distance_field(volume, spec, 2);

  const Vec3 down(0, -1, 0), front(0, 0, 1);
  const ScalpChart chart = make_scalp_chart(cap, front, down, "cap.obj");
  RootOptions o;
  o.density = 2.0;
  o.tilt = 70.0;
  o.guides = 10;
  o.tilt_toward = TiltToward::thicker;
  RootInputs shell;
  shell.thickness = layer_thickness(field);  // as the pipeline's roots stage passes it
  const Roots roots = make_roots(chart, shell, o, Exec{2, {}});
  o.tilt_toward = TiltToward::down;
  const Roots toward_down = make_roots(chart, {}, o, Exec{2, {}});
  REQUIRE(roots.pores.size() > 300);
  REQUIRE(toward_down.pores.size() == roots.pores.size());

  double worst = 0.0, sum = 0.0, worst_down = 0.0;
  int counted = 0;
  for (int i = 0; i < roots.pores.size(); ++i) {
    const Vec3 p = roots.pores.positions[i];
    CHECK(toward_down.pores.positions[i] == p);  // only the directions differ
    const Vec3 radial = p.normalized();
    const double theta = std::acos(std::clamp(radial.y(), -1.0, 1.0));
    CHECK(-field.value(p) == doctest::Approx(layer(theta)).epsilon(0.08));  // the depth is the layer
    if (theta < 10.0 * M_PI / 180.0) continue;  // the cone's tip at the pole has no gradient
    const Vec3 e_theta = Vec3(std::cos(theta) * radial.x() / std::sin(theta), -std::sin(theta),
                              std::cos(theta) * radial.z() / std::sin(theta));
    // Against the root's own normal (the mesh's, a fraction of a degree off the sphere's), with
    // the tangent toward the pole in its tangent plane.
    const Vec3 n = roots.pores.normals[i];
    const Vec3 to_pole = (-e_theta - (-e_theta).dot(n) * n).normalized();
    const double error = degrees_between(roots.pores.directions[i], tilted_by(n, to_pole, 70.0));
    worst = std::max(worst, error);
    sum += error;
    ++counted;
    worst_down = std::max(worst_down, degrees_between(toward_down.pores.directions[i], tilted_by(n, -to_pole, 70.0)));
  }
  REQUIRE(counted > 250);
  MESSAGE("toward the pole: mean error " << sum / counted << "°, worst " << worst << "° over " << counted
                                         << " roots; toward down, worst " << worst_down << "°");
  CHECK(sum / counted < 0.5);  // measured 0.16°
  CHECK(worst < 2.0);          // measured 0.84°
  CHECK(worst_down < 1.0);  // the same roots tilted toward down go the other way
}
