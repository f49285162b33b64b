// The rod against closed-form and independently computed answers (docs/design.md §1 "what must hold").
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "rod/rod.h"
#include "rod_references.h"

using namespace hairfit;
using namespace hairfit::test;

namespace {

double frame_error(const Mat3& a, const Mat3& b) { return (a - b).cwiseAbs().maxCoeff(); }

Mat3 tilted_frame() {  // a general root frame, so no test leans on the identity
  return (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) * Eigen::AngleAxisd(-0.4, Vec3::UnitX()))
      .toRotationMatrix();
}

}  // namespace

TEST_CASE("a terminal couple alone bends the rod into the exact helix") {
  struct Case {
    const char* name;
    Vec3 direction;  // in the root frame; rotated by R0 below
    double turns;    // |m|·L/EI / 2π: how often d3 goes round m
  };
  const Case cases[] = {
      {"nearly parallel", Vec3(0.02, -0.01, 1.0), 0.8},  {"nearly parallel, 3 turns", Vec3(0.03, 0.02, 1.0), 3.0},
      {"oblique", Vec3(1.0, 0.5, 1.0), 1.3},              {"oblique, 4 turns", Vec3(-0.6, 1.0, 0.8), 4.0},
      {"nearly perpendicular", Vec3(1.0, 0.3, 0.01), 0.6}, {"nearly perpendicular, 2.5 turns", Vec3(-0.2, 1.0, -0.02), 2.5},
  };
  const Mat3 root = tilted_frame();
  for (const double gj : {1.0, 0.46}) {  // isotropic section, and hair-like G·J/(E·I)
    for (const Case& c : cases) {
      CAPTURE(std::string(c.name));
      CAPTURE(gj);
      Rod rod;
      rod.length = 2.5;
      rod.stiffness = Vec3(3.0, 3.0, 3.0 * gj);
      const double ei = rod.stiffness[0];
      const Vec3 m = root * c.direction.normalized() * (2.0 * kPi * c.turns * ei / rod.length);
      RodRoot clamp;
      clamp.position = Vec3(0.3, -1.0, 2.0);
      clamp.frame = root;
      RodLoad load;
      load.terminal_torque = m;
      RodOptions options;
      // The material frame turns at the constant rate |κ| = |C⁻¹Rᵀm|: keep the same resolution,
      // 128 steps per full turn of the frame, whatever the total rotation.
      const Vec3 body = root.transpose() * m;
      const double turns = Vec3(body.x() / ei, body.y() / ei, body.z() / rod.stiffness[2]).norm() * rod.length / (2 * kPi);
      options.segments = static_cast<int>(std::ceil(128 * turns));
      const SolvedRod shot = solve_rod(rod, clamp, load, options);
      CHECK(shot.converged);
      const HelixState exact = exact_helix(m, ei, rod.stiffness[2], root, rod.length);
      CHECK((shot.tip() - clamp.position - exact.position).norm() <= 1e-6 * rod.length);
      CHECK(frame_error(shot.tip_frame(), exact.frame) <= 1e-6);
      CHECK((shot.root_moment - m).norm() <= 1e-8 * m.norm());  // m is constant along the rod
      // Every node, not only the tip, lies on the helix.
      double worst = 0.0;
      for (std::size_t i = 0; i < shot.nodes.size(); ++i) {
        const double s = rod.length * i / (shot.nodes.size() - 1);
        worst = std::max(worst, (shot.nodes[i] - clamp.position - exact_helix(m, ei, rod.stiffness[2], root, s).position).norm());
      }
      CHECK(worst <= 1e-6 * rod.length);
    }
  }
}

TEST_CASE("the elliptic references agree with each other") {
  // Two independent evaluations of the same closed form: C++17 special functions and our own
  // Gauss–Legendre quadrature. Also a limit: small loads give the linear deflection α/3.
  for (const double alpha : {0.5, 1.0, 2.0, 5.0, 10.0}) {
    const CantileverTip a = cantilever_tip(alpha, true);
    const CantileverTip b = cantilever_tip(alpha, false);
    CHECK(std::fabs(a.x - b.x) <= 1e-12);
    CHECK(std::fabs(a.z - b.z) <= 1e-12);
  }
  const CantileverTip small = cantilever_tip(1e-4, true);
  CHECK(small.x == doctest::Approx(1e-4 / 3.0).epsilon(1e-3));
  CHECK(small.angle == doctest::Approx(1e-4 / 2.0).epsilon(1e-3));
}

TEST_CASE("large-deflection cantilever matches the elliptic integrals to 1e-6 L at the defaults") {
  for (const double alpha : {0.5, 1.0, 2.0, 5.0, 10.0}) {
    CAPTURE(alpha);
    const CantileverTip exact = cantilever_tip(alpha, false);
    Rod rod;
    rod.length = 1.7;
    rod.stiffness = Vec3(0.8, 0.8, 0.5);
    RodLoad load;
    load.terminal_force = Vec3(alpha * rod.stiffness[0] / (rod.length * rod.length), 0.0, 0.0);
    const SolvedRod solved = solve_rod(rod, RodRoot{}, load);  // defaults: shooting, rk4, 64 segments
    CHECK(solved.converged);
    const Vec3 expected = rod.length * Vec3(exact.x, 0.0, exact.z);
    CHECK((solved.tip() - expected).norm() <= 1e-6 * rod.length);
    const Vec3 tangent = solved.tip_frame().col(2);
    CHECK(std::atan2(tangent.x(), tangent.z()) == doctest::Approx(exact.angle).epsilon(1e-6));
    CHECK(solved.terminal_torque.norm() <= 1e-9 * rod.stiffness[0] / rod.length);
  }
}

namespace {

// Tip error of the α = 2 cantilever (exact answer known) with N segments.
double cantilever_error(RodIntegrator integrator, int segments) {
  const CantileverTip exact = cantilever_tip(2.0, true);
  RodLoad load;
  load.terminal_force = Vec3(2.0, 0.0, 0.0);
  RodOptions options;
  options.integrator = integrator;
  options.segments = segments;
  options.tolerance = 1e-14;
  const SolvedRod solved = solve_rod(Rod{}, RodRoot{}, load, options);
  return (solved.tip() - Vec3(exact.x, 0.0, exact.z)).norm();
}

// Tip of an oblique helix with G·J ≠ E·I (initial-value form: no solver tolerance involved).
double helix_error(RodIntegrator integrator, int segments) {
  Rod rod;
  rod.stiffness = Vec3(1.0, 1.0, 0.4);
  const Vec3 m = Vec3(1.0, -0.5, 2.0).normalized() * 7.0;
  RodLoad load;
  load.root_moment = m;
  RodOptions options;
  options.solver = RodSolver::initial_value;
  options.integrator = integrator;
  options.segments = segments;
  const SolvedRod solved = solve_rod(rod, RodRoot{}, load, options);
  const HelixState exact = exact_helix(m, 1.0, 0.4, Mat3::Identity(), 1.0);
  return (solved.tip() - exact.position).norm() + frame_error(solved.tip_frame(), exact.frame);
}

// With gravity (n varies along s) and anisotropic stiffness plus natural curvature, no closed form:
// the order is log2 of the ratio of successive differences between resolutions N, 2N, 4N.
Vec3 gravity_tip(RodIntegrator integrator, int segments) {
  Rod rod;
  rod.stiffness = Vec3(1.0, 2.0, 0.7);
  rod.natural_curvature = {Vec3(0.5, -0.3, 0.2), Vec3(1.5, 0.4, -0.1), Vec3(0.2, 0.9, 0.3)};
  rod.force_per_length = Vec3(0.0, 0.0, -3.0);
  RodLoad load;
  load.terminal_force = Vec3(0.4, -0.2, 0.0);
  load.root_moment = Vec3(0.3, 1.2, -0.4);
  RodOptions options;
  options.solver = RodSolver::initial_value;
  options.integrator = integrator;
  options.segments = segments;
  RodRoot root;
  root.frame = Eigen::AngleAxisd(1.2, Vec3::UnitY()).toRotationMatrix();  // roughly horizontal
  return solve_rod(rod, root, load, options).tip();
}

}  // namespace

TEST_CASE("observed convergence order matches the nominal order of each integrator") {
  for (const RodIntegrator integrator : {RodIntegrator::rk2, RodIntegrator::rk4}) {
    const int p = rod_integrator_order(integrator);
    CAPTURE(p);
    const int n = p == 2 ? 32 : 16;
    const double cantilever = std::log2(cantilever_error(integrator, n) / cantilever_error(integrator, 2 * n));
    const double helix = std::log2(helix_error(integrator, 2 * n) / helix_error(integrator, 4 * n));
    const Vec3 a = gravity_tip(integrator, n), b = gravity_tip(integrator, 2 * n), c = gravity_tip(integrator, 4 * n);
    const double gravity = std::log2((a - b).norm() / (b - c).norm());
    std::printf("%s observed order: cantilever %.3f, helix %.3f, gravity+natural curvature %.3f\n",
                rod_integrator_name(integrator), cantilever, helix, gravity);
    CHECK(std::fabs(cantilever - p) <= 0.2);
    CHECK(std::fabs(helix - p) <= 0.2);
    CHECK(std::fabs(gravity - p) <= 0.2);
  }
}
