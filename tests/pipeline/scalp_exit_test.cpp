// The strands stage's head exit (pipeline/scalp_exit.h) on exact planes: a point behind the
// scalp moves out to the clearance, and, with the volume given, nearer the scalp where the layer
// in front of it is thinner than that.
#include <doctest/doctest.h>

#include "field/distance_field.h"
#include "pipeline/scalp_exit.h"

using namespace hairfit;

namespace {

// The closed box [lo, hi], its triangles facing out.
Mesh box(const Vec3& lo, const Vec3& hi) {
  Mesh m;
  for (int k = 0; k < 8; ++k) m.positions.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.emplace_back(q[0], q[1], q[2]);
    m.triangles.emplace_back(q[0], q[2], q[3]);
  }
  return m;
}

// The head: the box below z = 0, so that near the top face's centre the scalp field reads z.
const DistanceField& head() {
  static const DistanceField f = make_distance_field(box(Vec3(-2, -2, -1), Vec3(2, 2, 0)), FieldSpec{0.05, 4, 0.3, 1.0, "scalp"}, 2);
  return f;
}

// The hair volume, the head and a layer `t` thick over it: the field reads z − t there.
DistanceField volume(double t) { return make_distance_field(box(Vec3(-2, -2, -1), Vec3(2, 2, t)), FieldSpec{0.05, 4, 0.3, 1.0, "volume"}, 2); }

double moved_to(const HeadExit& exit, double z) {
  double scalp = 0.0;
  return exit(Vec3(0.1, -0.2, z), scalp).z();
}

}  // namespace

TEST_CASE("the head exit keeps the clearance, and where the layer is thinner, stops where the layer holds the point") {
  REQUIRE(head().value(Vec3(0.1, -0.2, 0.3)) == doctest::Approx(0.3).epsilon(1e-12));  // exact on a plane
  // Without the volume: always the clearance.
  CHECK(moved_to(scalp_exit(head()), -0.01) == doctest::Approx(kHeadExitClearance).epsilon(1e-9));
  const struct {
    double layer, from, to;
  } cases[] = {
      {0.2, -0.01, kHeadExitClearance},  // a layer thicker than the clearance
      {0.03, -0.01, 0.025},              // half the clearance is inside a 0.3 mm layer
      {0.02, -0.01, 0.0125},             // a quarter inside a 0.2 mm one
      {0.01, -0.01, kHeadExitClearance}, // none holds it: the head wins, as without the volume
      {0.04, 0.03, 0.03},                // in the layer already, nearer than the clearance: stays
      {0.02, 0.015, 0.015},
  };
  for (const auto& c : cases) {
    CAPTURE(c.layer);
    CAPTURE(c.from);
    const DistanceField v = volume(c.layer);
    CHECK(moved_to(scalp_exit(head(), nullptr, 1, &v), c.from) == doctest::Approx(c.to).epsilon(1e-9));
  }
  // A point in front of the clearance is left alone.
  const DistanceField v = volume(0.02);
  CHECK(moved_to(scalp_exit(head(), nullptr, 1, &v), 0.07) == 0.07);
}

TEST_CASE("layer placement: across the fibre over the scalp, fading to nothing kLayerBelowRim below its rim") {
  // The head's top face z = 0 under a layer 1 cm thick, so λ = z there; the rim taken level at
  // height `rim` along up = +z.
  const DistanceField hull = volume(1.0);
  auto rim_at = [](double height) {
    RimHeights r;
    r.up = Vec3::UnitZ(), r.e1 = Vec3::UnitX(), r.e2 = Vec3::UnitY();
    r.heights.assign(kRimBins, height);
    return r;
  };
  const Vec3 p(0.1, -0.2, 0.2), along = Vec3(1, 0, 1).normalized();
  // Over the scalp (the rim below p): λ 0.2 → 0.7, moved across the fibre, not along it.
  const auto over = layer_placement(head(), hull, rim_at(-1.0));
  const Vec3 q = over(p, along, 0.7, 1.0);
  CHECK(q.z() == doctest::Approx(0.7).epsilon(2e-3));
  CHECK(std::fabs((q - p).dot(along)) <= 1e-9);
  // Half the weight: half the way.
  CHECK(over(p, along, 0.7, 0.5).z() == doctest::Approx(0.45).epsilon(2e-3));
  // Below the rim by kLayerBelowRim or more: not moved; half way down the fade: by its smoothstep.
  const auto under = layer_placement(head(), hull, rim_at(p.z() + kLayerBelowRim));
  CHECK(under(p, along, 0.7, 1.0) == p);
  const auto halfway = layer_placement(head(), hull, rim_at(p.z() + 0.5 * kLayerBelowRim));
  CHECK(halfway(p, along, 0.7, 1.0).z() == doctest::Approx(0.45).epsilon(2e-3));
}

TEST_CASE("layer placement spreads the fibres through the top `spread` cm of a deeper layer") {
  // The head's top face under a layer 3 cm thick: λ = z/3 there. With a spread of 1.2 cm the
  // share 0.5 lies 0.6 cm under the hull, z = 2.4; without one, half way up, z = 1.5. In a
  // layer 1 cm thick (thinner than the spread) the share is λ itself: z = 0.7.
  // Boxes wide and deep enough that their top faces are the nearest to every point the moves
  // reach (inside the 3 cm layer too), the head's field reaching 3.5 cm over its top face; both
  // fields exact there (bands 3.6 cm wide, planes).
  const DistanceField tall_head =
      make_distance_field(box(Vec3(-4, -4, -4), Vec3(4, 4, 0)), FieldSpec{0.1, 36, 3.5, 1.0, "scalp"}, 2);
  const DistanceField deep = make_distance_field(box(Vec3(-4, -4, -4), Vec3(4, 4, 3)), FieldSpec{0.1, 36, 0.5, 1.0, "volume"}, 2);
  const DistanceField thin = make_distance_field(box(Vec3(-4, -4, -4), Vec3(4, 4, 1)), FieldSpec{0.1, 36, 0.5, 1.0, "volume"}, 2);
  // A fibre lying nearly along the layer, so that the move across it stays nearer the top face
  // than the boxes' sides.
  const Vec3 p(0.1, -0.2, 0.2), along = Vec3(1, 0, 0.25).normalized();
  REQUIRE(tall_head.value(Vec3(0.1, -0.2, 2.4)) == doctest::Approx(2.4).epsilon(1e-9));
  REQUIRE(deep.value(Vec3(0.1, -0.2, 2.4)) == doctest::Approx(-0.6).epsilon(1e-9));
  REQUIRE(deep.value(p) == doctest::Approx(-2.8).epsilon(1e-9));
  const Vec3 spread = layer_placement(tall_head, deep, RimHeights{}, 1.2)(p, along, 0.5, 1.0);
  CHECK(spread.z() == doctest::Approx(2.4).epsilon(1e-6));
  CHECK(std::fabs((spread - p).dot(along)) <= 1e-9);
  CHECK(layer_placement(tall_head, deep, RimHeights{})(p, along, 0.5, 1.0).z() == doctest::Approx(1.5).epsilon(1e-6));
  CHECK(layer_placement(tall_head, thin, RimHeights{}, 1.2)(p, along, 0.7, 1.0).z() == doctest::Approx(0.7).epsilon(1e-6));
  // Half the weight: half the way from λ(p) to the spread depth 0.8, z = 3·(0.2/3 + 0.5·(0.8 − 0.2/3)) = 1.3.
  CHECK(layer_placement(tall_head, deep, RimHeights{}, 1.2)(p, along, 0.5, 0.5).z() == doctest::Approx(1.3).epsilon(1e-6));
}
