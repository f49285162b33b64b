// The hairline follows the selection itself: the scan is clipped at the selection's zero level
// set (lib/prepare/level_set_clip.h). Checked against areas clipped here, independently, and
// against the bust's own closed-form cap.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/shapes.h"
#include "prepare/bust.h"
#include "prepare/hair_region.h"
#include "prepare/prepare.h"

using namespace hairfit;

namespace {

double polygon_area(const std::vector<Vec3>& polygon) {
  Vec3 sum = Vec3::Zero();
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) sum += (polygon[i] - polygon[0]).cross(polygon[i + 1] - polygon[0]);
  return 0.5 * sum.norm();
}

// The area of triangle abc on the side of the plane `normal` points to: its corners there and the
// points where its sides cross the plane, in order (the half-space of a triangle is convex).
double area_above(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& point, const Vec3& normal) {
  const Vec3 corners[3] = {a, b, c};
  std::vector<Vec3> kept;
  for (int k = 0; k < 3; ++k) {
    const Vec3 &p = corners[k], &q = corners[(k + 1) % 3];
    const double dp = (p - point).dot(normal), dq = (q - point).dot(normal);
    if (dp >= 0) kept.push_back(p);
    if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0)) kept.push_back(p + dp / (dp - dq) * (q - p));
  }
  return kept.size() < 3 ? 0.0 : polygon_area(kept);
}

double smallest_angle_degrees(const Mesh& mesh, const Vec3i& t) {
  double smallest = 180.0;
  for (int k = 0; k < 3; ++k) {
    const Vec3 u = mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]], v = mesh.positions[t[(k + 2) % 3]] - mesh.positions[t[k]];
    smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / M_PI);
  }
  return smallest;
}

// Hull triangles touching a point the cut made (−1 scan vertex): the ones clipping introduced.
std::vector<int> cut_made_triangles(const Hull& hull) {
  std::vector<int> out;
  for (int t = 0; t < static_cast<int>(hull.mesh.triangles.size()); ++t) {
    if (hull.scan_triangle[t] < 0) continue;
    const Vec3i& f = hull.mesh.triangles[t];
    if (hull.scan_vertex[f[0]] < 0 || hull.scan_vertex[f[1]] < 0 || hull.scan_vertex[f[2]] < 0) out.push_back(t);
  }
  return out;
}

HairSelection plane(const Vec3& point, const Vec3& normal) {
  HairSelection s;
  s.kind = HairSelection::Kind::plane;
  s.point = point;
  s.normal = normal;
  return s;
}

}  // namespace

TEST_CASE("a plane cut: the hairline lies on the plane and every scan triangle keeps exactly its part above it") {
  const double radius = 10.0;
  const Mesh sphere = icosphere(4, radius, Vec3(0.3, -0.2, 0.1));
  const Vec3 point(0.1, 2.345, -0.2), normal = Vec3(0.2, 1.0, -0.3).normalized();
  HullOptions exact;
  exact.clip.snap = 0.0;  // no vertex moved: the kept region is the exact one
  const Hull hull = cut_hull(sphere, selection_field(sphere, {}, plane(point, normal), "sphere"), exact, "sphere");
  REQUIRE(hull.holes_filled == 0);
  CHECK(hull.cut_triangles > 50);
  double worst_off = 0.0;
  for (int v : hull.hairline) worst_off = std::max(worst_off, std::abs((hull.mesh.positions[v] - point).dot(normal)));
  MESSAGE("hairline: " << hull.hairline.size() << " vertices, farthest from the plane " << worst_off / radius << " × the radius");
  CHECK(worst_off <= 1e-12 * radius);

  // Per scan triangle: the hull's pieces of it against its part above the plane, clipped here.
  std::map<int, double> pieces;
  for (int t = 0; t < static_cast<int>(hull.mesh.triangles.size()); ++t)
    pieces[hull.scan_triangle[t]] += triangle_area(hull.mesh, t);
  double exact_area = 0.0, worst = 0.0, staircase = 0.0;
  for (int t = 0; t < static_cast<int>(sphere.triangles.size()); ++t) {
    const Vec3i& f = sphere.triangles[t];
    const Vec3 &a = sphere.positions[f[0]], &b = sphere.positions[f[1]], &c = sphere.positions[f[2]];
    const double above = area_above(a, b, c, point, normal);
    exact_area += above;
    worst = std::max(worst, std::abs(above - (pieces.count(t) ? pieces[t] : 0.0)));
    if ((a - point).dot(normal) >= 0 && (b - point).dot(normal) >= 0 && (c - point).dot(normal) >= 0)
      staircase += triangle_area(sphere, t);
  }
  const double hull_area = surface_area(hull.mesh);
  MESSAGE("area above the plane " << exact_area << ", hull " << hull_area << " (whole triangles only: " << staircase
                                  << "); worst triangle off by " << worst);
  CHECK(std::abs(hull_area - exact_area) <= 1e-12 * exact_area);
  CHECK(worst <= 1e-12 * radius * radius);
  CHECK(exact_area - staircase > 1e-3 * exact_area);  // the test tells the old staircase apart

  SUBCASE("snapped (the default): the area within the snap's reach, no needles or slivers") {
    const Hull snapped = cut_hull(sphere, selection_field(sphere, {}, plane(point, normal), "sphere"), HullOptions{}, "sphere");
    for (int v : snapped.hairline) CHECK(std::abs((snapped.mesh.positions[v] - point).dot(normal)) <= 1e-12 * radius);
    const double area = surface_area(snapped.mesh);
    MESSAGE("snapped " << snapped.snapped_vertices << " vertices: area " << area << " (exact " << exact_area << ")");
    CHECK(snapped.snapped_vertices > 0);
    CHECK(std::abs(area - exact_area) <= 1e-3 * exact_area);
    CHECK(std::abs(area - exact_area) < 0.2 * (exact_area - staircase));
    double smallest = 180.0, smallest_share = 1.0;
    for (int t : cut_made_triangles(snapped)) {
      smallest = std::min(smallest, smallest_angle_degrees(snapped.mesh, snapped.mesh.triangles[t]));
      smallest_share = std::min(smallest_share, triangle_area(snapped.mesh, t) / triangle_area(sphere, snapped.scan_triangle[t]));
    }
    double scan_smallest = 180.0;
    for (const Vec3i& f : sphere.triangles) scan_smallest = std::min(scan_smallest, smallest_angle_degrees(sphere, f));
    MESSAGE("triangles the cut made: smallest angle " << smallest << "° (the scan's " << scan_smallest
                                                       << "°), smallest area " << smallest_share << " of its scan triangle");
    CHECK(smallest >= 3.0);
    CHECK(smallest_share >= 5e-3);
  }
}

TEST_CASE("a cap cut on the bust: hairline points at the half-angle, no needles, nothing outside the cap") {
  const BustShape shape;
  const BustScan scan = make_bust(shape);
  PrepareOptions o;
  o.selection.kind = HairSelection::Kind::cap;
  o.selection.axis = shape.cap_axis();
  o.selection.half_angle = shape.hairline_angle;
  const Prepared p = prepare_scan(scan.mesh, {}, o, "bust.obj");
  const Hull& hull = p.hull;
  double worst = 0.0;
  for (int v : hull.hairline) worst = std::max(worst, std::abs(shape.cap_angle(hull.mesh.positions[v].normalized()) * 180.0 / M_PI - shape.hairline_angle));
  MESSAGE("cap hairline: " << hull.hairline.size() << " vertices, worst " << worst << "° off the half-angle");
  CHECK(worst <= 1e-9);
  // Every hull point is in the cap (up to rounding): check the vertices and triangle centroids.
  double beyond = 0.0;
  for (const Vec3& q : hull.mesh.positions) beyond = std::max(beyond, shape.cap_angle(q.normalized()) * 180.0 / M_PI - shape.hairline_angle);
  CHECK(beyond <= 1e-9);
  double smallest = 180.0;
  for (int t : cut_made_triangles(hull)) smallest = std::min(smallest, smallest_angle_degrees(hull.mesh, hull.mesh.triangles[t]));
  MESSAGE("smallest angle of a triangle the cut made: " << smallest << "°; " << hull.cut_triangles << " scan triangles cut, "
                                                        << hull.snapped_vertices << " vertices snapped");
  CHECK(smallest >= 3.0);
}

TEST_CASE("a painted mask: the smoothed paint's hairline runs near the painted boundary, closer than the unsmoothed one") {
  const BustShape shape;
  const BustScan scan = make_bust(shape);
  HairSelection mask;
  mask.kind = HairSelection::Kind::mask;
  mask.color = Vec3(kHairColor[0], kHairColor[1], kHairColor[2]);
  // The paint's boundary is the cap at hairline_angle, known only to a vertex spacing.
  double spacing = 0.0;
  for (const Vec3i& f : scan.mesh.triangles)
    for (int k = 0; k < 3; ++k)
      spacing = std::max(spacing, std::acos(std::min(1.0, scan.directions[f[k]].dot(scan.directions[f[(k + 1) % 3]]))) * 180.0 / M_PI);
  auto deviation = [&](int smoothing, double& worst) {
    mask.mask_smoothing = smoothing;
    const Hull hull = cut_hull(scan.mesh, selection_field(scan.mesh, scan.colors, mask, "bust.obj"), HullOptions{}, "bust.obj");
    double sum = 0.0;
    worst = 0.0;
    for (int v : hull.hairline) {
      const double off = shape.cap_angle(hull.mesh.positions[v].normalized()) * 180.0 / M_PI - shape.hairline_angle;
      sum += off * off, worst = std::max(worst, std::abs(off));
    }
    return std::sqrt(sum / hull.hairline.size());
  };
  double worst_smooth = 0.0, worst_raw = 0.0;
  const double smooth = deviation(2, worst_smooth), raw = deviation(0, worst_raw);
  MESSAGE("mask hairline off the painted cap: rms " << smooth << "° (worst " << worst_smooth << "°) smoothed, " << raw
                                                    << "° (worst " << worst_raw << "°) unsmoothed; vertex spacing up to " << spacing << "°");
  CHECK(worst_smooth <= spacing);
  CHECK(smooth < 0.5 * raw);
}

TEST_CASE("a plane through scan vertices and along scan edges: those vertices are the hairline, nothing degenerate") {
  // The icosahedron has vertices (±1, 0, ±φ): the plane y = 0 passes through them and through the
  // subdivided edges between them.
  const Mesh sphere = icosphere(3, 5.0);
  int on_plane = 0;
  for (const Vec3& q : sphere.positions) on_plane += q.y() == 0.0;
  REQUIRE(on_plane >= 4);
  for (double snap : {0.0, 0.25}) {
    HullOptions o;
    o.clip.snap = snap;
    const Hull hull = cut_hull(sphere, selection_field(sphere, {}, plane(Vec3::Zero(), Vec3::UnitY()), "sphere"), o, "sphere");
    CHECK(analyse_topology(hull.mesh).is_disk());
    for (int v : hull.hairline) CHECK(std::abs(hull.mesh.positions[v].y()) <= 1e-12 * 5.0);
    double exact = 0.0;
    for (const Vec3i& f : sphere.triangles)
      exact += area_above(sphere.positions[f[0]], sphere.positions[f[1]], sphere.positions[f[2]], Vec3::Zero(), Vec3::UnitY());
    CHECK(surface_area(hull.mesh) == doctest::Approx(exact).epsilon(snap == 0.0 ? 1e-12 : 1e-3));
    for (int t = 0; t < static_cast<int>(hull.mesh.triangles.size()); ++t) CHECK(triangle_area(hull.mesh, t) > 1e-6);
  }
}
