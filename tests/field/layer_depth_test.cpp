#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "core/random.h"
#include "field/layer_depth.h"
#include "tests/field/sampled_field.h"

using namespace hairfit;

using hairfit::test::sampled;

TEST_CASE("layer depth: value and gradient of λ = S/(S − V) against the formula and central differences") {
  // Concentric spheres about the origin: the scalp r = 3, the hull r = 4.2, analytic values and gradients.
  const double R = 3.0, T = 1.2;
  auto fields = [&](const Vec3& p, FieldValueGradient& s, FieldValueGradient& v) {
    const double r = p.norm();
    s.value = r - R, s.gradient = p / r;
    v.value = r - R - T, v.gradient = p / r;
  };
  Random random(5, RandomStage::test, 0);
  for (int n = 0; n < 100; ++n) {
    const Vec3 p = random.uniform(2.5, 5.0) * Vec3(random.normal(), random.normal(), random.normal()).normalized();
    FieldValueGradient s, v;
    fields(p, s, v);
    const LayerDepth d = layer_depth(s, v);
    CHECK(d.thickness == doctest::Approx(T).epsilon(1e-12));
    CHECK(d.value == doctest::Approx((p.norm() - R) / T).epsilon(1e-12));
    const double e = 1e-6;
    for (int a = 0; a < 3; ++a) {
      Vec3 step = Vec3::Zero();
      step[a] = e;
      FieldValueGradient s1, v1, s0, v0;
      fields(p + step, s1, v1);
      fields(p - step, s0, v0);
      const double derivative = (layer_depth(s1, v1).value - layer_depth(s0, v0).value) / (2 * e);
      CHECK(d.gradient[a] == doctest::Approx(derivative).epsilon(1e-6).scale(1.0));
    }
  }
  // Where the two surfaces meet (S − V ≤ 0), nothing is defined.
  FieldValueGradient s, v;
  s.value = 0.5, v.value = 0.5;
  CHECK(layer_depth(s, v).thickness == 0.0);
  v.value = std::nan("");
  CHECK(layer_depth(s, v).thickness == 0.0);
}

TEST_CASE("to_layer_depth: exact between parallel planes, and within the interpolant's error between spheres") {
  Random random(6, RandomStage::test, 0);
  {
    // Tilted parallel planes n·p = 0.3 (the scalp) and n·p = 1.1 (the hull): both fields are
    // linear, their trilinear samples exact, so one Newton step lands exactly, along n.
    const Vec3 n = Vec3(0.3, -0.5, 0.8).normalized();
    const DistanceField scalp = sampled([&](const Vec3& p) { return n.dot(p) - 0.3; }, Vec3(-3, -3, -3), 0.25, 25);
    const DistanceField hull = sampled([&](const Vec3& p) { return n.dot(p) - 1.1; }, Vec3(-3, -3, -3), 0.25, 25);
    for (int k = 0; k < 100; ++k) {
      const Vec3 p(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
      const double target = random.uniform(-0.2, 1.2);
      const LayerDepth at_p = layer_depth(scalp.value_and_gradient(p), hull.value_and_gradient(p));
      const Vec3 q = to_layer_depth(scalp, hull, p, at_p, target);
      CHECK(n.dot(q) - 0.3 == doctest::Approx(0.8 * target).epsilon(1e-9).scale(1.0));
      CHECK((q - p).cross(n).norm() <= 1e-9);
      // Across a fibre at 60-86° to the layer's normal (a fibre lying in the layer): still exact
      // in one step, and the move is normal to the fibre, along ∇λ less its part along the fibre.
      const Vec3 e = n.unitOrthogonal();
      const double angle = random.uniform(1.05, 1.5);
      const Vec3 along = std::cos(angle) * n + std::sin(angle) * e;
      const Vec3 r = to_layer_depth(scalp, hull, p, at_p, target, &along);
      CHECK(n.dot(r) - 0.3 == doctest::Approx(0.8 * target).epsilon(1e-9).scale(1.0));
      CHECK(std::fabs((r - p).dot(along)) <= 1e-9);
      const Vec3 across = (n - n.dot(along) * along).normalized();
      CHECK((r - p).cross(across).norm() <= 1e-9);
    }
  }
  {
    // Spheres r = 3 and r = 4 sampled at h = 0.1: λ = r − 3 up to the interpolant's error, which
    // for r sampled at h is at most h²/(2r) < 2e-3.
    const double h = 0.1;
    const DistanceField scalp = sampled([](const Vec3& p) { return p.norm() - 3.0; }, Vec3(-5, -5, -5), h, 101);
    const DistanceField hull = sampled([](const Vec3& p) { return p.norm() - 4.0; }, Vec3(-5, -5, -5), h, 101);
    for (int k = 0; k < 100; ++k) {
      const Vec3 u = Vec3(random.normal(), random.normal(), random.normal()).normalized();
      const Vec3 p = random.uniform(3.05, 3.95) * u;
      const double target = random.uniform(0.1, 0.9);
      const LayerDepth at_p = layer_depth(scalp.value_and_gradient(p), hull.value_and_gradient(p));
      const Vec3 q = to_layer_depth(scalp, hull, p, at_p, target);
      CHECK(std::fabs(q.norm() - (3.0 + target)) <= 2e-3);
      // Moved across the layer, not along it: the interpolant's gradient leans off the radius by
      // O(h/r), over a move of at most one layer.
      CHECK(q.normalized().cross(u).norm() <= 5e-3);
    }
  }
}

TEST_CASE("spread_layer_depth: the top `spread` cm of a deeper layer, the whole of a thinner one") {
  // A layer 6 cm deep, fibres spread through its top 1.2 cm: the share s lies (1 − s)·1.2 cm
  // under the hull, λ = 1 − (1 − s)·1.2/6. Kept clear at either side by a tenth of the spread:
  // the top fibre (s = 0.9) 0.12 cm under the hull, the lowest (s = 0.1) 1.08 cm.
  CHECK(spread_layer_depth(0.9, 6.0, 1.2) == doctest::Approx(0.98).epsilon(1e-15));
  CHECK(spread_layer_depth(0.1, 6.0, 1.2) == doctest::Approx(0.82).epsilon(1e-15));
  CHECK((1.0 - spread_layer_depth(0.1, 6.0, 1.2)) * 6.0 == doctest::Approx(1.08).epsilon(1e-14));
  CHECK(spread_layer_depth(1.0, 6.0, 1.2) == 1.0);  // on the hull stays on it
  CHECK(spread_layer_depth(0.0, 6.0, 1.2) == doctest::Approx(0.8).epsilon(1e-15));
  // A layer the spread's depth or thinner, and no spread (not positive, not finite): the share.
  for (double spread : {1.2, 2.0, 0.0, -1.0, std::numeric_limits<double>::infinity(), std::nan("")}) {
    CAPTURE(spread);
    CHECK(spread_layer_depth(0.3, 1.2, spread) == 0.3);
  }
  // Continuous at the layer as deep as the spread.
  CHECK(spread_layer_depth(0.3, 1.2 * (1.0 + 1e-12), 1.2) == doctest::Approx(0.3).epsilon(1e-11));
}
