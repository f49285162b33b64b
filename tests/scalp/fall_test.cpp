// The fall from the hull (scalp/fall.h) against exact path lengths on walls, slopes, floors and a
// sphere, its pull toward a share of the layer's depth, the rim heights of a level hairline, and
// the hair the hull gives (scalp/hull_hair.h) from known falls.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "scalp/hanging.h"
#include "scalp/growth_field.h"
#include "scalp/hull_hair.h"
#include "tests/scalp/scalp_meshes.h"

using namespace hairfit;

namespace {

using Field = std::function<void(const Vec3&, double&, Vec3&)>;

// The plane through `through` with unit normal m, positive on m's side.
Field plane(const Vec3& m, const Vec3& through = Vec3::Zero()) {
  return [m, through](const Vec3& p, double& value, Vec3& gradient) {
    value = m.dot(p - through);
    gradient = m;
  };
}

// The larger (`larger`: their intersection) or the smaller (their union) of two fields, with the
// gradient of that one.
Field extreme(Field a, Field b, bool larger) {
  return [a, b, larger](const Vec3& p, double& value, Vec3& gradient) {
    double va, vb;
    Vec3 ga, gb;
    a(p, va, ga);
    b(p, vb, gb);
    const bool first = larger ? va >= vb : va <= vb;
    value = first ? va : vb;
    gradient = first ? ga : gb;
  };
}
Field intersection(Field a, Field b) { return extreme(std::move(a), std::move(b), true); }
Field union_of(Field a, Field b) { return extreme(std::move(a), std::move(b), false); }

// The sphere of radius R about the origin, negative inside.
Field sphere(double R) {
  return [R](const Vec3& p, double& value, Vec3& gradient) {
    value = p.norm() - R;
    gradient = p.normalized();
  };
}

// A region whose floor is the height `floor`: the hull holds the hair above it (and, with `outer`,
// inside that field too).
FallRegion region(Field skin, double floor, double step, Field outer = {}) {
  FallRegion r;
  r.skin = std::move(skin);
  const Field above = plane(Vec3(0, -1, 0), Vec3(0, floor, 0));
  r.hull = outer ? intersection(outer, above) : above;
  r.step = step;
  return r;
}

// A rim at height h all round the vertical axis.
RimHeights level_rim(double h) {
  RimHeights rim;
  rim.heights.assign(kRimBins, h);
  return rim;
}

// A sphere's cap of radius kCapRadius to kCapRim from the pole (up = +y), on `rings` rings, as a
// scalp chart (front +z, down −y).
constexpr double kCapRadius = 9.0, kCapRim = M_PI / 3.0;
ScalpChart cap_chart(int rings) {
  const Mesh cap = test::ring_disk(
      rings,
      [](double r, double phi) {
        const double theta = r * kCapRim;
        return Vec3(kCapRadius * std::sin(theta) * std::cos(phi), kCapRadius * std::cos(theta),
                    kCapRadius * std::sin(theta) * std::sin(phi));
      },
      [](const Vec3& p) { return p; });
  return make_scalp_chart(cap, Vec3(0, 0, 1), Vec3(0, -1, 0), "cap.obj");
}

}  // namespace

TEST_CASE("the fall runs straight down a wall to the layer's floor, to a 2⁻²⁰ step") {
  for (double step : {0.3, 0.1, 0.07}) {
    CAPTURE(step);
    const FallRegion wall = region(plane(Vec3(1, 0, 0)), -5.0, step);
    const Fall f = fall_from(wall, level_rim(-1.0), Vec3::Zero(), Vec3(1, 0, 0), 20.0, kNoDepth, true);
    CHECK(f.length == doctest::Approx(5.0).epsilon(1e-6));
    CHECK(f.below_rim == doctest::Approx(4.0).epsilon(1e-6));
    CHECK(f.nodes.back().y() == doctest::Approx(-5.0).epsilon(1e-6));
    CHECK(f.nodes.back().x() == doctest::Approx(kHangStart).epsilon(1e-12));
    // The cap ends it.
    const Fall capped = fall_from(wall, level_rim(-1.0), Vec3::Zero(), Vec3(1, 0, 0), 3.0, kNoDepth);
    CHECK(capped.length == doctest::Approx(3.0).epsilon(1e-12));
    CHECK(capped.below_rim == doctest::Approx(2.0).epsilon(1e-6));
  }
}

TEST_CASE("the fall slides down a sloping skin, kFallClearance off it, to the floor") {
  // Skin with unit normal m = (0.8, 0.6, 0): down along it is (0.6, −0.8, 0). The bead slides at
  // kFallClearance off the skin from the start's height down to the floor at −4.
  const Vec3 m(0.8, 0.6, 0.0);
  const FallRegion slope = region(plane(m), -4.0, 0.05);
  const Fall f = fall_from(slope, level_rim(10.0), Vec3::Zero(), m, 20.0, kNoDepth, true);
  const Vec3 end = f.nodes.back();
  CHECK(end.y() < -4.0 + 0.05);  // where its last step would leave through the skin or the floor
  CHECK(m.dot(end) == doctest::Approx(kFallClearance).epsilon(0.2));
  // Along the slope from the start (height 0.6·kHangStart) to the floor: 1/0.8 cm a cm of height.
  CHECK(std::fabs(f.length - (4.0 + 0.6 * kHangStart) / 0.8) < 0.1);
  CHECK(f.below_rim == doctest::Approx(f.length).epsilon(1e-12));  // all of it below a rim at 10
}

TEST_CASE("on a skin flatter than kFallSlope the fall leans over kCrownLean and rests") {
  const Vec3 m = Vec3(0.1, 1.0, 0.0).normalized();  // sin of the slope: 0.0995 < kFallSlope
  const FallRegion flat = region(plane(m), -4.0, 0.05);
  const Fall f = fall_from(flat, level_rim(10.0), Vec3::Zero(), m, 20.0, kNoDepth);
  CHECK(f.length >= kCrownLean);
  CHECK(f.length <= kCrownLean + 0.05 + 1e-9);
  // Steeper than kFallSlope it slides on to the floor.
  const Vec3 steep = Vec3(0.2, 1.0, 0.0).normalized();  // 0.196
  const Fall g = fall_from(region(plane(steep), -4.0, 0.05), level_rim(10.0), Vec3::Zero(), steep, 100.0, kNoDepth);
  CHECK(g.length > 4.0 / 0.196 - 1.0);
}

TEST_CASE("the fall from the crown of a sphere leans over, runs round it and hangs to the floor") {
  // A skull of radius 8 under a layer 2 cm thick, cut off 5 cm below the centre. From the crown
  // the bead leans toward −front, runs a quarter great circle on the skin (8·π/2, within the
  // clearance), leaves it where it turns under, and falls 5 cm to the floor.
  const double R = 8.0, c = 5.0;
  FallRegion r;
  r.skin = sphere(R);
  r.hull = intersection(sphere(R + 2.0), plane(Vec3(0, -1, 0), Vec3(0, -c, 0)));
  r.step = 0.05;
  const Fall f = fall_from(r, level_rim(0.0), Vec3(0, R, 0), Vec3(0, 1, 0), 100.0, kNoDepth, true);
  const Vec3 end = f.nodes.back();
  CHECK(end.y() == doctest::Approx(-c).epsilon(1e-6));
  CHECK(end.z() < -R);                  // behind the head, toward −front
  CHECK(std::fabs(end.x()) < 1e-9);     // in the plane of front and down
  CHECK(std::fabs(f.length - (R * M_PI / 2 + c)) < 0.3);
  CHECK(std::fabs(f.below_rim - c) < 0.1);
}

TEST_CASE("the fall is pulled to its share of the layer's depth and keeps it") {
  // A wall of hair 4 cm deep (skin x = 0, hull x = 4) down to y = −10: at share ½ the bead moves
  // from kHangStart off the skin to x = 2 within a few kFallDepthReach and falls there.
  FallRegion r = region(plane(Vec3(1, 0, 0)), -10.0, 0.05, plane(Vec3(1, 0, 0), Vec3(4, 0, 0)));
  const Fall f = fall_from(r, level_rim(0.0), Vec3::Zero(), Vec3(1, 0, 0), 100.0, 0.5, true);
  CHECK(f.nodes.back().y() == doctest::Approx(-10.0).epsilon(1e-6));
  CHECK(std::fabs(f.nodes.back().x() - 2.0) < 0.05);
  for (const Vec3& p : f.nodes) CHECK(p.x() <= 2.0 + 1e-9);  // it never overshoots its depth
  // Without a target it falls straight down where it started.
  const Fall straight = fall_from(r, level_rim(0.0), Vec3::Zero(), Vec3(1, 0, 0), 100.0, kNoDepth, true);
  CHECK(straight.nodes.back().x() == doctest::Approx(kHangStart).epsilon(1e-12));
}

TEST_CASE("a root outside the region has no fall") {
  const FallRegion wall = region(plane(Vec3(1, 0, 0)), -5.0, 0.1);
  CHECK(fall_from(wall, level_rim(0.0), Vec3(0, -6, 0), Vec3(1, 0, 0), 20.0, kNoDepth).length == 0.0);
  CHECK(fall_from(wall, level_rim(0.0), Vec3::Zero(), Vec3(1, 0, 0), 0.0, kNoDepth).length == 0.0);
}

TEST_CASE("the rim heights of a level hairline are its height all round") {
  // A sphere's cap down to the polar angle 1.2: its hairline is the circle at height 8·cos 1.2.
  const Mesh cap = test::head_cap(8, 1.2, 0.0, 8.0, 8.0, 8.0);
  const ScalpChart chart = make_scalp_chart(cap, Vec3(0, 0, 1), Vec3(0, -1, 0), "cap.obj");
  const RimHeights rim = rim_heights(chart);
  REQUIRE(rim.heights.size() == static_cast<std::size_t>(kRimBins));
  CHECK(rim.centre.y() == doctest::Approx(8.0 * std::cos(1.2)).epsilon(1e-12));
  for (double h : rim.heights) CHECK(std::fabs(h) < 1e-12);
  CHECK(rim.below(Vec3(3, -3, 5)) == doctest::Approx(8.0 * std::cos(1.2) + 3.0).epsilon(1e-12));
  CHECK(rim.below(Vec3(0, 20, 0)) < 0.0);
}

TEST_CASE("hair from the hull: lying above the rim, hanging past kHangRamp below it, smooth between") {
  std::vector<Fall> falls(4);
  falls[0].length = 3.0, falls[0].below_rim = 0.0;                 // a cap: keeps the lying length
  falls[1].length = 30.0, falls[1].below_rim = kHangRamp;          // hangs its fall's length
  falls[2].length = 20.0, falls[2].below_rim = 0.5 * kHangRamp;    // half and half
  falls[3].length = 1.2, falls[3].below_rim = kHangRamp;           // hangs, but no shorter than the least
  const HullHair h = hull_hair(falls, 6.0);
  CHECK(h.hangs);
  CHECK(h.hang_weights[0] == 0.0);
  CHECK(h.lengths[0] == 6.0);
  CHECK(h.hang_weights[1] == 1.0);
  CHECK(h.lengths[1] == doctest::Approx(30.0 - kFallTipMargin).epsilon(1e-15));
  CHECK(h.hang_weights[2] == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(h.lengths[2] == doctest::Approx(0.5 * (20.0 - kFallTipMargin) + 0.5 * 6.0).epsilon(1e-15));
  CHECK(h.lengths[3] == kShortestHullHair);
  CHECK_FALSE(hull_hair({falls[0]}, 6.0).hangs);
}

TEST_CASE("the comb from the hull: a layer thickening up to the crown over the whole cap is a carved cap, unless its hair hangs") {
  // A sphere's cap of radius 9 to 60° from the pole (up = +y). The layer's thickness a + b·y grows
  // up along the scalp everywhere but at the pole, where its gradient is normal to the scalp.
  constexpr double kRadius = kCapRadius;
  const ScalpChart chart = cap_chart(24);
  const Mesh& mesh = chart.mesh;
  double total = 0.0, pole = 0.0;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    for (int v : mesh.triangles[t]) {
      total += triangle_area(mesh, t) / 3.0;
      if (mesh.positions[v].y() > kRadius - 1e-9) pole += triangle_area(mesh, t) / 3.0;
    }
  REQUIRE(pole > 0.0);
  auto slope = [](double b) {
    return ThicknessField([b](const Vec3& p) { return LayerThickness{1.0 + b * p.y(), Vec3(0.0, b, 0.0)}; });
  };
  std::vector<Fall> lying(mesh.positions.size()), hanging(mesh.positions.size());
  for (Fall& f : hanging) f.below_rim = kHangRamp;  // φ = 1
  const CombChoice up = comb_from_hull(chart, slope(0.1), lying);
  CHECK(up.thickening_up == doctest::Approx(1.0 - pole / total).epsilon(1e-12));
  CHECK(up.hanging == 0.0);
  CHECK(up.comb == Comb::from_crown);
  const CombChoice down = comb_from_hull(chart, slope(-0.1), lying);
  CHECK(down.thickening_up == 0.0);
  CHECK(down.comb == Comb::into_layer);
  const CombChoice flat = comb_from_hull(chart, slope(0.0), lying);  // no gradient: nowhere up
  CHECK(flat.thickening_up == 0.0);
  CHECK(flat.comb == Comb::into_layer);
  const CombChoice hangs = comb_from_hull(chart, slope(0.1), hanging);
  CHECK(hangs.hanging == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(hangs.comb == Comb::into_layer);
  // Up on the front half only (z > 0): about half the area, below the share a carved cap needs.
  const ThicknessField front = [](const Vec3& p) {
    return LayerThickness{1.0, Vec3(0.0, p.z() > 0.0 ? 0.1 : -0.1, 0.0)};
  };
  const CombChoice half = comb_from_hull(chart, front, lying);
  CHECK(half.thickening_up > 0.4);
  CHECK(half.thickening_up < 0.6);
  CHECK(half.comb == Comb::into_layer);
  CHECK_THROWS_AS(comb_from_hull(chart, slope(0.1), std::vector<Fall>(3)), std::invalid_argument);
}

TEST_CASE("combed hair: as long as the layer ahead to the rim, less the margin; a speck of no layer is no end") {
  // A sphere's cap of radius 9 to 60° from the pole; the layer covers it and ends past the rim.
  constexpr double kRadius = kCapRadius, kRim = kCapRim;
  const ScalpChart chart = cap_chart(36);
  const Vec3 speck = chart.mesh.positions[0];  // the pole
  auto polar = [](const Vec3& p) { return std::acos(std::clamp(p.normalized().y(), -1.0, 1.0)); };
  const ThicknessField layer = [&](const Vec3& p) {
    return LayerThickness{polar(p) <= kRim + 1e-9 ? 1.0 : -1.0, Vec3::Zero()};
  };
  const std::vector<double> lengths = combed_lengths(chart, layer, 25.0);
  // The pole: the geodesic to the rim, 9·π/3 = 9.42 cm, by edges on 36 rings: no shorter than the
  // meridian's chords (each ring step Δ shrinks to 2·sin(Δ/2)), and up to 8 % longer where the
  // shortest way by edges zigzags across the rings.
  const double step = kRim / 36.0, chord = std::sin(0.5 * step) / (0.5 * step);
  const double exact = chord * kRadius * kRim - kCombedTipMargin;
  CHECK(lengths[0] >= exact - 1e-9);
  CHECK(lengths[0] <= exact * 1.04);
  // The combed length of a way d to the end: d − 2 cm, a third of d within 3 cm of the end, at
  // least kShortestCombedHair; monotone in d, so the bounds on the way bound the length.
  auto rule = [](double d) {
    return std::clamp(std::max(d - kCombedTipMargin, d / 3.0), kShortestCombedHair, kLongestCombedHair);
  };
  CHECK(rule(3.0) == doctest::Approx(1.0));  // the two rules meet at 3 cm
  int near_end = 0;
  for (std::size_t v = 0; v < lengths.size(); ++v) {
    CAPTURE(v);
    const double ahead = kRadius * (kRim - polar(chart.mesh.positions[v]));  // geodesic, meridian to the rim
    CHECK(lengths[v] >= rule(chord * ahead) - 1e-6);
    CHECK(lengths[v] <= rule(1.09 * ahead) + 1e-6);  // by edges: up to 8.7 % longer by the rim
    // Within 3 cm of the end the hair ends before the layer does, short of it by two thirds.
    if (ahead > 0.3 && ahead < 3.0) {
      ++near_end;
      CHECK(lengths[v] <= 0.4 * ahead);
    }
  }
  CHECK(near_end > 100);  // the rings within 3 cm of the rim
  // No layer in a speck at the pole: the paper's layer end counts it, the combed length does not.
  const ThicknessField specked = [&](const Vec3& p) {
    return LayerThickness{(p - speck).norm() < 0.1 ? -1.0 : layer(p).value, Vec3::Zero()};
  };
  const std::vector<double> combed = combed_lengths(chart, specked, 25.0);
  CHECK(combed[0] == doctest::Approx(lengths[0]));
  std::vector<double> thickness(chart.mesh.positions.size());
  for (std::size_t v = 0; v < thickness.size(); ++v) thickness[v] = specked(chart.mesh.positions[v]).value;
  CHECK(layer_end_distance(chart, thickness, specked, kLayerEndProbe)[0] == 0.0);
  CHECK(layer_end_distance(chart, thickness, specked, kLayerEndProbe, true)[0] == doctest::Approx(lengths[0] + kCombedTipMargin));
  // A layer that never ends: the fallback.
  const ThicknessField everywhere = [](const Vec3&) { return LayerThickness{1.0, Vec3::Zero()}; };
  for (double l : combed_lengths(chart, everywhere, 25.0)) CHECK(l == 25.0);
}

TEST_CASE("in the bowl at the bottom of a bag the fall rests where it reached the bottom") {
  // A scalp cap of radius 8 closed by its floor (y = 0) inside a closed bag of radius 20 about
  // the same centre. From the scalp, pulled to the middle of the layer's depth, the bead runs
  // round the cap, falls from its rim and reaches the bag's bottom, where the layer's depth runs
  // up to the floor: the pull lifts the bead, it falls back a little lower, and so on round the
  // bowl for long after it stopped falling. Wherever it ends, it got there falling: it is within
  // kFallSlope·kFallStall of its lowest node, and went at most kFallStall on past the first node
  // that low.
  FallRegion r;
  r.skin = intersection(sphere(8.0), plane(Vec3(0, -1, 0)));
  r.hull = sphere(20.0);
  r.step = 0.1;
  for (const Vec3& root : {Vec3(0, 8, 0), Vec3(4, 6.9282, 0), Vec3(0, 4, -6.9282)}) {
    const Fall f = fall_from(r, level_rim(0.0), root, root.normalized(), 200.0, 0.5, true);
    REQUIRE(f.nodes.size() > 2);
    const double end = -f.nodes.back().y();
    double lowest = end, length = 0.0, first_low = -1.0;
    for (std::size_t k = 0; k < f.nodes.size(); ++k) {
      if (k > 0) length += (f.nodes[k] - f.nodes[k - 1]).norm();
      lowest = std::max(lowest, -f.nodes[k].y());
      if (first_low < 0.0 && -f.nodes[k].y() >= end - kFallSlope * kFallStall) first_low = length;
    }
    CHECK(end > 15.0);  // it reached the bowl
    CHECK(lowest - end <= kFallSlope * kFallStall + 1e-9);
    CHECK(length - first_low <= kFallStall + r.step + 1e-9);
  }
}

TEST_CASE("over a crown under a thick layer the pull lifts the bead off the skin only where the skin goes on as a shell") {
  // A skull of radius 8 under a hull of radius 12, the bead pulled to 0.15 of the depth (near the
  // hull). With a shell past the hairline the layer's depth runs across the hair everywhere, and
  // the bead rises toward its depth on the way round; with the head's floor past the hairline the
  // pull never lifts, so over the crown the bead keeps to the skin until its way turns down.
  FallRegion r;
  r.skin = sphere(8.0);
  r.hull = sphere(12.0);
  r.step = 0.1;
  auto highest_off_skin = [&](bool floor) {
    r.floor_past_hairline = floor;
    const Fall f = fall_from(r, level_rim(0.0), Vec3(0, 8, 0), Vec3(0, 1, 0), 12.0, 0.15, true);
    double off = 0.0;
    for (const Vec3& p : f.nodes)
      if (p.y() > 4.0) off = std::max(off, p.norm() - 8.0);
    return off;
  };
  CHECK(highest_off_skin(false) > 1.5);
  CHECK(highest_off_skin(true) < 0.5);
}

namespace {

// A capped vertical cylinder about the y axis, negative inside: the largest of the three
// distances out through its side, its bottom and its top, with that one's gradient. Its bottom
// rises by `rise` per cm out from the axis (a cone's, 0 for a flat one).
Field cylinder(double radius, double bottom, double top, double rise = 0.0) {
  return [=](const Vec3& p, double& value, Vec3& gradient) {
    const double r = std::hypot(p.x(), p.z());
    const Vec3 out = r > 0.0 ? Vec3(p.x() / r, 0, p.z() / r) : Vec3(1, 0, 0);
    value = r - radius, gradient = out;
    const double norm = std::sqrt(1.0 + rise * rise);
    const double below = (bottom + rise * r - p.y()) / norm;
    if (below > value) value = below, gradient = (rise * out - Vec3(0, 1, 0)) / norm;
    if (p.y() - top > value) value = p.y() - top, gradient = Vec3(0, 1, 0);
  };
}


}  // namespace

TEST_CASE("below a head closed by its floor the bead gets round a braid's ledge instead of resting on it") {
  // Under a cap closed by its floor (y = 0), a tube of radius 3 and a narrower one of radius 1.5
  // on down to y = −25, the wider one's bottom a ledge that rises 0.3 a cm out from the narrower
  // one's wall at y = −12: flatter than kHullWallSlope, so a bead sliding on it rests. Hair from
  // under the floor, 2.5 from the axis, falls to the ledge; the level pull toward its depth alone
  // leaves it resting there, the whole pull lifts it off, in over the edge and on down the narrower
  // tube.
  FallRegion r;
  r.skin = intersection(sphere(8.0), plane(Vec3(0, -1, 0)));
  r.hull = union_of(sphere(10.0), union_of(cylinder(3.0, -12.0 - 0.3 * 1.5, 1.0, 0.3), cylinder(1.5, -25.0, -11.0)));
  r.step = 0.05;
  const Fall f = fall_from(r, level_rim(0.0), Vec3(2.5, 0, 0), Vec3(0, -1, 0), 100.0, 0.3, true);
  REQUIRE(!f.nodes.empty());
  CHECK(f.nodes.back().y() < -20.0);
  for (const Vec3& p : f.nodes) {
    double v;
    Vec3 g;
    r.hull(p, v, g);
    CHECK(v <= 0.0);
  }
}
