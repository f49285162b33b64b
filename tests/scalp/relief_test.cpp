// The hull's grain against the direction of grooves carved along known curves.
#include <doctest/doctest.h>

#include <cmath>

#include "core/shapes.h"
#include "scalp/relief.h"
#include "tests/scalp/scalp_meshes.h"

using namespace hairfit;

namespace {

constexpr double R = 8.0, kCap = 1.0, kTwist = 1.0;
constexpr int kGrooves = 24;

// θ from the pole +y, φ about it.
double polar(const Vec3& u) { return std::acos(std::clamp(u.y() / u.norm(), -1.0, 1.0)); }
double azimuth(const Vec3& u) { return std::atan2(u.z(), u.x()); }

// The unit tangent of the groove through the direction u: along the level set of s = φ + kθ,
// i.e. perpendicular to ∇s = e_φ / sin θ + k e_θ / R (up to the common 1/R).
Vec3 groove_direction(const Vec3& u) {
  const double theta = polar(u), phi = azimuth(u);
  const Vec3 e_theta(std::cos(theta) * std::cos(phi), -std::sin(theta), std::cos(theta) * std::sin(phi));
  const Vec3 e_phi(-std::sin(phi), 0.0, std::cos(phi));
  const Vec3 gradient = e_phi / std::sin(theta) + kTwist * e_theta;
  return u.normalized().cross(gradient).normalized();
}

// The scalp cap of radius R to kCap from the pole, and over it the sphere of radius R + 1 with
// grooves 0.3 cm deep along the lines φ + kTwist·θ = const, and the same sphere smooth.
struct GroovedCase {
  ScalpChart chart;
  Mesh hull, smooth;
};

GroovedCase grooved_case() {
  const Mesh cap = test::ring_disk(
      24,
      [](double r, double phi) {
        const double theta = r * kCap;
        return Vec3(R * std::sin(theta) * std::cos(phi), R * std::cos(theta), R * std::sin(theta) * std::sin(phi));
      },
      [](const Vec3& p) { return p; });
  const ScalpChart chart = make_scalp_chart(cap, Vec3(0, 0, 1), Vec3(0, -1, 0), "cap.obj");
  Mesh hull = icosphere(6, 1.0);
  Mesh smooth = hull;
  for (Vec3& p : hull.positions) {
    const double s = kGrooves * (azimuth(p) + kTwist * polar(p)) / (2.0 * M_PI);
    p *= R + 1.0 - 0.3 * (0.5 + 0.5 * std::cos(2.0 * M_PI * s));
  }
  for (Vec3& p : smooth.positions) p *= R + 1.0;
  return {chart, hull, smooth};
}

}  // namespace

TEST_CASE("relief grain: along grooves that swirl from the crown (mean error under 10°, none over 30°); none over a smooth hull") {
  const GroovedCase grooved = grooved_case();
  const ScalpChart& chart = grooved.chart;
  const Mesh &hull = grooved.hull, &smooth = grooved.smooth;
  const std::vector<Vec3> grain = relief_grain(chart, hull, 1.5, 2);
  int checked = 0;
  double worst = 0.0, mean = 0.0, lowest = 1.0;
  for (std::size_t v = 0; v < grain.size(); ++v) {
    const double theta = polar(chart.mesh.positions[v]);
    if (theta < 0.4) continue;  // near the pole the grooves crowd below the mesh's resolution
    const Vec3 expected = groove_direction(chart.mesh.positions[v]);
    CAPTURE(theta);
    lowest = std::min(lowest, grain[v].norm());
    const double degrees = std::acos(std::min(1.0, std::fabs(grain[v].normalized().dot(expected)))) * 180.0 / M_PI;
    worst = std::max(worst, degrees);
    mean += degrees;
    CHECK(degrees < 30.0);
    CHECK(grain[v].norm() > 0.5);
    ++checked;
  }
  CHECK(checked > 200);
  CHECK(mean / checked < 10.0);
  MESSAGE("grain vs grooves: mean " << mean / checked << "°, worst " << worst << "°, weakest " << lowest);
  // A smooth sphere: every edge bends alike, no direction stands out.
  double smooth_most = 0.0;
  for (const Vec3& g : relief_grain(chart, smooth, 1.5, 2)) smooth_most = std::max(smooth_most, g.norm());
  MESSAGE("smooth sphere: strongest grain " << smooth_most);
  CHECK(smooth_most < 0.01);
}

namespace {

// A square sheet y = lift + A·cos(2πx/λ) over [−half, half]², triangulated on an n × n grid with
// alternating diagonals, normals up: parallel grooves along z.
Mesh corrugated_sheet(int n, double half, double lift, double amplitude, double wavelength) {
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -half + 2.0 * half * i / n, z = -half + 2.0 * half * j / n;
      m.positions.emplace_back(x, lift + amplitude * std::cos(2.0 * M_PI * x / wavelength), z);
    }
  auto at = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if ((i + j) % 2 == 0) {
        m.triangles.emplace_back(at(i, j), at(i, j + 1), at(i + 1, j + 1));
        m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i + 1, j));
      } else {
        m.triangles.emplace_back(at(i, j), at(i, j + 1), at(i + 1, j));
        m.triangles.emplace_back(at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
      }
    }
  return m;
}

double line_degrees(const Vec3& a, const Vec3& b) {
  return std::acos(std::min(1.0, std::fabs(a.normalized().dot(b.normalized())))) * 180.0 / M_PI;
}

}  // namespace

TEST_CASE("relief grain of normals: parallel grooves over a flat scalp read exactly along them, fully sure") {
  // Every face normal of the sheet lies in the xy-plane: their tangential parts vary along x only,
  // so the covariance is rank one and its minor eigenvector is z, exactly, at every scale.
  const ScalpChart chart = make_scalp_chart(test::flat_disk(8, 4.0), Vec3(0, 0, 1), Vec3(0, -1, 0), "disk.obj");
  const Mesh sheet = corrugated_sheet(120, 10.0, 1.0, 0.15, 1.5);
  const std::vector<double> lift(chart.mesh.positions.size(), 1.0);
  const std::vector<Vec3> grain = relief_grain_of_normals(chart, sheet, lift, 1.5, 2);
  for (std::size_t v = 0; v < grain.size(); ++v) {
    CAPTURE(v);
    CHECK(grain[v].norm() == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(std::fabs(grain[v].normalized().z()) == doctest::Approx(1.0).epsilon(1e-9));
  }
  // A flat sheet: no spread, no grain.
  const std::vector<Vec3> flat = relief_grain_of_normals(chart, corrugated_sheet(40, 10.0, 1.0, 0.0, 1.5), lift, 1.5, 2);
  for (const Vec3& g : flat) CHECK(g.norm() == 0.0);
}

TEST_CASE("relief grain of normals: along grooves that swirl from the crown, read on the hull 1 cm above") {
  const GroovedCase grooved = grooved_case();
  const ScalpChart& chart = grooved.chart;
  const Mesh &hull = grooved.hull, &smooth = grooved.smooth;
  const std::vector<double> lift(chart.mesh.positions.size(), 0.85);
  const std::vector<Vec3> grain = relief_grain_of_normals(chart, hull, lift, 1.5, 2);
  int checked = 0;
  double mean = 0.0, worst = 0.0;
  for (std::size_t v = 0; v < grain.size(); ++v) {
    const double theta = polar(chart.mesh.positions[v]);
    if (theta < 0.4) continue;  // near the pole the grooves crowd below the mesh's resolution
    CAPTURE(theta);
    const double degrees = line_degrees(grain[v], groove_direction(chart.mesh.positions[v]));
    CHECK(degrees < 5.0);
    CHECK(grain[v].norm() > 0.5);
    mean += degrees;
    worst = std::max(worst, degrees);
    ++checked;
  }
  CHECK(checked > 200);
  // Measured: mean 0.41°, worst 1.3° (the edges' grain above: 7.5°, 27°).
  CHECK(mean / checked < 1.5);
  MESSAGE("grain of normals vs grooves: mean " << mean / checked << "°, worst " << worst << "°");
  // A smooth sphere: its normals spread alike every way about the point above the root.
  double smooth_most = 0.0;
  for (const Vec3& g : relief_grain_of_normals(chart, smooth, lift, 1.5, 2)) smooth_most = std::max(smooth_most, g.norm());
  MESSAGE("smooth sphere: strongest grain " << smooth_most);
  CHECK(smooth_most < 0.03);
}
