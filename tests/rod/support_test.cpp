// Rods on a support (n' = −f − c(r)): exact answers for a straight rod resting on a plane and for
// the beam on an elastic (Winkler) foundation, implicit load derivatives against finite
// differences, and hard cases that must stay finite.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "rod/rod.h"
#include "rod/rod_jet.h"
#include "rod/rod_sensitivity.h"
#include "rod/rod_shooting.h"
#include "load_derivatives.h"
#include "ramp_plane.h"

using namespace hairfit;
using hairfit::test::RampPlane;

namespace {

// A linear, two-sided foundation c = −K·y·ŷ (Winkler).
class Foundation : public RodSupport {
 public:
  explicit Foundation(double stiffness) : k_(stiffness) {}
  void force(const double r[3], double c[3], double* jacobian) const override {
    c[0] = c[2] = 0.0;
    c[1] = -k_ * r[1];
    if (jacobian) {
      for (int i = 0; i < 9; ++i) jacobian[i] = 0.0;
      jacobian[4] = -k_;
    }
  }
  double stiffness() const override { return k_; }

 private:
  double k_;
};

// The clamp with its tangent d3 in the xy plane at `angle` above x, d2 = z.
Mat3 planar_clamp(double angle) {
  Mat3 frame;
  frame.col(0) = Vec3(-std::sin(angle), std::cos(angle), 0.0);
  frame.col(1) = Vec3(0.0, 0.0, 1.0);
  frame.col(2) = Vec3(std::cos(angle), std::sin(angle), 0.0);
  return frame;
}

std::vector<double> traced_nodes(const RodModel& model, const ShootingOptions& options, const ShootingResult& s) {
  std::vector<double> nodes(3 * (options.segments + 1));
  trace_pieces(model, options.integrator, options.segments, s, RodTrace<double>{nodes.data(), nullptr, nullptr, nullptr});
  return nodes;
}

}  // namespace

TEST_CASE("a heavy rod clamped level at its resting height lies straight on the support, carrying no moment") {
  // The support carries the weight exactly at that height: n ≡ 0, m ≡ 0, the rod straight.
  const double w = 1800.0;
  auto plane = std::make_shared<RampPlane>(0.0, 4e5, 0.05);
  const double rest = plane->resting(w);
  RodModel model;
  model.root_frame = planar_clamp(0.0);
  model.force_per_length = Vec3(0.0, -w, 0.0);
  model.support = std::make_shared<RampPlane>(-rest, 4e5, 0.05);
  ShootingOptions options;
  options.segments = 128;
  const ShootingResult s = shoot_root_moment(model, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), options);
  REQUIRE(s.converged);
  CHECK(s.root_moment.norm() < 1e-9);
  CHECK(root_force(s).norm() < 1e-8);
  const std::vector<double> nodes = traced_nodes(model, options, s);
  for (int i = 0; i <= options.segments; ++i) {
    CHECK(std::fabs(nodes[3 * i + 1]) < 1e-12);
    CHECK(nodes[3 * i] == doctest::Approx(static_cast<double>(i) / options.segments).epsilon(1e-12));
  }
}

TEST_CASE("a rod on a Winkler foundation takes the exact decaying wave") {
  // EI·y'''' + K·y = 0 with y(0) = 0, y'(0) = α and a free end far beyond the decay length 1/β:
  // y = (α/β)·e^(−βx)·sin βx, β = (K/4)^¼ (Hetényi). A small α keeps the rod linear (error ~α²).
  const double beta = 20.0, k = 4.0 * std::pow(beta, 4.0), alpha = 1e-4;
  RodModel model;
  model.root_frame = planar_clamp(alpha);
  model.support = std::make_shared<Foundation>(k);
  double errors[2];
  for (int pass = 0; pass < 2; ++pass) {
    ShootingOptions options;
    options.segments = pass == 0 ? 256 : 512;
    const ShootingResult s = shoot_root_moment(model, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), options);
    REQUIRE(s.converged);
    CHECK(s.breaks.size() > 2);  // the foundation's stiffness asks for multiple shooting
    const std::vector<double> nodes = traced_nodes(model, options, s);
    double worst = 0.0;
    for (int i = 0; i <= options.segments; ++i) {
      const double x = nodes[3 * i], y = nodes[3 * i + 1];
      worst = std::max(worst, std::fabs(y - alpha / beta * std::exp(-beta * x) * std::sin(beta * x)));
    }
    errors[pass] = worst / (alpha / beta);
    MESSAGE(options.segments, " segments: largest deflection error ", errors[pass], " of α/β");
  }
  CHECK(errors[1] <= 1e-6);
}

TEST_CASE("on a support the rod converges at the integrator's order") {
  // A heavy rod hanging onto a plane below its root, resting there for most of its length.
  RodModel model;
  model.root_frame = planar_clamp(0.3);
  model.force_per_length = Vec3(0.0, -300.0, 0.0);
  model.support = std::make_shared<RampPlane>(-0.05, 2e4, 0.1);
  const int finest = 1024;
  ShootingOptions reference_options;
  reference_options.segments = finest;
  const ShootingResult reference = shoot_root_moment(model, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), reference_options);
  REQUIRE(reference.converged);
  const Vec3 tip = Eigen::Map<const Vec3>(&traced_nodes(model, reference_options, reference)[3 * finest]);
  double errors[3];
  for (int k = 0; k < 3; ++k) {
    ShootingOptions options;
    options.segments = 64 << k;
    const ShootingResult s = shoot_root_moment(model, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), options);
    REQUIRE(s.converged);
    errors[k] = (Eigen::Map<const Vec3>(&traced_nodes(model, options, s)[3 * options.segments]) - tip).norm();
  }
  MESSAGE("tip errors ", errors[0], " ", errors[1], " ", errors[2]);
  CHECK(tip.y() < 0.0);
  for (int k = 0; k < 2; ++k) CHECK(std::log2(errors[k] / errors[k + 1]) == doctest::Approx(4.0).epsilon(0.15));
}

TEST_CASE("load derivatives of a rod on a support agree with finite differences of the boundary-value solve") {
  RodModel model;
  model.root_frame = planar_clamp(0.4) * Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix();
  model.compliance = Vec3(1.0, 0.7, 1.3);
  model.kappa_hat = {Vec3(0.5, -0.3, 0.2)};
  model.force_per_length = Vec3(0.1, -400.0, 0.2);
  model.support = std::make_shared<RampPlane>(-0.08, 3e4, 0.1);
  ShootingOptions options;
  options.segments = 64;
  const Vec3 force(3.0, -2.0, 1.0), torque(0.5, 0.2, -0.3);
  const ShootingResult at = shoot_root_moment(model, force, torque, Vec3::Zero(), options);
  REQUIRE(at.converged);
  // Some of the rod rests on the plane, so the contact force is in the derivative.
  const std::vector<double> nodes = traced_nodes(model, options, at);
  int touching = 0;
  for (int i = 0; i <= options.segments; ++i) touching += nodes[3 * i + 1] < -0.08 + 0.1;
  CHECK(touching > 5);
  const double worst = test::worst_load_derivative_error(model, options, at, force, torque);
  MESSAGE("worst relative derivative error " << worst << ", pieces " << at.breaks.size() - 1);
  CHECK(worst <= 1e-6);
}

TEST_CASE("hard cases on a support stay finite and say whether they converged") {
  struct Case {
    const char* name;
    double angle, weight, stiffness, height;
  };
  const Case cases[] = {
      {"w = 1e4 onto the plane", 0.2, 1e4, 2e5, -0.02},
      {"tangent to the support, contact from the root on", 0.0, 1800.0, 4e5, 0.0},
      {"growing into the support", -0.5, 1800.0, 4e5, 0.0},
      {"a support 1e6 times too stiff", 0.2, 1800.0, 4e11, -0.02},
  };
  for (const Case& c : cases) {
    CAPTURE(std::string(c.name));
    RodModel model;
    model.root_frame = planar_clamp(c.angle);
    model.force_per_length = Vec3(0.0, -c.weight, 0.0);
    const auto plane = std::make_shared<RampPlane>(c.height, c.stiffness, 0.05);
    model.support = plane;
    ShootingOptions options;
    const ShootingResult s = shoot_root_moment(model, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), options);
    CHECK(s.root_moment.allFinite());
    CHECK(std::isfinite(s.residual));
    const std::vector<double> nodes = traced_nodes(model, options, s);
    bool finite = true;
    for (double v : nodes) finite = finite && std::isfinite(v);
    CHECK(finite);
    MESSAGE(std::string(c.name), ": converged ", s.converged, ", residual ", s.residual, ", tip y ", nodes[3 * options.segments + 1]);
    // Where it converges, the far part of the rod rests where the support carries its weight.
    if (s.converged)
      CHECK(nodes[3 * options.segments + 1] == doctest::Approx(c.height + plane->resting(c.weight)).epsilon(1e-6));
  }
}
