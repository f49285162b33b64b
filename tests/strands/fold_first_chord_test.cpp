// A pore on the middle sheet of a Z-fold of the scalp (as a level-set scalp's hairline strip folds
// over itself): its triangle faces into the head's general direction, and no turn of the first
// chord toward that triangle's normal clears the fold; the chord turns to the nearest clear
// direction, along the fold.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/segment_triangle.h"
#include "core/triangle_grid.h"
#include "strands/strands.h"

using namespace hairfit;

namespace {

// The profile in (x, y), extruded over |z| ≤ 1: the bottom sheet y = 0 (x ≤ 0.75, facing +y),
// the fold's riser x = 0.75 (facing −x), the middle sheet y = 0.2 back to x = −1 (facing −y, into
// the pocket between it and the bottom sheet, which is outside the head and opens toward −x),
// the riser x = −1 (facing −x) and the top sheet y = 0.4 (facing +y). Between the middle and the
// top sheet lies the head.
Mesh z_fold() {
  const double profile[][2] = {{-3.0, 0.0}, {0.75, 0.0}, {0.75, 0.2}, {-1.0, 0.2}, {-1.0, 0.4}, {3.0, 0.4}};
  Mesh m;
  for (const auto& p : profile) {
    m.positions.emplace_back(p[0], p[1], -1.0);
    m.positions.emplace_back(p[0], p[1], 1.0);
  }
  for (int i = 0; i + 1 < 6; ++i) {  // (a, c, b): the normal is the profile's tangent turned by +90°
    const int a = 2 * i, c = 2 * i + 1, b = 2 * i + 2, d = 2 * i + 3;
    m.triangles.emplace_back(a, c, b);
    m.triangles.emplace_back(b, c, d);
  }
  return m;
}

}  // namespace

TEST_CASE("a pore on a fold of the scalp: its first chord turns along the fold to where it crosses nothing") {
  // The head exit sees the fold filled in (an interpolated field rounds a fold thinner than a
  // voxel): it moves a point over the fold (x > −1) below y = 0.45 up to y = 0.45. The guide
  // leaves the pore (0.5, 0.2, 0) at slope 0.5 toward +x, up through the head. Raised to 2° above
  // the middle sheet, the first chord meets the riser x = 0.75; lifted off it, the exit puts its
  // end at y = 0.45, above the top sheet, which the chord then crosses from behind. Turned up
  // toward the pore's normal (0, −1, 0) to the rises 0.25, 0.5, 0.75 and 0.9, the chord (0.32 cm)
  // meets the riser or the bottom sheet. The clear directions that leave above the pore's
  // triangle stay in the pocket: toward −x, or along the fold (z).
  const Mesh scalp = z_fold();
  REQUIRE(triangle_normal(scalp, 0).isApprox(Vec3(0, 1, 0)));
  REQUIRE(triangle_normal(scalp, 2).isApprox(Vec3(-1, 0, 0)));
  REQUIRE(triangle_normal(scalp, 4).isApprox(Vec3(0, -1, 0)));
  REQUIRE(triangle_normal(scalp, 8).isApprox(Vec3(0, 1, 0)));
  const TriangleGrid grid(scalp);
  HeadExit exit = [](const Vec3& p, double& value) {
    if (p.x() > -1.0 && p.y() < 0.45) {
      value = p.y() - 0.4;
      return Vec3(p.x(), 0.45, p.z());
    }
    value = std::numeric_limits<double>::infinity();
    return p;
  };
  exit.chord_crossing = [&](const Vec3& a, const Vec3& b, bool from_root, ChordCrossing& first) {
    const SegmentHit hit = grid.first_crossing(a, b, 1e-6, from_root ? 1e-6 : -1e-6, 1 + 1e-6);
    if (!hit.found()) return false;
    first = {hit.t, a + hit.t * (b - a), triangle_normal(scalp, hit.triangle)};
    return true;
  };
  auto crosses = [&](const Vec3& a, const Vec3& b) {  // every triangle, no grid, the root's own touch aside
    for (const Vec3i& f : scalp.triangles)
      if (!std::isnan(segment_triangle_parameter(a, b, scalp.positions[f[0]], scalp.positions[f[1]],
                                                 scalp.positions[f[2]], 0.0, 1e-9, 1.0)))
        return true;
    return false;
  };
  std::vector<Vec3> line;
  const Vec3 pore(0.5, 0.2, 0.0);
  for (int k = 0; k <= 20; ++k) line.push_back(pore + 0.25 * k * Vec3(1.0, 0.5, 0.0).normalized());
  Curves guides;
  guides.add(line, 0);
  Pores pores;
  pores.positions = {pore};
  pores.lengths = {4.0};
  pores.guide = {0};
  pores.normals = {Vec3(0, -1, 0)};
  StrandOptions o;
  o.wisp.points = 16;
  StrandSurroundings around;
  around.out_of_head = exit;
  const Strands s = make_strands(guides, pores, o, around, Exec{1, {}}).strands;
  CHECK(s.scalp_crossings == 0);  // 1 when only turns toward the pore's normal are tried
  const std::vector<Vec3> fibre(s.fibres.points.begin(), s.fibres.points.end());
  REQUIRE(fibre.size() >= 2);
  CHECK(fibre[0] == pore);
  for (std::size_t k = 1; k < fibre.size(); ++k) {
    CAPTURE(k);
    CHECK(!crosses(fibre[k - 1], fibre[k]));
  }
  // The first chord leaves above the pore's triangle, into the pocket, and reaches neither the
  // riser nor the bottom sheet; the nearest such direction to the chord it had runs along the fold.
  const Vec3 first = fibre[1] - fibre[0];
  CHECK(-first.y() >= kRootRise * first.norm() - 1e-12);
  CHECK(fibre[1].y() > 0.0);
  CHECK(fibre[1].x() < 0.75);
  CHECK(std::fabs(fibre[1].z()) > 0.05);
  // Before the turn the chord ran from the pore to (0.72, 0.45, 0): lifted to kProbeClearance
  // (0.03 cm) in front of the riser, then up to the exit's level. The turn keeps its length L and
  // goes no further than the next cone (5°, and a cone's samples at most 5.5° apart round it) past
  // the least angle to a clear direction: d·(0, −1, 0) ≥ kRootRise, x = 0.5 + L·d_x < 0.75, so
  // d_x < 0.25/L, with d_z taking up the rest (the bottom sheet is then out of reach).
  const Vec3 before = Vec3(0.72, 0.45, 0.0) - pore, a = before.normalized();
  CHECK(first.norm() == doctest::Approx(before.norm()).epsilon(1e-12));
  const double dx = 0.25 / before.norm(), dy = -kRootRise;
  const double least = std::acos(a.x() * dx + a.y() * dy);  // 62.0°
  const double turned = std::acos(std::clamp(first.normalized().dot(a), -1.0, 1.0));
  CHECK(turned >= least);
  CHECK(turned <= least + 7.5 * M_PI / 180.0);
  // The next chord runs from the pocket up through the fold, which the exit (seeing the fold
  // filled in) cannot lift it off: the fibre ends before it, at the skin.
  CHECK(fibre.size() == 2);
  CHECK(s.cut_at_scalp == 1);
  CHECK(s.fibres.points == make_strands(guides, pores, o, around, Exec{3, {}}).strands.fibres.points);
}
