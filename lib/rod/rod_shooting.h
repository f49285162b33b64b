// Shooting for the dimensionless rod (DESIGN §1): given the terminal force f_L and torque t_L,
// find the root moment m(0) with m(1; f_L, m(0)) = t_L. Damped Newton (3×3 Jacobian from jets,
// backtracking line search), and, when the full load cannot be reached from the start, load
// continuation λ: 0 → 1 on (f_L, t_L, f) with a secant predictor. At λ = 0 the exact root is
// m(0) = 0, so continuation follows the branch connected to the unloaded rod.
#pragma once
#include "rod/rod_integrate.h"

namespace hairfit {

struct ShootingOptions {
  RodIntegrator integrator = RodIntegrator::rk4;
  int segments = 64;
  double tolerance = 1e-11;  // on |m(1) − t_L|, relative to max(1, |f_L|, |t_L|, |f|)
  int max_iterations = 400;  // Newton steps in total
};

struct ShootingResult {
  Vec3 root_moment = Vec3::Zero();  // m(0), the best iterate (always finite)
  Vec3 terminal_moment = Vec3::Zero();  // m(1) at that root moment
  int iterations = 0;               // Newton steps (jet evaluations)
  double residual = 0.0;            // |m(1) − t_L|
  bool converged = false;
};

// All quantities dimensionless (rod_integrate.h). `guess` is the warm start for m(0).
ShootingResult shoot_root_moment(const RodModel& model, const Vec3& terminal_force, const Vec3& terminal_torque,
                                 const Vec3& guess, const ShootingOptions& options);

}  // namespace hairfit
