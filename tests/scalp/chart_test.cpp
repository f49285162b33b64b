#include <doctest/doctest.h>

#include <cmath>

#include "core/error.h"
#include "scalp/chart.h"
#include "tests/scalp/scalp_meshes.h"

using namespace hairfit;

namespace {

const Vec3 kFront(0, 0, 1), kDown(0, -1, 0);

void check_boundary_on_circle(const ScalpChart& ch) {
  double max_radius_error = 0.0;
  for (int v : ch.boundary) max_radius_error = std::max(max_radius_error, std::abs(ch.chart[v].norm() - 1.0));
  CHECK(max_radius_error < 1e-14);
  // Chord-length spacing: consecutive angles proportional to the 3D chord lengths.
  const int nb = static_cast<int>(ch.boundary.size());
  double total = 0.0;
  for (int k = 0; k < nb; ++k)
    total += (ch.mesh.positions[ch.boundary[(k + 1) % nb]] - ch.mesh.positions[ch.boundary[k]]).norm();
  double worst = 0.0;
  for (int k = 0; k < nb; ++k) {
    const Vec2 a = ch.chart[ch.boundary[k]], b = ch.chart[ch.boundary[(k + 1) % nb]];
    double dangle = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));  // counter-clockwise step
    const double chord = (ch.mesh.positions[ch.boundary[(k + 1) % nb]] - ch.mesh.positions[ch.boundary[k]]).norm();
    worst = std::max(worst, std::abs(dangle - 2 * M_PI * chord / total));
  }
  CHECK(worst < 1e-12);
}

void check_one_to_one(const ScalpChart& ch) {
  CHECK(ch.flipped_triangles == 0);
  // Independently: every triangle has the same (non-zero) chart orientation sign, and the chart
  // areas add up to the area of the hairline polygon (no overlap, no gap).
  double sum = 0.0;
  int wrong = 0;
  for (int t = 0; t < static_cast<int>(ch.mesh.triangles.size()); ++t) {
    const double a = ch.outward * chart_triangle_area(ch, t);
    if (!(a > 0)) ++wrong;
    sum += std::abs(a);
  }
  double polygon = 0.0;
  const int nb = static_cast<int>(ch.boundary.size());
  for (int k = 0; k < nb; ++k) {
    const Vec2 a = ch.chart[ch.boundary[k]], b = ch.chart[ch.boundary[(k + 1) % nb]];
    polygon += 0.5 * (a.x() * b.y() - a.y() * b.x());
  }
  CHECK(wrong == 0);
  CHECK(polygon > 0);
  CHECK(sum == doctest::Approx(polygon).epsilon(1e-10));
}

}  // namespace

TEST_CASE("chart: a planar disk is reproduced up to similarity (mean-value linear precision)") {
  const double radius = 7.0;
  const Mesh disk = test::flat_disk(12, radius, 0.35, 7);  // 12 rings: the hairline has a vertex at +z
  const ScalpChart ch = make_scalp_chart(disk, kFront, kDown, "disk.obj");
  CHECK(ch.outward == 1);
  check_boundary_on_circle(ch);
  check_one_to_one(ch);
  // Seen from above with the front (+z) at the top, the person's right (−x) is on the right:
  // chart = (−x, z) / R exactly.
  double worst = 0.0;
  for (std::size_t v = 0; v < disk.positions.size(); ++v) {
    const Vec2 expected(-disk.positions[v].x() / radius, disk.positions[v].z() / radius);
    worst = std::max(worst, (ch.chart[v] - expected).norm());
  }
  CHECK(worst < 1e-12);
  CHECK(ch.area == doctest::Approx(surface_area(disk)));
}

TEST_CASE("chart: orientation convention — front at +90°, not mirrored, independent of winding and pose") {
  const Mesh cap = test::head_cap(20);
  const ScalpChart ch = make_scalp_chart(cap, kFront, kDown, "cap.obj");
  check_boundary_on_circle(ch);
  check_one_to_one(ch);
  // The front-most hairline vertex sits exactly at (0, 1).
  int front_vertex = ch.boundary.front();
  for (int v : ch.boundary)
    if (cap.positions[v].z() > cap.positions[front_vertex].z()) front_vertex = v;
  CHECK(ch.chart[front_vertex].x() == doctest::Approx(0.0).epsilon(1e-15));
  CHECK(ch.chart[front_vertex].y() == doctest::Approx(1.0));
  // Person's right (−x): the right-most hairline vertex maps to chart x ≈ +1, the back to y ≈ −1.
  int right = front_vertex, back = front_vertex, top = 0;
  for (int v : ch.boundary) {
    if (cap.positions[v].x() < cap.positions[right].x()) right = v;
    if (cap.positions[v].z() < cap.positions[back].z()) back = v;
  }
  for (int v = 0; v < static_cast<int>(cap.positions.size()); ++v)
    if (cap.positions[v].y() > cap.positions[top].y()) top = v;
  CHECK(ch.chart[right].x() > 0.999);
  CHECK(ch.chart[back].y() < -0.999);
  // An interior point on the person's right side of the head lies in the right half of the chart.
  int side = 0;
  for (int v = 0; v < static_cast<int>(cap.positions.size()); ++v)
    if (cap.positions[v].x() < cap.positions[side].x()) side = v;
  CHECK(ch.chart[side].x() > 0.5);
  CHECK(std::abs(ch.chart[side].y()) < 0.1);
  CHECK(ch.chart[top].norm() < 1e-9);  // the crown of a symmetric cap is the chart centre
  CHECK(chart_to_image(ch.chart[front_vertex]).y() == doctest::Approx(0.0).epsilon(1e-15));  // front = row 0

  // Inward-facing triangles: the same chart.
  Mesh flipped = cap;
  for (Vec3i& t : flipped.triangles) std::swap(t[1], t[2]);
  const ScalpChart chf = make_scalp_chart(flipped, kFront, kDown, "flipped.obj");
  CHECK(chf.outward == -1);
  check_one_to_one(chf);
  double worst = 0.0, worst_normal = 0.0;
  for (std::size_t v = 0; v < cap.positions.size(); ++v) {
    worst = std::max(worst, (chf.chart[v] - ch.chart[v]).norm());
    worst_normal = std::max(worst_normal, (chf.vertex_normals[v] - ch.vertex_normals[v]).norm());
  }
  CHECK(worst < 1e-12);
  CHECK(worst_normal < 1e-12);
  CHECK(ch.vertex_normals[top].y() > 0.999);  // outward

  // A rigid rotation of mesh, front and down together leaves the chart unchanged.
  const Mat3 rotation = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  Mesh turned = cap;
  for (Vec3& p : turned.positions) p = rotation * p;
  const ScalpChart cht = make_scalp_chart(turned, rotation * kFront, rotation * kDown, "turned.obj");
  worst = 0.0;
  for (std::size_t v = 0; v < cap.positions.size(); ++v) worst = std::max(worst, (cht.chart[v] - ch.chart[v]).norm());
  CHECK(worst < 1e-9);

  // A mirror image of the head gives the mirror image of the chart (x → −x).
  Mesh mirrored = cap;
  for (Vec3& p : mirrored.positions) p.x() = -p.x();
  const ScalpChart chm = make_scalp_chart(mirrored, kFront, kDown, "mirrored.obj");
  worst = 0.0;
  for (std::size_t v = 0; v < cap.positions.size(); ++v)
    worst = std::max(worst, (chm.chart[v] - Vec2(-ch.chart[v].x(), ch.chart[v].y())).norm());
  CHECK(worst < 1e-9);
}

TEST_CASE("chart: one-to-one on a bumpy 50k-triangle cap") {
  const Mesh cap = test::head_cap(91, 1.6, 0.06);
  CHECK(cap.triangles.size() > 49000);
  const ScalpChart ch = make_scalp_chart(cap, kFront, kDown, "bumpy.obj");
  check_boundary_on_circle(ch);
  check_one_to_one(ch);
  for (const Vec2& c : ch.chart) CHECK_MESSAGE(c.norm() <= 1.0 + 1e-12, "chart point outside the unit disk");
}

TEST_CASE("chart: point location maps chart points back to the surface") {
  const Mesh cap = test::head_cap(30, 1.6, 0.03);
  const ScalpChart ch = make_scalp_chart(cap, kFront, kDown, "cap.obj");
  // Round trip: surface point → chart → locate → the same surface point.
  Random rng(3, RandomStage::test, 0);
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    SurfacePoint sp;
    sp.triangle = static_cast<int>(rng.below(cap.triangles.size()));
    double u = rng.uniform(), w = rng.uniform();
    if (u + w > 1) u = 1 - u, w = 1 - w;
    sp.barycentric = Vec3(1 - u - w, u, w);
    const SurfacePoint back = locate_in_chart(ch, chart_position(ch, sp));
    REQUIRE(back.triangle >= 0);
    worst = std::max(worst, (surface_position(ch, back) - surface_position(ch, sp)).norm());
  }
  CHECK(worst < 1e-9);
  // Outside the hairline polygon: the nearest polygon point, which lies on the hairline.
  const SurfacePoint outside = locate_in_chart(ch, Vec2(0.0, 1.5));
  CHECK(chart_position(ch, outside).isApprox(Vec2(0.0, 1.0), 1e-12));
  double front_z = -INFINITY;
  for (int v : ch.boundary) front_z = std::max(front_z, cap.positions[v].z());
  CHECK(surface_position(ch, outside).z() == doctest::Approx(front_z).epsilon(1e-12));
}

TEST_CASE("chart: scalps that are not disks are rejected, saying what they are") {
  const Mesh disk = test::flat_disk(4, 5.0);
  auto message = [](const Mesh& m) {
    try {
      make_scalp_chart(m, kFront, kDown, "bad.obj");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // Closed: an octahedron.
  Mesh closed;
  closed.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  closed.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  CHECK(message(closed).find("closed") != std::string::npos);
  CHECK(message(closed).find("bad.obj") != std::string::npos);
  // Two boundary loops: remove the central fan.
  Mesh annulus = disk;
  annulus.triangles.erase(annulus.triangles.begin(), annulus.triangles.begin() + 6);
  CHECK(message(annulus).find("2 boundary loops") != std::string::npos);
  // Non-manifold: a fin on an interior edge.
  Mesh fin = disk;
  fin.positions.push_back(Vec3(0, 3, 0));
  fin.triangles.push_back(Vec3i(0, 1, static_cast<int>(fin.positions.size()) - 1));
  const std::string nm = message(fin);
  CHECK(nm.find("non-manifold") != std::string::npos);
  CHECK(nm.find(" 1 (") != std::string::npos);  // names vertex 1 (1-based)
  // Two parts.
  Mesh two = disk;
  const int offset = static_cast<int>(two.positions.size());
  for (const Vec3& p : disk.positions) two.positions.push_back(p + Vec3(20, 0, 0));
  for (const Vec3i& t : disk.triangles) two.triangles.push_back(t + Vec3i::Constant(offset));
  CHECK(message(two).find("2 separate parts") != std::string::npos);
  // Inconsistent orientation.
  Mesh mixed = disk;
  std::swap(mixed.triangles[10][1], mixed.triangles[10][2]);
  CHECK(message(mixed).find("consistently oriented") != std::string::npos);
  // Edge-on: down lies in the disk's plane.
  CHECK_THROWS_AS(make_scalp_chart(disk, kFront, Vec3(1, 0, 0), "edge.obj"), InputError);
  CHECK_THROWS_AS(make_scalp_chart(disk, kDown, kDown, "parallel.obj"), InputError);
}
