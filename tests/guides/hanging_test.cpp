// A heavy rod under its weight alone (hang_under_weight, where every pre-guide under gravity and
// every heavy guide's fallback start): hair that grows nearly upright falls over and hangs, or
// lies on a support, and what is returned is an equilibrium at the weight it reports.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "guides/preguides.h"
#include "rod/rod_shooting.h"
#include "tests/rod/ramp_plane.h"

using namespace hairfit;
using hairfit::test::RampPlane;

namespace {

// The clamp with its tangent d3 in the xy plane at `degrees` from the vertical (+y) toward +x.
Mat3 clamp_from_vertical(double degrees) {
  const double a = degrees * M_PI / 180.0;
  Mat3 frame;
  frame.col(2) = Vec3(std::sin(a), std::cos(a), 0.0);
  frame.col(0) = Vec3(std::cos(a), -std::sin(a), 0.0);
  frame.col(1) = frame.col(2).cross(frame.col(0));
  return frame;
}

std::vector<Vec3> nodes_of(const RodModel& model, const RodDiscretisation& rod, const ShootingResult& s) {
  return fibre_shape(model, Vec3::Zero(), 1.0, rod, s).nodes;
}

// The mismatch of a solution as an equilibrium of `model` under no terminal load: a solve warm
// started from it that may take no Newton step beyond the first check.
double equilibrium_residual(const RodModel& model, const RodDiscretisation& rod, const ShootingResult& s) {
  ShootingOptions options;
  options.integrator = rod.integrator;
  options.segments = rod.segments;
  options.max_iterations = 1;
  options.restart_from_rest = false;
  return shoot_root_moment(model, Vec3::Zero(), Vec3::Zero(), s, options).residual;
}

}  // namespace

TEST_CASE("a heavy rod grown nearly upright falls over and hangs below its root") {
  const RodDiscretisation rod;
  for (double w : {60.0, 300.0, 1800.0}) {
    CAPTURE(w);
    RodModel model;
    model.root_frame = clamp_from_vertical(5.0);
    model.force_per_length = Vec3(0.0, -w, 0.0);
    const HangingRod h = hang_under_weight(model, rod);
    REQUIRE(h.weight_share == 1.0);
    CHECK(h.solution.converged);
    CHECK(h.solution.force_per_length == model.force_per_length);
    CHECK(equilibrium_residual(model, rod, h.solution) < 1e-8);
    const std::vector<Vec3> nodes = nodes_of(model, rod, h.solution);
    // The rod bends over within its boundary layer ~ L/√w and hangs like a chain beyond it: no
    // node rises above the root by more than that layer, and the tip hangs nearly a length below.
    double highest = 0.0;
    for (const Vec3& p : nodes) highest = std::max(highest, p.y());
    CHECK(highest < 2.0 / std::sqrt(w));
    CHECK(nodes.back().y() < -(1.0 - 4.0 / std::sqrt(w)));
    CHECK(nodes.back().x() > 0.0);  // toward the side it leant to
  }
}

TEST_CASE("a heavy rod grown nearly upright over a support falls onto it and lies there") {
  // The continuation from rest under the full weight alone takes 200–340 Newton steps on these.
  const RodDiscretisation rod;
  const double k = 4e5, layer = 0.05;
  struct Case {
    double degrees, w;
  };
  for (const Case c : {Case{2.0, 1800.0}, Case{5.0, 300.0}, Case{10.0, 1800.0}}) {
    CAPTURE(c.degrees);
    CAPTURE(c.w);
    RodModel model;
    model.root_frame = clamp_from_vertical(c.degrees);
    model.force_per_length = Vec3(0.0, -c.w, 0.0);
    model.support = std::make_shared<RampPlane>(-0.5 * layer, k, layer);
    const HangingRod h = hang_under_weight(model, rod);
    REQUIRE(h.weight_share == 1.0);
    CHECK(equilibrium_residual(model, rod, h.solution) < 1e-8);
    const std::vector<Vec3> nodes = nodes_of(model, rod, h.solution);
    // Beyond the arch from the clamp to the support (and the wave it leaves, decaying over the
    // foundation's length (4/k)^¼ ≈ 0.056) the rod rests level at the height where the support
    // carries its weight, its last quarter within 1e-3, reaching out nearly its whole length to
    // the side it leant to.
    const double resting = -0.5 * layer + RampPlane(0.0, k, layer).resting(c.w);
    double highest = 0.0;
    for (const Vec3& p : nodes) highest = std::max(highest, p.y());
    CHECK(highest < 0.15);
    for (std::size_t i = 3 * nodes.size() / 4; i < nodes.size(); ++i) CHECK(std::fabs(nodes[i].y() - resting) < 1e-3);
    CHECK(nodes.back().x() > 0.8);
  }
}
