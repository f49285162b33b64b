// Hair derived from its shell, the distance to where the layer ends, and the growth field away
// from that end, against the exact answers of a spherical cap under a concentric shell.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "scalp/growth_field.h"
#include "scalp/shell_hair.h"
#include "tests/scalp/scalp_meshes.h"

using namespace hairfit;

namespace {

constexpr double R = 8.0, kThickness = 0.8, kCap = 1.2;  // scalp cap θ ≤ 1.2 rad of the sphere of radius R

Mesh cap_mesh() {
  return test::ring_disk(
      32,
      [](double r, double phi) {
        const double theta = r * kCap;
        return Vec3(R * std::sin(theta) * std::cos(phi), R * std::cos(theta), R * std::sin(theta) * std::sin(phi));
      },
      [](const Vec3& p) { return p; });
}

// The layer between the scalp sphere and the hull sphere R + 0.8 over θ ≤ θ_end: depth below the
// hull, and outside it (negative) beyond θ_end, where the hull stops.
ThicknessField shell(double theta_end) {
  return [theta_end](const Vec3& p) {
    const double theta = std::acos(std::clamp(p.y() / p.norm(), -1.0, 1.0));
    LayerThickness t;
    t.value = theta <= theta_end ? R + kThickness - p.norm() : -1.0;
    return t;
  };
}

}  // namespace

TEST_CASE("layer end distance: zero along a hairline the hull stops at, the geodesic distance from it inside") {
  const ScalpChart chart = make_scalp_chart(cap_mesh(), Vec3(0, 0, 1), Vec3(0, -1, 0), "cap.obj");
  const ThicknessField field = shell(kCap);  // the hull stops exactly at the hairline
  std::vector<double> thickness;
  for (const Vec3& p : chart.mesh.positions) thickness.push_back(field(p).value);
  const std::vector<double> d = layer_end_distance(chart, thickness, field, kLayerEndProbe);
  for (int v : chart.boundary) CHECK(d[v] == 0.0);
  for (std::size_t i = 0; i < d.size(); ++i) {
    const Vec3& p = chart.mesh.positions[i];
    const double geodesic = R * (kCap - std::acos(std::clamp(p.y() / R, -1.0, 1.0)));
    // Edge paths are never shorter than the geodesic (of the polyhedron: its edges are chords, by
    // at most 1 − (Δθ)²/24 = 6e-5 shorter than their arcs), and on this mesh at most 8 % longer.
    CHECK(d[i] >= (1.0 - 1e-4) * geodesic - 1e-9);
    CHECK(d[i] <= 1.08 * geodesic + 1e-9);
  }
  // A hull that goes on beyond the hairline: the layer never ends.
  const ThicknessField beyond = shell(kCap + 0.3);
  thickness.clear();
  for (const Vec3& p : chart.mesh.positions) thickness.push_back(beyond(p).value);
  for (double x : layer_end_distance(chart, thickness, beyond, kLayerEndProbe)) CHECK(std::isinf(x));
}

TEST_CASE("shell hair: tilt and length from the layer's thickness and reach, capped at 80°; nothing where it never ends") {
  const ShellHair rule = hair_for_shell(3.0, 15.5);
  CHECK(rule.tilt == std::round(90.0 - std::atan(3.0 / 15.5) * 180.0 / M_PI));  // 79°: below the cap
  CHECK(rule.length == 10.5);  // ⅔ of 15.5, to 0.5 cm (prepare's test bust)
  CHECK(hair_for_shell(0.1, 20.0).tilt == kMaxShellTilt);
  const ScalpChart chart = make_scalp_chart(cap_mesh(), Vec3(0, 0, 1), Vec3(0, -1, 0), "cap.obj");
  const ShellHair h = shell_hair(chart, shell(kCap), 2);
  REQUIRE(h.layer_ends);
  CHECK(h.thickness == doctest::Approx(kThickness).epsilon(1e-9));
  const double reach = R * kCap;  // from the hairline to the pole
  CHECK(h.reach >= (1.0 - 1e-4) * reach);
  CHECK(h.reach <= 1.08 * reach);
  CHECK(h.length == std::round(2.0 * (2.0 / 3.0) * h.reach) / 2.0);
  CHECK(h.tilt == kMaxShellTilt);  // 90° − atan(0.8 / 9.6) = 85° is capped
  CHECK_FALSE(shell_hair(chart, shell(kCap + 0.3), 2).layer_ends);
  // T alone, whether the layer ends or not (strands.depth = "auto" reads it).
  CHECK(shell_thickness(chart, shell(kCap), 2) == h.thickness);
  CHECK(shell_thickness(chart, shell(kCap + 0.3), 2) == doctest::Approx(kThickness).epsilon(1e-9));
}

TEST_CASE("growth field: near a hairline where the layer ends, hair grows away from it, toward the pole") {
  const ScalpChart chart = make_scalp_chart(cap_mesh(), Vec3(0, 0, 1), Vec3(0, -1, 0), "cap.obj");
  RootOptions o;
  o.tilt_toward = TiltToward::thicker;
  RootInputs layer;
  layer.thickness = shell(kCap);
  o.length = 10.0;
  o.flow_smoothing = 1.0;
  const DirectionField f = make_growth_field(chart, layer, o);
  int checked = 0;
  for (std::size_t i = 0; i < chart.mesh.positions.size(); ++i) {
    const Vec3& p = chart.mesh.positions[i];
    const double theta = std::acos(std::clamp(p.y() / R, -1.0, 1.0));
    if (theta < 0.8 || theta > kCap - 0.05) continue;  // the band within 3 cm of the hairline
    const Vec3 toward_pole = (Vec3(0, 1, 0) - p.normalized() * p.normalized().y()).normalized();
    CHECK(f.directions[i].dot(toward_pole) > std::cos(20.0 * M_PI / 180.0));
    ++checked;
  }
  CHECK(checked > 100);
}

TEST_CASE("growth field with swirl: near the hairline it turns clockwise from the pole by the swirl") {
  const ScalpChart chart = make_scalp_chart(cap_mesh(), Vec3(0, 0, 1), Vec3(0, -1, 0), "cap.obj");
  for (double swirl : {30.0, 60.0}) {
    RootOptions o;
    o.tilt_toward = TiltToward::thicker;
    RootInputs layer;
  layer.thickness = shell(kCap);
    o.length = 10.0;
    o.flow_smoothing = 1.0;
    o.swirl = swirl;
    const DirectionField f = make_growth_field(chart, layer, o);
    int checked = 0;
    for (std::size_t i = 0; i < chart.mesh.positions.size(); ++i) {
      const Vec3& p = chart.mesh.positions[i];
      const double theta = std::acos(std::clamp(p.y() / R, -1.0, 1.0));
      if (theta < 0.8 || theta > kCap - 0.05) continue;
      const Vec3 n = p.normalized();
      const Vec3 toward_pole = (Vec3(0, 1, 0) - n * n.y()).normalized();
      // Clockwise seen from outside: from toward_pole by −swirl about the outward normal.
      const double a = -swirl * M_PI / 180.0;
      const Vec3 expected = std::cos(a) * toward_pole + std::sin(a) * n.cross(toward_pole);
      CAPTURE(swirl);
      CHECK(f.directions[i].dot(expected) > std::cos(15.0 * M_PI / 180.0));
      ++checked;
    }
    CHECK(checked > 100);
  }
}

TEST_CASE("declared style: near a whorl hair grows away from it, beside a parting away from the line") {
  const ScalpChart chart = make_scalp_chart(cap_mesh(), Vec3(0, 0, 1), Vec3(0, -1, 0), "cap.obj");
  RootOptions o;  // toward down: on its own radial from the pole, so the style must turn it
  o.flow = FlowModel::field;
  o.flow_smoothing = 0.5;
  o.whorl = Vec2(0.4, -0.3);
  o.whorl_radius = 2.0;
  const Vec3 w = surface_position(chart, locate_in_chart(chart, o.whorl));
  const DirectionField f = make_growth_field(chart, {}, o);
  int checked = 0;
  for (std::size_t i = 0; i < chart.mesh.positions.size(); ++i) {
    const Vec3& p = chart.mesh.positions[i];
    const double d = (p - w).norm();
    if (d < 0.5 || d > 1.2) continue;
    const Vec3 n = chart.vertex_normals[i];
    const Vec3 away = ((p - w) - (p - w).dot(n) * n).normalized();
    CHECK(f.directions[i].dot(away) > std::cos(35.0 * M_PI / 180.0));  // the whorl weighs 0.70 at 1.2 cm
    ++checked;
  }
  CHECK(checked > 5);
  // A parting from the front (chart (0, 0.9)) to the pole: on either side hair grows away from it.
  RootOptions q = o;
  q.whorl = Vec2(0.0, 0.0);
  q.whorl_radius = 0.0;
  q.parting = Vec2(0.0, 0.9);
  q.parting_radius = 1.5;
  const DirectionField g = make_growth_field(chart, {}, q);
  const Vec3 a = surface_position(chart, locate_in_chart(chart, q.parting));
  const Vec3 b = surface_position(chart, locate_in_chart(chart, q.whorl));
  checked = 0;
  for (std::size_t i = 0; i < chart.mesh.positions.size(); ++i) {
    const Vec3& p = chart.mesh.positions[i];
    // Beside the middle of the parting: its points lie in the plane x = 0 (front–back through the pole).
    const Vec3 mid = 0.5 * (a + b);
    if ((p - mid).norm() > 2.5 || std::fabs(p.x()) < 0.4 || std::fabs(p.x()) > 1.0) continue;
    const Vec3 n = chart.vertex_normals[i];
    const Vec3 side = (Vec3(p.x() > 0 ? 1.0 : -1.0, 0, 0) - n * n.x() * (p.x() > 0 ? 1.0 : -1.0)).normalized();
    CHECK(g.directions[i].dot(side) > std::cos(35.0 * M_PI / 180.0));
    ++checked;
  }
  CHECK(checked > 5);
}
