#include "rod/rod_shooting.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "rod/rod_jet.h"

namespace hairfit {

namespace {

// The shooting problem at one continuation level λ: loads scaled by λ.
struct Level {
  RodModel model;
  Vec3 terminal_force;
  Vec3 terminal_torque;
};

struct Evaluation {
  Vec3 residual;  // m(1) − t_L
  Mat3 jacobian;  // ∂m(1)/∂m(0)
};

Vec3 residual_at(const Level& level, const ShootingOptions& options, const Vec3& m0) {
  Vec3 m1;
  integrate_rod<double>(level.model, options.integrator, options.segments, level.terminal_force.data(), m0.data(),
                        m1.data(), RodTrace<double>{});
  return m1 - level.terminal_torque;
}

Evaluation evaluate_with_jacobian(const Level& level, const ShootingOptions& options, const Vec3& m0) {
  RodJet3 force[3], moment[3], m1[3];
  for (int k = 0; k < 3; ++k) {
    force[k] = RodJet3(level.terminal_force[k]);
    moment[k] = RodJet3(m0[k], k);
  }
  integrate_rod<RodJet3>(level.model, options.integrator, options.segments, force, moment, m1, RodTrace<RodJet3>{});
  Evaluation e;
  for (int k = 0; k < 3; ++k) {
    e.residual[k] = m1[k].a - level.terminal_torque[k];
    e.jacobian.row(k) = m1[k].v.transpose();
  }
  return e;
}

bool finite(const Vec3& v) { return v.allFinite(); }

// Damped Newton from `x` at one level; returns true and updates x when |residual| ≤ tol.
bool newton(const Level& level, const ShootingOptions& options, double tol, int max_steps, Vec3& x, int& iterations,
            double& residual) {
  for (int step = 0; step <= max_steps; ++step) {
    const Evaluation e = evaluate_with_jacobian(level, options, x);
    const double norm = e.residual.norm();
    if (!std::isfinite(norm)) return false;
    residual = norm;
    if (norm <= tol) return true;
    if (step == max_steps || iterations >= options.max_iterations) return false;
    ++iterations;
    Vec3 delta = Vec3::Zero();
    const Eigen::FullPivLU<Mat3> lu(e.jacobian);
    if (lu.isInvertible()) delta = -lu.solve(e.residual);
    if (!finite(delta) || !lu.isInvertible()) {  // singular Jacobian: a Levenberg–Marquardt step
      const double mu = 1e-6 * std::max(1.0, e.jacobian.squaredNorm());
      delta = -(e.jacobian.transpose() * e.jacobian + mu * Mat3::Identity()).ldlt().solve(e.jacobian.transpose() *
                                                                                          e.residual);
    }
    // Backtracking on |residual|: full Newton steps near the root, shorter ones far from it.
    double alpha = 1.0;
    bool accepted = false;
    for (int trial = 0; trial < 30 && !accepted; ++trial, alpha *= 0.5) {
      const Vec3 candidate = x + alpha * delta;
      const double n = residual_at(level, options, candidate).norm();
      if (std::isfinite(n) && n <= (1.0 - 1e-4 * alpha) * norm) {
        x = candidate;
        accepted = true;
      }
    }
    if (!accepted) return false;
  }
  return false;
}

Level level_at(const RodModel& model, const Vec3& force, const Vec3& torque, double lambda) {
  Level level{model, lambda * force, lambda * torque};
  level.model.force_per_length = lambda * model.force_per_length;
  return level;
}

}  // namespace

ShootingResult shoot_root_moment(const RodModel& model, const Vec3& terminal_force, const Vec3& terminal_torque,
                                 const Vec3& guess, const ShootingOptions& options) {
  const double scale =
      std::max({1.0, terminal_force.norm(), terminal_torque.norm(), model.force_per_length.norm()});
  const double tol = options.tolerance * scale;
  ShootingResult result;
  const Level full = level_at(model, terminal_force, terminal_torque, 1.0);

  // First the warm start at the full load: most calls (continuation in callers, moderate loads) end here.
  Vec3 x = finite(guess) ? guess : Vec3::Zero();
  double residual = 0.0;
  bool converged = newton(full, options, tol, 25, x, result.iterations, residual);

  if (!converged) {
    // Continuation from the unloaded rod, whose root moment is exactly zero.
    double lambda = 0.0, previous_lambda = -1.0, step = 0.25;
    Vec3 at = Vec3::Zero(), previous = Vec3::Zero();
    while (lambda < 1.0 && step >= 1e-6 && result.iterations < options.max_iterations) {
      const double target = std::min(1.0, lambda + step);
      Vec3 trial = at;
      if (previous_lambda >= 0.0) trial += (at - previous) * ((target - lambda) / (lambda - previous_lambda));
      double r = 0.0;
      if (newton(level_at(model, terminal_force, terminal_torque, target), options, tol, 12, trial,
                 result.iterations, r)) {
        previous = at;
        previous_lambda = lambda;
        at = trial;
        lambda = target;
        step = std::min(1.0, 2.0 * step);
      } else {
        step *= 0.5;
      }
    }
    converged = lambda >= 1.0;
    // On failure keep the better of the warm-start iterate and the last level reached.
    if (converged || (residual_at(full, options, at).norm() < residual_at(full, options, x).norm())) x = at;
  }

  result.root_moment = x;
  result.terminal_moment = residual_at(full, options, x) + full.terminal_torque;
  result.residual = (result.terminal_moment - full.terminal_torque).norm();
  result.converged = converged;
  if (!std::isfinite(result.residual)) {  // cannot happen for finite input; never hand out NaN
    result.root_moment = Vec3::Zero();
    result.terminal_moment = residual_at(full, options, result.root_moment) + full.terminal_torque;
    result.residual = (result.terminal_moment - full.terminal_torque).norm();
    result.converged = false;
  }
  return result;
}

}  // namespace hairfit
