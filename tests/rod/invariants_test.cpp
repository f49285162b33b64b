// Properties every solved rod must have, on a suite of hard cases: finite, inextensible (|r'| = 1),
// frames orthonormal to 1e-12; zero load straight to round-off; the cgs hair equals its
// dimensionless twin.
#include <doctest/doctest.h>

#include <string>

#include "rod/rod.h"
#include "rod_references.h"

using namespace hairfit;
using namespace hairfit::test;

namespace {

Mat3 general_frame() {
  return Eigen::AngleAxisd(2.1, Vec3(-0.3, 1.0, 0.4).normalized()).toRotationMatrix();
}

// Finite; frames orthonormal and right-handed to 1e-12; each chord at most the step (a Runge–Kutta
// chord is a positive combination of unit tangents) and no shorter than an arc of the largest
// curvature met allows (chord/arc ≈ 1 − κ²h²/24; we allow twice that).
void check_invariants(const Rod& rod, const SolvedRod& solved) {
  const std::size_t n = solved.nodes.size();
  REQUIRE(n >= 2);
  const double h = rod.length / static_cast<double>(n - 1);
  double kappa_max = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    REQUIRE(solved.nodes[i].allFinite());
    REQUIRE(solved.frames[i].allFinite());
    REQUIRE(solved.curvature[i].allFinite());
    const Mat3& R = solved.frames[i];
    CHECK((R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff() <= 1e-12);
    CHECK(std::fabs(R.determinant() - 1.0) <= 1e-12);
    kappa_max = std::max(kappa_max, solved.curvature[i].head<2>().norm());
  }
  CHECK(solved.root_moment.allFinite());
  CHECK(solved.terminal_torque.allFinite());
  CHECK(std::isfinite(solved.residual));
  const double shortest = 1.0 - kappa_max * kappa_max * h * h / 12.0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double chord = (solved.nodes[i + 1] - solved.nodes[i]).norm() / h;
    CHECK(chord <= 1.0 + 1e-12);
    CHECK(chord >= shortest - 1e-12);
  }
}

}  // namespace

TEST_CASE("zero load keeps the rod straight to round-off") {
  Rod rod;
  rod.length = 7.0;
  rod.stiffness = Vec3(0.3, 2.0, 0.9);
  RodRoot root;
  root.position = Vec3(1.0, -2.0, 0.5);
  root.frame = general_frame();
  for (const RodSolver solver : {RodSolver::shooting, RodSolver::initial_value})
    for (const RodIntegrator integrator : {RodIntegrator::rk2, RodIntegrator::rk4}) {
      RodOptions options;
      options.solver = solver;
      options.integrator = integrator;
      const SolvedRod solved = solve_rod(rod, root, RodLoad{}, options);
      CHECK(solved.converged);
      CHECK(solved.iterations == 0);
      for (std::size_t i = 0; i < solved.nodes.size(); ++i) {
        const double s = rod.length * i / (solved.nodes.size() - 1);
        CHECK((solved.nodes[i] - root.position - s * root.frame.col(2)).norm() <= 1e-14 * rod.length);
        CHECK((solved.frames[i] - root.frame).cwiseAbs().maxCoeff() <= 1e-15);
        CHECK(solved.curvature[i].norm() == 0.0);
      }
      check_invariants(rod, solved);
    }
}

TEST_CASE("unloaded rod with constant natural curvature is the exact helix of its rest shape") {
  Rod rod;
  rod.length = 3.0;
  rod.stiffness = Vec3(1.0, 4.0, 0.5);
  const Vec3 kappa_hat(1.1, -0.7, 2.3);  // 1/cm; |κ̂|·L ≈ 8 rad
  rod.natural_curvature = {kappa_hat};
  RodRoot root;
  root.frame = general_frame();
  RodOptions options;
  options.segments = 128;
  const SolvedRod solved = solve_rod(rod, root, RodLoad{}, options);
  // R(s) = R0·exp(s[κ̂]×): the helix of exact_helix with axis R0κ̂ and unit stiffness.
  const HelixState exact = exact_helix(root.frame * kappa_hat, 1.0, 1.0, root.frame, rod.length);
  CHECK((solved.tip() - exact.position).norm() <= 1e-7 * rod.length);
  CHECK((solved.tip_frame() - exact.frame).cwiseAbs().maxCoeff() <= 1e-7);
  for (const Vec3& k : solved.curvature) CHECK((k - kappa_hat).norm() <= 1e-14);
  check_invariants(rod, solved);
}

TEST_CASE("hard cases stay finite, inextensible and orthonormal") {
  struct Case {
    std::string name;
    Vec3 stiffness;
    std::vector<Vec3> kappa_hat;  // dimensionless (per L = 1)
    Vec3 gravity;                 // dimensionless f L³/EI
    Vec3 force;                   // dimensionless f_L L²/EI
    Vec3 torque;                  // dimensionless t_L L/EI
    bool expect_converged;
  };
  const double big = 1e3;
  const std::vector<Case> cases = {
      {"tip force 1e3 across", Vec3(1, 1, 1), {}, Vec3::Zero(), Vec3(big, 0, 0), Vec3::Zero(), true},
      {"tip force 1e3 oblique, partly compressive", Vec3(1, 1, 0.7), {}, Vec3::Zero(),
       Vec3(1, 1, -1).normalized() * big, Vec3::Zero(), true},
      {"tip force 1e3 pulling backwards: the rod turns round", Vec3(1, 1, 1), {}, Vec3::Zero(), Vec3(0.1, 0, 1).normalized() * big, Vec3::Zero(), true},
      {"gravity 1e3 across", Vec3(1, 1, 1), {}, Vec3(0, -big, 0), Vec3::Zero(), Vec3::Zero(), true},
      {"gravity 50 across", Vec3(1, 1, 1), {}, Vec3(0, -50, 0), Vec3::Zero(), Vec3::Zero(), true},
      {"tip force 50 across", Vec3(1, 1, 1), {}, Vec3::Zero(), Vec3(50, 0, 0), Vec3::Zero(), true},
      {"torque 1e3 (160 turns, unresolved)", Vec3(1, 1, 1), {}, Vec3::Zero(), Vec3::Zero(), Vec3(0.3, 0.2, 1) * big, true},
      {"force and torque 1e3 together (shooting may give up; output stays finite)", Vec3(1, 1, 0.46), {}, Vec3::Zero(), Vec3(0, big, 0), Vec3(big, 0, 0), false},
      {"multi-turn helix, anisotropic", Vec3(1, 3, 0.4), {}, Vec3::Zero(), Vec3::Zero(), Vec3(5, -8, 30), true},
      {"anisotropic with varying natural curvature, gravity and force", Vec3(1, 6, 0.3),
       {Vec3(3, 0, 1), Vec3(-2, 4, 0), Vec3(0, -5, -2), Vec3(6, 1, 3)}, Vec3(0, 0, -40), Vec3(10, -5, 3),
       Vec3(-1, 2, 0.5), true},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    Rod rod;
    rod.length = 1.0;
    rod.stiffness = c.stiffness;
    rod.natural_curvature = c.kappa_hat;
    rod.force_per_length = c.gravity;
    RodLoad load;
    load.terminal_force = c.force;
    load.terminal_torque = c.torque;
    RodRoot root;
    root.frame = general_frame();
    for (const RodIntegrator integrator : {RodIntegrator::rk2, RodIntegrator::rk4}) {
      RodOptions options;
      options.integrator = integrator;
      const SolvedRod solved = solve_rod(rod, root, load, options);
      if (c.expect_converged) CHECK(solved.converged);
      check_invariants(rod, solved);
      // The initial-value form from the same root moment is the same rod.
      RodOptions forward = options;
      forward.solver = RodSolver::initial_value;
      RodLoad given = load;
      given.root_moment = solved.root_moment;
      check_invariants(rod, solve_rod(rod, root, given, forward));
    }
  }
}

TEST_CASE("real hair in cgs units has the shape of its dimensionless twin") {
  // Paper §3.1: E = 3.89e10, G = 0.89e10 dyn/cm², A = 1.5e-5 cm², 30 cm, under its own weight
  // (ρ = 1.3 g/cm³, g = 981 cm/s²) and a tip force, clamped horizontally.
  const Rod hair = [] {
    Rod r = make_circular_rod(30.0, 3.89e10, 0.89e10, 1.5e-5);
    r.force_per_length = Vec3(0.0, 0.0, -1.3 * 1.5e-5 * 981.0);
    return r;
  }();
  const double ei = hair.stiffness[0];
  CHECK(ei == doctest::Approx(3.89e10 * 1.5e-5 * 1.5e-5 / (4.0 * kPi)).epsilon(1e-15));
  CHECK(hair.stiffness[2] == doctest::Approx(0.89e10 * 2.0 * 1.5e-5 * 1.5e-5 / (4.0 * kPi)).epsilon(1e-15));
  RodRoot root;
  root.position = Vec3(2.0, 3.0, 15.0);
  root.frame = Eigen::AngleAxisd(kPi / 2, Vec3::UnitY()).toRotationMatrix();  // d3 = +x: horizontal
  RodLoad load;
  load.terminal_force = Vec3(0.0, 2e-4, 1e-4);  // dyn
  const SolvedRod cgs = solve_rod(hair, root, load);
  CHECK(cgs.converged);
  check_invariants(hair, cgs);
  CHECK(cgs.tip().z() < root.position.z() - 10.0);  // it hangs

  Rod twin;
  twin.length = 1.0;
  twin.stiffness = Vec3(1.0, 1.0, hair.stiffness[2] / ei);
  twin.force_per_length = hair.force_per_length * std::pow(hair.length, 3) / ei;
  RodLoad twin_load;
  twin_load.terminal_force = load.terminal_force * hair.length * hair.length / ei;
  RodRoot twin_root;
  twin_root.frame = root.frame;
  const SolvedRod dimensionless = solve_rod(twin, twin_root, twin_load);
  CHECK(dimensionless.converged);
  for (std::size_t i = 0; i < cgs.nodes.size(); ++i) {
    CHECK(((cgs.nodes[i] - root.position) / hair.length - dimensionless.nodes[i]).norm() <= 1e-12);
    CHECK((cgs.frames[i] - dimensionless.frames[i]).cwiseAbs().maxCoeff() <= 1e-12);
  }
  CHECK((cgs.root_moment * hair.length / ei - dimensionless.root_moment).norm() <= 1e-9 * dimensionless.root_moment.norm());
}
