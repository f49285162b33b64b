// Hair that hangs (hair.tilt_toward = "hanging", scalp/hanging.h): the hang probe against exact
// path lengths on planes and a sphere, its weight and length rules, and roots and growth fields
// that reduce exactly to "thicker" where nothing hangs and to "down" where everything does.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "scalp/growth_field.h"
#include "scalp/hanging.h"
#include "scalp/roots.h"
#include "tests/scalp/scalp_meshes.h"

using namespace hairfit;

namespace {

// A skin that is the plane through the origin with unit normal m (distance m·p), and a volume
// above the height `floor`.
HangProbe plane_probe(const Vec3& m, double floor, double step) {
  HangProbe probe;
  probe.skin = [m](const Vec3& p, double& distance, Vec3& gradient) {
    distance = m.dot(p);
    gradient = m;
  };
  probe.in_volume = [floor](const Vec3& p) { return p.y() >= floor; };
  probe.step = step;
  return probe;
}

// A skull of radius R about the origin under a layer 2 cm thick, cut off below the height −c.
HangProbe sphere_probe(double R, double c, double step) {
  HangProbe probe;
  probe.skin = [R](const Vec3& p, double& distance, Vec3& gradient) {
    distance = p.norm() - R;
    gradient = p.normalized();
  };
  probe.in_volume = [R, c](const Vec3& p) { return p.norm() <= R + 2.0 && p.y() >= -c; };
  probe.step = step;
  return probe;
}

}  // namespace

TEST_CASE("the hang runs down a wall to where the layer ends, to a 2⁻²⁰ step") {
  for (double step : {0.3, 0.1, 0.07}) {
    CAPTURE(step);
    const HangProbe wall = plane_probe(Vec3(1, 0, 0), -5.0, step);
    CHECK(std::fabs(hang_length(wall, Vec3::Zero(), Vec3(1, 0, 0), 20.0) - 5.0) < 1e-6);
    // The hair's length caps it.
    CHECK(hang_length(wall, Vec3::Zero(), Vec3(1, 0, 0), 3.0) == doctest::Approx(3.0).epsilon(1e-12));
  }
}

TEST_CASE("the hang slides down a sloping skin within kHangHug of it, and falls straight beyond") {
  // Skin with unit normal m = (0.8, 0.6, 0): down along it is (0.6, −0.8, 0), 0.8 cm lower per
  // cm. From a root on the skin the probe starts 0.1 cm off it at height 0.06 and slides to the
  // floor at −4: 4.06 / 0.8 cm exactly.
  const Vec3 m(0.8, 0.6, 0.0);
  const HangProbe slope = plane_probe(m, -4.0, 0.05);
  CHECK(std::fabs(hang_length(slope, Vec3::Zero(), m, 20.0) - 4.06 / 0.8) < 1e-6);
  // From 2 cm off the skin (2.1 at the start) it falls straight down, nearing the skin by 0.6 per
  // cm, until it is within kHangHug, then slides: (2.1 − kHangHug) / 0.6 cm falling, the rest
  // of the drop from 1.26 to −4 at 0.8 per cm. The switch comes at the first step within reach,
  // so the exact figure holds to a step.
  const double step = 1e-3;
  const HangProbe fine = plane_probe(m, -4.0, step);
  const double fall = (2.1 - kHangHug) / 0.6, slide = (1.26 - fall - -4.0) / 0.8;
  CHECK(std::fabs(hang_length(fine, 2.0 * m, m, 20.0) - (fall + slide)) < 2.0 * step);
}

TEST_CASE("the hang follows a spherical skull down its meridian, converging with the step") {
  // Root at polar angle θ0 on a skull of radius R: the probe keeps 0.1 cm off it (drifting out
  // by O(step) over the path), down the meridian, until the height −c at cos θ = −c / (R + 0.1).
  constexpr double R = 8.0, c = 4.0, kStart = kHangStart;
  for (double theta0 : {0.5, 1.0, 1.6}) {
    CAPTURE(theta0);
    const Vec3 n(std::sin(theta0), std::cos(theta0), 0.0);
    const double rho = R + kStart;
    const double exact = rho * (std::acos(-c / rho) - theta0);
    double previous = INFINITY;
    for (double step : {0.1, 0.01, 0.001}) {
      CAPTURE(step);
      const double error = std::fabs(hang_length(sphere_probe(R, c, step), R * n, n, 30.0) - exact);
      MESSAGE("θ0 " << theta0 << ", step " << step << ": error " << error << " cm of " << exact);
      CHECK(error < 2.0 * step);
      if (std::isfinite(previous) && previous > 1e-6) CHECK(error < 0.3 * previous);  // first order
      previous = error;
    }
  }
  // At the crown down is normal to the skin: nowhere to fall.
  CHECK(hang_length(sphere_probe(R, c, 0.01), Vec3(0, R, 0), Vec3(0, 1, 0), 30.0) == 0.0);
}

TEST_CASE("heavy hair leaves the skull at its equator and hangs straight down; weightless hair follows it") {
  // The skull of the test above under a dome of radius R + 2 on a cylinder of that radius, cut
  // off at the height −c. From 0.1 cm off the skin at polar angle θ0 a heavy hair slides down the
  // skull to its equator, where the skin turns to face down, and hangs straight down from there
  // to −c; a weightless one keeps to the skull down to −c.
  constexpr double R = 8.0, c = 7.0;
  const double rho = R + kHangStart;
  auto probe = [&](double step, bool falls_free) {
    HangProbe p = sphere_probe(R, c, step);
    p.in_volume = [=](const Vec3& q) {
      return q.y() >= -c && (q.norm() <= R + 2.0 || (q.y() <= 0.0 && std::hypot(q.x(), q.z()) <= R + 2.0));
    };
    p.falls_free = falls_free;
    return p;
  };
  for (double theta0 : {0.5, 1.0, 2.0}) {
    CAPTURE(theta0);
    const Vec3 n(std::sin(theta0), std::cos(theta0), 0.0);
    // Below the equator the skin faces down from the root on: the hair hangs free at once.
    const double heavy = theta0 < M_PI / 2 ? rho * (M_PI / 2 - theta0) + c : rho * std::cos(theta0) + c;
    const double weightless = rho * (std::acos(-c / rho) - theta0);
    double previous = INFINITY;
    for (double step : {0.1, 0.01, 0.001}) {
      CAPTURE(step);
      const double error = std::fabs(hang_length(probe(step, true), R * n, n, 30.0) - heavy);
      MESSAGE("θ0 " << theta0 << ", step " << step << ": heavy error " << error << " cm of " << heavy);
      CHECK(error < 2.0 * step);
      if (std::isfinite(previous) && previous > 1e-6) CHECK(error < 0.3 * previous);  // first order
      previous = error;
      CHECK(std::fabs(hang_length(probe(step, false), R * n, n, 30.0) - weightless) < 2.0 * step);
    }
    CHECK(weightless - heavy > 1.0);  // the exact paths differ by the skull's underside
  }
}

TEST_CASE("the hang is zero for a root in the head, outside the volume, or where the field says nothing") {
  const HangProbe wall = plane_probe(Vec3(1, 0, 0), -5.0, 0.1);
  CHECK(hang_length(wall, Vec3(-1, 0, 0), Vec3(1, 0, 0), 10.0) == 0.0);   // in the head
  CHECK(hang_length(wall, Vec3(0, -6, 0), Vec3(1, 0, 0), 10.0) == 0.0);   // below the layer
  HangProbe blind = wall;
  blind.skin = [](const Vec3&, double& distance, Vec3& gradient) {
    distance = NAN;
    gradient = Vec3::Zero();
  };
  CHECK(hang_length(blind, Vec3::Zero(), Vec3(1, 0, 0), 10.0) == 0.0);
  CHECK(hang_length(wall, Vec3::Zero(), Vec3(1, 0, 0), 0.0) == 0.0);
}

TEST_CASE("hang weight and hanging length") {
  constexpr double L = 12.0;
  CHECK(hang_weight(0.0, L) == 0.0);
  CHECK(hang_weight(0.5 * L, L) == 0.5);
  CHECK(hang_weight(L, L) == 1.0);
  CHECK(hang_weight(3.0 * L, L) == 1.0);
  CHECK(hang_weight(1.0, 0.0) == 0.0);
  CHECK(hanging_length(L, 0.0, 0.0) == L);                  // nothing hangs: its own length
  CHECK(hanging_length(L, 0.5 * L, 0.5) == 0.75 * L);       // half: L − ½·(L − L/2)
  CHECK(hanging_length(L, L, 1.0) == L);                    // the layer holds all of it
  CHECK(hanging_length(L, 0.3 * L, 1.0) == 0.3 * L);        // a hanging hair ends where its layer does
  CHECK(hanging_length(L, 0.0, 1.0) == kShortestHangingHair);
  CHECK(hanging_length(0.5, 0.0, 1.0) == 0.5);              // never longer than it was
  CHECK(hanging_length(L, 0.2 * L, 7.0) == 0.2 * L);        // the weight is clamped to [0, 1]
}

TEST_CASE("downness: how far a growth direction points down along the skin") {
  const Vec3 down(0, -2, 0);  // need not be unit
  // On the side of a head (normal +x): straight down the skin is 1, across 0, up 0 (clamped).
  const Vec3 side(1, 0, 0);
  CHECK(downness(Vec3(0.3, -1, 0).normalized(), side, down) == doctest::Approx(1.0).epsilon(1e-15));
  CHECK(downness(Vec3(0.3, 0, 1).normalized(), side, down) == doctest::Approx(0.0));
  CHECK(downness(Vec3(0, 1, 0), side, down) == 0.0);
  CHECK(downness(Vec3(0, -1, 1).normalized(), side, down) == doctest::Approx(std::sqrt(0.5)).epsilon(1e-15));
  // At the crown down says nothing; a direction along the normal has no tangential part.
  CHECK(downness(Vec3(1, 0, 0), Vec3(0, 1, 0), down) == 0.0);
  CHECK(downness(side, side, down) == 0.0);
  // Halfway down the skull (normal at 45°): the tangent toward down is only |down × n| sure.
  const Vec3 n = Vec3(1, 1, 0).normalized();
  CHECK(downness(Vec3(1, -1, 0).normalized(), n, down) == doctest::Approx(std::sqrt(0.5)).epsilon(1e-15));
}

namespace {

// A cap θ ≤ 60° of the sphere of radius R about the origin (pole +y) under a 2 cm layer.
struct Cap {
  static constexpr double R = 8.0;
  ScalpChart chart;
  RootInputs inputs;
  Cap() {
    const Mesh cap = test::ring_disk(
        16,
        [](double r, double phi) {
          const double theta = r * M_PI / 3;
          return Vec3(R * std::sin(theta) * std::cos(phi), R * std::cos(theta), R * std::sin(theta) * std::sin(phi));
        },
        [](const Vec3& p) { return p; });
    chart = make_scalp_chart(cap, Vec3(0, 0, 1), Vec3(0, -1, 0), "cap.obj");
    // The depth below the hull r = R + 2 + 0.1·x: thicker toward +x.
    inputs.thickness = [](const Vec3& p) {
      const Vec3 radial = p.normalized();
      return LayerThickness{R + 2.0 + 0.1 * p.x() - p.norm(), Vec3(0.1, 0, 0) - radial};
    };
  }
};

RootOptions cap_options(TiltToward toward, FlowModel flow) {
  RootOptions o;
  o.density = 1.0;
  o.tilt = 70.0;
  o.length = 10.0;
  o.guides = 8;
  o.tilt_toward = toward;
  o.flow = flow;
  return o;
}

}  // namespace

TEST_CASE("hanging roots: nothing hangs gives the thicker roots, everything hangs gives down's directions") {
  Cap cap;
  for (FlowModel flow : {FlowModel::local, FlowModel::field}) {
    CAPTURE(static_cast<int>(flow));
    const Roots thicker = make_roots(cap.chart, cap.inputs, cap_options(TiltToward::thicker, flow), Exec{2, {}});
    RootInputs none = cap.inputs;
    none.hangs.assign(cap.chart.mesh.positions.size(), 0.0);
    const Roots still = make_roots(cap.chart, none, cap_options(TiltToward::hanging, flow), Exec{2, {}});
    REQUIRE(still.pores.size() == thicker.pores.size());
    REQUIRE(still.pores.size() > 100);
    CHECK(still.pores.positions == thicker.pores.positions);
    CHECK(still.pores.directions == thicker.pores.directions);
    CHECK(std::all_of(still.pores.hang_weights.begin(), still.pores.hang_weights.end(), [](double w) { return w == 0.0; }));
    CHECK(thicker.pores.hang_weights.empty());
    // No layer below any root: a root growing down is cut to where it ends (here at once: the
    // shortest hair), one growing up or across keeps its length.
    int shortened = 0, kept = 0;
    for (int i = 0; i < still.pores.size(); ++i) {
      const double w = downness(still.pores.directions[i], still.pores.normals[i], cap.chart.down);
      CHECK(still.pores.lengths[i] == hanging_length(10.0, 0.0, w));
      shortened += w > 0.5, kept += w == 0.0;
      if (w == 0.0) CHECK(still.pores.lengths[i] == 10.0);
    }
    CHECK(shortened > 10);
    CHECK(kept > 10);

    const Roots down = make_roots(cap.chart, cap.inputs, cap_options(TiltToward::down, flow), Exec{2, {}});
    RootInputs all = cap.inputs;
    all.hangs.assign(cap.chart.mesh.positions.size(), 20.0);  // more layer below than hair
    const Roots hanging = make_roots(cap.chart, all, cap_options(TiltToward::hanging, flow), Exec{2, {}});
    REQUIRE(hanging.pores.size() == down.pores.size());
    double worst = 0.0;
    for (int i = 0; i < hanging.pores.size(); ++i) {
      worst = std::max(worst, (hanging.pores.directions[i] - down.pores.directions[i]).norm());
      CHECK(hanging.pores.lengths[i] == 10.0);
      CHECK(hanging.pores.hang_weights[i] == 1.0);
      CHECK(hangs(hanging.pores, i));
    }
    CHECK(worst < 1e-12);

    // Half hanging: the length L − ½·(L − L/2), and a direction between the two.
    RootInputs half = cap.inputs;
    half.hangs.assign(cap.chart.mesh.positions.size(), 5.0);
    const Roots partly = make_roots(cap.chart, half, cap_options(TiltToward::hanging, flow), Exec{2, {}});
    for (int i = 0; i < partly.pores.size(); ++i) {
      const double w = std::max(0.5, downness(partly.pores.directions[i], partly.pores.normals[i], cap.chart.down));
      CHECK(partly.pores.lengths[i] == doctest::Approx(10.0 - 5.0 * w).epsilon(1e-9));
      CHECK(partly.pores.lengths[i] <= 7.5 + 1e-9);
      CHECK(partly.pores.hang_weights[i] == doctest::Approx(0.5).epsilon(1e-12));
      CHECK(!hangs(partly.pores, i));
    }
  }
}

TEST_CASE("heavy hair: the hang along the skull weighs the roots, the hang as it falls sets their length") {
  // Every root hangs along the skull (hangs 20 cm, more than the hair), but falling free the layer
  // below holds only 4 cm (falls): directions and weights are those of the hang, lengths L − (L − 4).
  Cap cap;
  for (FlowModel flow : {FlowModel::local, FlowModel::field}) {
    CAPTURE(static_cast<int>(flow));
    RootInputs along = cap.inputs;
    along.hangs.assign(cap.chart.mesh.positions.size(), 20.0);
    RootInputs heavy = along;
    heavy.falls.assign(cap.chart.mesh.positions.size(), 4.0);
    const Roots light = make_roots(cap.chart, along, cap_options(TiltToward::hanging, flow), Exec{2, {}});
    const Roots fallen = make_roots(cap.chart, heavy, cap_options(TiltToward::hanging, flow), Exec{2, {}});
    REQUIRE(fallen.pores.size() == light.pores.size());
    REQUIRE(fallen.pores.size() > 100);
    CHECK(fallen.pores.positions == light.pores.positions);
    CHECK(fallen.pores.directions == light.pores.directions);
    CHECK(fallen.pores.hang_weights == light.pores.hang_weights);
    for (int i = 0; i < fallen.pores.size(); ++i) {
      CHECK(light.pores.lengths[i] == 10.0);
      CHECK(fallen.pores.lengths[i] == doctest::Approx(4.0).epsilon(1e-12));
    }
  }
}

TEST_CASE("hanging roots need the hang at every scalp vertex") {
  Cap cap;
  CHECK_THROWS_AS(make_roots(cap.chart, cap.inputs, cap_options(TiltToward::hanging, FlowModel::field)), std::invalid_argument);
  RootInputs short_falls = cap.inputs;
  short_falls.hangs.assign(cap.chart.mesh.positions.size(), 1.0);
  short_falls.falls.assign(3, 1.0);
  CHECK_THROWS_AS(make_roots(cap.chart, short_falls, cap_options(TiltToward::hanging, FlowModel::field)), std::invalid_argument);
}

TEST_CASE("the hang at a scalp point interpolates its triangle's corners") {
  Cap cap;
  std::vector<double> hangs(cap.chart.mesh.positions.size());
  for (std::size_t v = 0; v < hangs.size(); ++v) hangs[v] = 2.0 + cap.chart.mesh.positions[v].x();  // linear
  const Vec3i& t = cap.chart.mesh.triangles[17];
  const SurfacePoint sp{17, Vec3(0.2, 0.3, 0.5)};
  const Vec3 p = 0.2 * cap.chart.mesh.positions[t[0]] + 0.3 * cap.chart.mesh.positions[t[1]] + 0.5 * cap.chart.mesh.positions[t[2]];
  CHECK(hang_at(cap.chart, hangs, sp) == doctest::Approx(2.0 + p.x()).epsilon(1e-14));
}

TEST_CASE("the hang's margin: the layer ends that much sooner, and a layer holding cap + margin holds the cap") {
  // A wall whose layer ends 5 cm below every vertex of the cap's chart, probed from each vertex
  // straight down the wall's plane x = 0: each vertex's own hang is its height + 5 (y ≥ −5).
  Cap cap;
  const HangProbe wall = plane_probe(Vec3(1, 0, 0), -5.0, 0.05);
  ScalpChart flat = cap.chart;
  for (Vec3& p : flat.mesh.positions) p = Vec3(0.0, p.y(), p.z());  // every vertex on the wall
  for (Vec3& n : flat.vertex_normals) n = Vec3(1, 0, 0);
  const std::vector<double> plain = vertex_hangs(flat, wall, 30.0, 2);
  for (double margin : {0.5, 2.0}) {
    CAPTURE(margin);
    for (double top : {30.0, 3.0}) {
      const std::vector<double> kept = vertex_hangs(flat, wall, top, 2, margin);
      for (std::size_t v = 0; v < kept.size(); ++v) {
        // The layer below v: plain[v] (≈ height + 5, to the probe's bisection).
        const double expected = std::clamp(plain[v] - margin, 0.0, top);
        CHECK(kept[v] == doctest::Approx(expected).epsilon(1e-6).scale(1.0));
      }
    }
  }
  CHECK(vertex_hangs(flat, wall, 30.0, 2, 0.0) == plain);  // no margin: the hang as it was
}
