// `hairfit prepare`'s library on the procedural bust (lib/prepare/bust.h), whose hair region,
// skull and bumps are known in closed form.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include "core/error.h"
#include "field/distance_field.h"
#include "prepare/bust.h"
#include "prepare/prepare.h"
#include "prepare/surface_checks.h"

using namespace hairfit;

namespace {

const BustShape kShape;

// The scan triangles with all three corners, or with at least one, satisfying `picked`, computed
// here from the bust's own definition, not by the code under test.
std::set<int> triangles_where(const BustScan& scan, const std::function<bool(int)>& picked, bool all = true) {
  std::set<int> out;
  for (int t = 0; t < static_cast<int>(scan.mesh.triangles.size()); ++t) {
    const Vec3i& f = scan.mesh.triangles[t];
    const int count = picked(f[0]) + picked(f[1]) + picked(f[2]);
    if (all ? count == 3 : count > 0) out.insert(t);
  }
  return out;
}

// The hull covers the selected region: every scan triangle wholly inside is in it, and it holds
// (parts of) scan triangles with a corner inside only; the clipped rim lies between.
void check_covers(const Hull& hull, const BustScan& scan, const std::function<bool(int)>& picked) {
  const std::set<int> inside = triangles_where(scan, picked), touching = triangles_where(scan, picked, false);
  std::set<int> in_hull;
  for (int t : hull.scan_triangle)
    if (t >= 0) in_hull.insert(t);
  CHECK(std::includes(in_hull.begin(), in_hull.end(), inside.begin(), inside.end()));
  CHECK(std::includes(touching.begin(), touching.end(), in_hull.begin(), in_hull.end()));
  CHECK(in_hull.size() > inside.size());  // the rim's triangles are there in part
}

PrepareOptions cap_options() {
  PrepareOptions o;
  o.selection.kind = HairSelection::Kind::cap;
  o.selection.centre = Vec3::Zero();
  o.selection.axis = kShape.cap_axis();
  o.selection.half_angle = kShape.hairline_angle;
  return o;
}

}  // namespace

TEST_CASE("the hull covers the selected region, for a cap, a colour mask and a plane") {
  const BustScan scan = make_bust(kShape);
  const double cos_cap = std::cos(kShape.hairline_angle * M_PI / 180.0);
  SUBCASE("cap") {
    const Prepared p = prepare_scan(scan.mesh, {}, cap_options(), "bust.obj");
    check_covers(p.hull, scan, [&](int v) { return scan.directions[v].dot(kShape.cap_axis()) >= cos_cap; });
    CHECK(p.hull.holes_filled == 0);
  }
  SUBCASE("mask") {
    PrepareOptions o;
    o.selection.kind = HairSelection::Kind::mask;
    o.selection.color = Vec3(kHairColor[0], kHairColor[1], kHairColor[2]);
    const Prepared p = prepare_scan(scan.mesh, scan.colors, o, "bust.obj");
    check_covers(p.hull, scan, [&](int v) { return kShape.in_hair(scan.directions[v]); });
  }
  SUBCASE("plane") {
    PrepareOptions o;
    o.selection.kind = HairSelection::Kind::plane;
    o.selection.point = Vec3(0, 2.5, 0);
    o.selection.normal = Vec3(0, 1, 0);
    const Prepared p = prepare_scan(scan.mesh, {}, o, "bust.obj");
    check_covers(p.hull, scan, [&](int v) { return scan.mesh.positions[v].y() >= 2.5; });
    for (int v : p.hull.hairline) CHECK(p.hull.mesh.positions[v].y() == doctest::Approx(2.5).epsilon(1e-13));
    // Its area against the part of every scan triangle above y = 2.5, clipped here: equal but
    // for the snapped vertices' moves (far below the staircase's shortfall).
    double exact = 0.0, staircase = 0.0;
    for (const Vec3i& f : scan.mesh.triangles) {
      std::vector<Vec3> kept;
      for (int k = 0; k < 3; ++k) {
        const Vec3 &a = scan.mesh.positions[f[k]], &b = scan.mesh.positions[f[(k + 1) % 3]];
        if (a.y() >= 2.5) kept.push_back(a);
        if ((a.y() - 2.5) * (b.y() - 2.5) < 0) kept.push_back(a + (2.5 - a.y()) / (b.y() - a.y()) * (b - a));
      }
      double area = 0.0;
      for (std::size_t i = 1; i + 1 < kept.size(); ++i) area += 0.5 * (kept[i] - kept[0]).cross(kept[i + 1] - kept[0]).norm();
      exact += area;
      if (scan.mesh.positions[f[0]].y() >= 2.5 && scan.mesh.positions[f[1]].y() >= 2.5 && scan.mesh.positions[f[2]].y() >= 2.5)
        staircase += area;
    }
    const double area = surface_area(p.hull.mesh);
    MESSAGE("plane y ≥ 2.5: hull area " << area << " cm², exact " << exact << ", whole triangles only " << staircase);
    CHECK(std::abs(area - exact) <= 1e-3 * exact);
    CHECK(std::abs(area - exact) < 0.2 * (exact - staircase));
  }
}

TEST_CASE("a hole in the scanned hair is filled and near-duplicate seam vertices are welded") {
  BustScan scan = make_bust(kShape);
  // Missing data on the crown: drop the triangles within 0.7 cm of a crown point.
  const Vec3 crown = kShape.radius(kShape.cap_axis()) * kShape.cap_axis();
  std::set<int> removed;
  std::vector<Vec3i> kept;
  for (int t = 0; t < static_cast<int>(scan.mesh.triangles.size()); ++t) {
    const Vec3i& f = scan.mesh.triangles[t];
    const Vec3 centroid = (scan.mesh.positions[f[0]] + scan.mesh.positions[f[1]] + scan.mesh.positions[f[2]]) / 3.0;
    if ((centroid - crown).norm() < 0.7) removed.insert(t);
    else kept.push_back(f);
  }
  REQUIRE(removed.size() >= 6);
  Mesh holed = scan.mesh;
  holed.triangles = kept;
  const Prepared p = prepare_scan(holed, {}, cap_options(), "bust.obj");
  CHECK(p.hull.holes_filled == 1);
  CHECK(analyse_topology(p.hull.mesh).is_disk());
  CHECK(std::count(p.hull.scan_triangle.begin(), p.hull.scan_triangle.end(), -1) >= 3);

  // A seam: the triangles with x > 0 get their own copies of the vertices, 1e-7 cm away.
  Mesh seamed = scan.mesh;
  std::vector<int> copy(scan.mesh.positions.size(), -1);
  for (Vec3i& f : seamed.triangles) {
    const Vec3 centroid = (scan.mesh.positions[f[0]] + scan.mesh.positions[f[1]] + scan.mesh.positions[f[2]]) / 3.0;
    if (centroid.x() <= 0) continue;
    for (int k = 0; k < 3; ++k) {
      if (copy[f[k]] < 0) {
        copy[f[k]] = static_cast<int>(seamed.positions.size());
        seamed.positions.push_back(scan.mesh.positions[f[k]] + Vec3(1e-7, -1e-7, 1e-7));
      }
      f[k] = copy[f[k]];
    }
  }
  const Prepared welded = prepare_scan(seamed, {}, cap_options(), "bust.obj");
  CHECK(welded.welded_vertices > 0);
  CHECK(welded.hull.mesh.triangles.size() == prepare_scan(scan.mesh, {}, cap_options(), "b").hull.mesh.triangles.size());
  PrepareOptions unwelded = cap_options();
  unwelded.weld_tolerance = 0.0;
  // Unwelded, the seam cuts the hair in two and only the larger half is kept.
  CHECK(prepare_scan(seamed, {}, unwelded, "bust.obj").hull.mesh.triangles.size() < 0.6 * welded.hull.mesh.triangles.size());
}

TEST_CASE("a scan whose triangles run both ways round gives the same hull, every triangle facing out") {
  // Raw scans mix windings. Every third triangle reversed (and a whole patch on the crown) must
  // give the hull of the clean scan, consistently oriented and facing out. (The hairline's cut
  // points may differ in the last bits, where an edge is interpolated from its other end.)
  const BustScan scan = make_bust(kShape);
  Mesh mixed = scan.mesh;
  const Vec3 crown = kShape.radius(kShape.cap_axis()) * kShape.cap_axis();
  for (int t = 0; t < static_cast<int>(mixed.triangles.size()); ++t) {
    Vec3i& f = mixed.triangles[t];
    const Vec3 centroid = (mixed.positions[f[0]] + mixed.positions[f[1]] + mixed.positions[f[2]]) / 3.0;
    if (t % 3 == 0 || (centroid - crown).norm() < 2.0) std::swap(f[1], f[2]);
  }
  const Prepared clean = prepare_scan(scan.mesh, {}, cap_options(), "bust.obj");
  const Prepared p = prepare_scan(mixed, {}, cap_options(), "bust.obj");
  CHECK(analyse_topology(p.hull.mesh).orientation_consistent);
  CHECK(inward_triangles(p.hull.mesh, p.hull.centre).empty());
  REQUIRE(p.hull.mesh.triangles.size() == clean.hull.mesh.triangles.size());
  CHECK(p.hull.kept_area == doctest::Approx(clean.hull.kept_area).epsilon(1e-12));
  CHECK(p.hull.hairline.size() == clean.hull.hairline.size());
}

TEST_CASE("the scalp: a disk with the hull's hairline, inside it, skull-like and smooth") {
  const BustScan scan = make_bust(kShape);
  PrepareOptions o = cap_options();
  o.scalp.crown_thickness = kShape.hair_thickness;
  const Prepared p = prepare_scan(scan.mesh, {}, o, "bust.obj");
  const Mesh& hull = p.hull.mesh;
  const Mesh& scalp = p.scalp.scalp;
  const MeshTopology topology = analyse_topology(scalp);
  REQUIRE(topology.is_disk());
  CHECK(topology.orientation_consistent);
  CHECK(inward_triangles(scalp, p.hull.centre).empty());
  CHECK(self_intersections(scalp).empty());
  // The hairline: the same vertices at the same positions, in the same order.
  CHECK(topology.boundary_loops[0].size() == p.hull.hairline.size());
  for (int v : p.hull.hairline) CHECK(scalp.positions[v] == hull.positions[v]);
  // Outward: every scalp triangle's normal points away from the bust's centre (the origin).
  for (int t = 0; t < static_cast<int>(scalp.triangles.size()); ++t) {
    const Vec3i& f = scalp.triangles[t];
    CHECK(triangle_normal(scalp, t).dot(scalp.positions[f[0]] + scalp.positions[f[1]] + scalp.positions[f[2]]) > 0.0);
  }

  // Inside the hull: sampled points of every scalp triangle have winding number > ½ in the closed
  // volume (exact), and the volume's distance field is ≤ 0 there (what the pipeline will see).
  FieldSpec spec;
  spec.voxel = 0.2;
  const DistanceField field = make_distance_field(p.scalp.volume, spec, 2);
  std::vector<char> on_hairline(scalp.positions.size(), 0);
  for (int v : p.hull.hairline) on_hairline[v] = 1;
  int tested = 0, inside = 0, field_inside = 0;
  for (int t = 0; t < static_cast<int>(scalp.triangles.size()); t += 3) {
    const Vec3i& f = scalp.triangles[t];
    if (on_hairline[f[0]] || on_hairline[f[1]] || on_hairline[f[2]]) continue;
    const Vec3 q = (scalp.positions[f[0]] + scalp.positions[f[1]] + scalp.positions[f[2]]) / 3.0;
    ++tested;
    inside += winding_number(p.scalp.volume, q) > 0.5;
    field_inside += field.value(q) <= 0.0;
  }
  CHECK(tested > 1000);
  CHECK(inside == tested);
  CHECK(field_inside >= 0.99 * tested);
  MESSAGE("field ≤ 0 at " << field_inside << " of " << tested << " sampled scalp points");

  // Skull-like: away from the hairline's ramp, the scalp lies near the bust's true skull, also
  // under the bun (4.5 cm high) and the braids; the hull there is far above it.
  double worst = 0.0, worst_hull = 0.0, sum = 0.0;
  int counted = 0;
  for (std::size_t v = 0; v < scalp.positions.size(); ++v) {
    if (p.scalp.ramp[v] < 1.0) continue;
    const Vec3 u = scalp.positions[v].normalized();
    const double off = scalp.positions[v].norm() - kShape.skin_radius(u);
    worst = std::max(worst, std::abs(off));
    worst_hull = std::max(worst_hull, hull.positions[v].norm() - kShape.skin_radius(u));
    sum += std::abs(off), ++counted;
  }
  MESSAGE("scalp to skull: mean " << sum / counted << " cm, worst " << worst << " cm; hull up to " << worst_hull << " cm above");
  CHECK(worst_hull > 6.0);
  CHECK(sum / counted < 0.6);
  CHECK(worst < 1.0);

  // Smooth: under the hair (ramp ≥ ½) the mean curvature stays below 0.25/cm (no feature tighter
  // than a 4 cm radius; the skull's own reaches 0.15/cm where the head meets the neck), while the
  // hull's braids and bun reach far more. Near the hairline the scalp follows the head itself.
  const std::vector<double> h_scalp = mean_curvature(scalp), h_hull = mean_curvature(hull);
  double max_under = 0.0, max_scalp = 0.0, max_hull_band = 0.0;
  for (std::size_t v = 0; v < scalp.positions.size(); ++v) {
    max_scalp = std::max(max_scalp, h_scalp[v]);
    if (p.scalp.ramp[v] >= 0.5) max_under = std::max(max_under, h_scalp[v]);
    else max_hull_band = std::max(max_hull_band, h_hull[v]);
  }
  const double max_hull = *std::max_element(h_hull.begin(), h_hull.end());
  MESSAGE("max mean curvature: scalp " << max_under << "/cm under the hair, " << max_scalp << "/cm overall; hull "
                                       << max_hull << "/cm, " << max_hull_band << "/cm near the hairline");
  CHECK(max_under < 0.25);
  CHECK(max_scalp < std::max(0.25, 1.1 * max_hull_band));
  CHECK(max_hull > 0.6);

  // Thickness: zero at the hairline, about the declared crown thickness where the hair has no bumps.
  for (int v : p.hull.hairline) CHECK(p.scalp.thickness[v] == 0.0);
  const Vec3 axis = kShape.cap_axis(), forward = Vec3(0.0, std::sin(25.0 * M_PI / 180), std::cos(25.0 * M_PI / 180));
  const Vec3 bare = std::cos(35.0 * M_PI / 180) * axis + std::sin(35.0 * M_PI / 180) * forward;
  REQUIRE(kShape.bumps(bare) < 0.01);
  int nearest = 0;
  for (std::size_t v = 0; v < hull.positions.size(); ++v)
    if (hull.positions[v].normalized().dot(bare) > hull.positions[nearest].normalized().dot(bare)) nearest = static_cast<int>(v);
  MESSAGE("thickness at a bare crown point: " << p.scalp.thickness[nearest] << " cm (declared " << kShape.hair_thickness << ")");
  CHECK(p.scalp.thickness[nearest] == doctest::Approx(kShape.hair_thickness).epsilon(0.3));
}
