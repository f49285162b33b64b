#include "rod/rod_shooting.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "rod/band_lu.h"
#include "rod/cayley.h"
#include "rod/rod_jet.h"
#include "rod/rod_sensitivity.h"

namespace hairfit {

namespace {

// The model under the weight a solution was solved for (continuations scale the weight).
RodModel solved_model(const RodModel& model, const ShootingResult& solution) {
  RodModel loaded = model;
  loaded.force_per_length = solution.force_per_length;
  return loaded;
}

}  // namespace

Vec3 trace_pieces(const RodModel& model, RodIntegrator integrator, int segments, const ShootingResult& solution,
                  const RodTrace<double>& trace) {
  const RodModel loaded = solved_model(model, solution);
  RodState<double> state{};
  for (std::size_t k = 0; k + 1 < solution.breaks.size(); ++k) {
    Eigen::Map<Mat3>(state.frame) = solution.frames[k];
    Eigen::Map<Vec3>(state.moment) = solution.moments[k];
    integrate_rod_steps<double>(loaded, integrator, segments, solution.breaks[k], solution.breaks[k + 1],
                                solution.terminal_force.data(), state, trace);
  }
  return Eigen::Map<const Vec3>(state.moment);
}

int shooting_pieces(const RodModel& model, const Vec3& terminal_force, int segments) {
  const double tension = terminal_force.norm() + model.force_per_length.norm();
  const int pieces = static_cast<int>(std::ceil(std::sqrt(tension) / 3.0));
  return std::clamp(pieces, 1, std::min(segments, 48));
}

namespace {

// The unknowns: the state at the start of every piece. frames[0] is the clamp and never moves;
// the other frames are updated multiplicatively, R ← R·cay(δφ), so they stay rotations.
struct Iterate {
  std::vector<Mat3> frames;
  std::vector<Vec3> moments;
};

// The problem at one continuation level λ: loads scaled by λ.
struct Level {
  RodModel model;
  Vec3 terminal_force;
  Vec3 terminal_torque;
};

Level level_at(const RodModel& model, const Vec3& force, const Vec3& torque, double lambda) {
  Level level{model, lambda * force, lambda * torque};
  level.model.force_per_length = lambda * model.force_per_length;
  return level;
}

struct Problem {
  const ShootingOptions& options;
  std::vector<int> breaks;  // K+1 step indices
  int pieces() const { return static_cast<int>(breaks.size()) - 1; }
  int size() const { return 6 * pieces() - 3; }
  // Row 6k + i (i < 6) of the Jacobian touches columns 6k − 3 … 6k + 8: piece k's start and the next.
  static constexpr int kBand = 8;
};

// Frame and moment at the end of piece k from the start state (double).
void piece_end(const Problem& p, const Level& level, const Iterate& x, int k, Mat3& frame, Vec3& moment) {
  RodState<double> state{};
  Eigen::Map<Mat3>(state.frame) = x.frames[k];
  Eigen::Map<Vec3>(state.moment) = x.moments[k];
  integrate_rod_steps<double>(level.model, p.options.integrator, p.options.segments, p.breaks[k], p.breaks[k + 1],
                              level.terminal_force.data(), state, RodTrace<double>{});
  frame = Eigen::Map<const Mat3>(state.frame);
  moment = Eigen::Map<const Vec3>(state.moment);
}

// All mismatches: per interior break, the frame (Cayley coordinates of R_next⁻¹·R_end) and the
// moment; then m(1) − t_L.
Eigen::VectorXd residual(const Problem& p, const Level& level, const Iterate& x) {
  Eigen::VectorXd f(p.size());
  for (int k = 0; k < p.pieces(); ++k) {
    Mat3 frame;
    Vec3 moment;
    piece_end(p, level, x, k, frame, moment);
    if (k + 1 < p.pieces()) {
      f.segment<3>(6 * k) = cayley::log<double>(x.frames[k + 1].transpose() * frame);
      f.segment<3>(6 * k + 3) = moment - x.moments[k + 1];
    } else {
      f.segment<3>(6 * k) = moment - level.terminal_torque;
    }
  }
  return f;
}

// Residual and its Jacobian with respect to the corrections u = (δm0, δφ1, δm1, …): piece k's end
// state by jets over its own 6 (3 for the root piece) start parameters; the dependence on the next
// break's frame correction δφ by jets over 3, with the end state held fixed.
void residual_and_jacobian(const Problem& p, const Level& level, const Iterate& x, Eigen::VectorXd& f,
                           Eigen::MatrixXd& jacobian) {
  using J6 = RodJet6;
  using J3 = RodJet3;
  f.resize(p.size());
  jacobian.setZero(p.size(), p.size());
  J6 force[3];
  for (int i = 0; i < 3; ++i) force[i] = J6(level.terminal_force[i]);
  for (int k = 0; k < p.pieces(); ++k) {
    // Unknown columns of this piece: the root piece has δm0 at 0..2; piece k ≥ 1 has δφ_k at
    // 6k−3 … 6k−1 and δm_k at 6k … 6k+2.
    const int column = k == 0 ? 0 : 6 * k - 3;
    Eigen::Matrix<J6, 3, 1> phi, dm;
    for (int i = 0; i < 3; ++i) {
      phi[i] = k == 0 ? J6(0.0) : J6(0.0, i);
      dm[i] = k == 0 ? J6(0.0, i) : J6(0.0, 3 + i);
    }
    RodState<J6> state;
    Eigen::Map<Eigen::Matrix<J6, 3, 1>>(state.position).setZero();
    Eigen::Map<Eigen::Matrix<J6, 3, 3>>(state.frame) = x.frames[k].cast<J6>() * cayley::matrix<J6>(phi);
    Eigen::Map<Eigen::Matrix<J6, 3, 1>>(state.moment) = x.moments[k].cast<J6>() + dm;
    integrate_rod_steps<J6>(level.model, p.options.integrator, p.options.segments, p.breaks[k], p.breaks[k + 1],
                            force, state, RodTrace<J6>{});
    const Eigen::Map<const Eigen::Matrix<J6, 3, 3>> end_frame(state.frame);
    const Eigen::Map<const Eigen::Matrix<J6, 3, 1>> end_moment(state.moment);
    const int own = k == 0 ? 3 : 6;
    auto put = [&](int row, const J6& value) {
      f[row] = value.a;
      for (int j = 0; j < own; ++j) jacobian(row, column + j) = value.v[j];
    };
    if (k + 1 < p.pieces()) {
      const Eigen::Matrix<J6, 3, 1> psi = cayley::log<J6>(x.frames[k + 1].transpose().cast<J6>() * end_frame);
      for (int i = 0; i < 3; ++i) put(6 * k + i, psi[i]);
      for (int i = 0; i < 3; ++i) put(6 * k + 3 + i, end_moment[i] - J6(x.moments[k + 1][i]));
      // ∂/∂δφ_{k+1} of log(cay(δφ)ᵀ·R_next⁻¹·R_end) and ∂/∂δm_{k+1} of −m_next.
      Mat3 a;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) a(r, c) = end_frame(r, c).a;
      a = x.frames[k + 1].transpose() * a;
      Eigen::Matrix<J3, 3, 1> next_phi;
      for (int i = 0; i < 3; ++i) next_phi[i] = J3(0.0, i);
      const Eigen::Matrix<J3, 3, 1> psi_next =
          cayley::log<J3>(cayley::matrix<J3>(next_phi).transpose() * a.cast<J3>());
      const int next = 6 * (k + 1) - 3;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) jacobian(6 * k + i, next + j) = psi_next[i].v[j];
        jacobian(6 * k + 3 + i, next + 3 + i) = -1.0;
      }
    } else {
      for (int i = 0; i < 3; ++i) put(6 * k + i, end_moment[i] - J6(level.terminal_torque[i]));
    }
  }
}

Iterate moved(const Iterate& x, const Eigen::VectorXd& step) {
  Iterate y = x;
  y.moments[0] += step.head<3>();
  for (std::size_t k = 1; k < x.frames.size(); ++k) {
    const int at = 6 * static_cast<int>(k) - 3;
    y.frames[k] = x.frames[k] * cayley::matrix<double>(step.segment<3>(at));
    y.moments[k] += step.segment<3>(at + 3);
  }
  return y;
}

// A forward sweep from m(0) gives the other start states (exact when the load is zero).
Iterate sweep(const Problem& p, const Level& level, const Vec3& root_moment) {
  Iterate x;
  x.frames.assign(p.pieces(), level.model.root_frame);
  x.moments.assign(p.pieces(), root_moment);
  for (int k = 0; k + 1 < p.pieces(); ++k) piece_end(p, level, x, k, x.frames[k + 1], x.moments[k + 1]);
  return x;
}

// Damped Newton at one level from x; true (x updated) when the residual is below tol.
bool newton(const Problem& p, const Level& level, double tol, int max_steps, Iterate& x, int& iterations,
            double& residual_norm) {
  Eigen::VectorXd f;
  Eigen::MatrixXd jacobian;
  for (int step = 0; step <= max_steps; ++step) {
    residual_and_jacobian(p, level, x, f, jacobian);
    const double norm = f.norm();
    if (!std::isfinite(norm)) return false;
    residual_norm = norm;
    if (norm <= tol) return true;
    if (step == max_steps || iterations >= p.options.max_iterations) return false;
    ++iterations;
    const BandLU lu(jacobian, Problem::kBand, Problem::kBand);
    const Eigen::VectorXd delta = -lu.solve(f);
    if (!delta.allFinite()) return false;
    // Backtracking on the residual: full Newton steps near the root, shorter ones far from it.
    double alpha = 1.0;
    bool accepted = false;
    for (int trial = 0; trial < 20 && !accepted; ++trial, alpha *= 0.5) {
      const Iterate candidate = moved(x, alpha * delta);
      const double n = residual(p, level, candidate).norm();
      if (std::isfinite(n) && n <= (1.0 - 1e-4 * alpha) * norm) {
        x = candidate;
        accepted = true;
      }
    }
    // Round-off floor: an iterate Newton can no longer improve and that no longer moves is the
    // root to machine precision; its residual is reported as it is.
    if (!accepted) return delta.norm() <= 1e-10 * (1.0 + x.moments[0].norm());
  }
  return false;
}

// Start states on the breaks of `p` from an earlier solution: each new piece start is traced, under
// the earlier loads, from the start of the earlier piece that holds it. That reproduces the earlier
// solution at the new breaks (no trace spans more than one earlier piece, so the exponential growth
// stays bounded). Without earlier pieces: a sweep from m(0).
Iterate warm_start(const Problem& p, const Level& level, const ShootingResult& near) {
  const Vec3 m0 = near.root_moment.allFinite() ? near.root_moment : Vec3::Zero();
  const bool usable = near.breaks.size() >= 2 && near.frames.size() + 1 == near.breaks.size() &&
                      near.moments.size() == near.frames.size() && near.breaks.back() == p.options.segments;
  if (!usable) return sweep(p, level, m0);
  const RodModel earlier = solved_model(level.model, near);
  Iterate x;
  for (int k = 0; k < p.pieces(); ++k) {
    const int at = p.breaks[k];
    std::size_t j = 0;
    while (j + 2 < near.breaks.size() && near.breaks[j + 1] <= at) ++j;
    RodState<double> state{};
    Eigen::Map<Mat3>(state.frame) = near.frames[j];
    Eigen::Map<Vec3>(state.moment) = near.moments[j];
    integrate_rod_steps<double>(earlier, p.options.integrator, p.options.segments, near.breaks[j], at,
                                near.terminal_force.data(), state, RodTrace<double>{});
    x.frames.push_back(k == 0 ? level.model.root_frame : Mat3(Eigen::Map<const Mat3>(state.frame)));
    x.moments.push_back(Eigen::Map<const Vec3>(state.moment));
  }
  if (!x.moments[0].allFinite()) return sweep(p, level, m0);
  return x;
}

}  // namespace

ShootingResult shoot_root_moment(const RodModel& model, const Vec3& terminal_force, const Vec3& terminal_torque,
                                 const Vec3& guess, const ShootingOptions& options) {
  ShootingResult near;
  near.root_moment = guess;
  return shoot_root_moment(model, terminal_force, terminal_torque, near, options);
}

ShootingResult shoot_root_moment(const RodModel& model, const Vec3& terminal_force, const Vec3& terminal_torque,
                                 const ShootingResult& near, const ShootingOptions& options) {
  const Vec3 guess = near.root_moment.allFinite() ? near.root_moment : Vec3::Zero();
  const int pieces = shooting_pieces(model, terminal_force, options.segments);
  Problem p{options, {}};
  for (int k = 0; k <= pieces; ++k)
    p.breaks.push_back(static_cast<int>((static_cast<long long>(k) * options.segments) / pieces));
  const double scale =
      std::max({1.0, terminal_force.norm(), terminal_torque.norm(), model.force_per_length.norm()});
  const double tol = options.tolerance * scale;
  const Level full = level_at(model, terminal_force, terminal_torque, 1.0);
  ShootingResult result;
  double residual_norm = 0.0;

  // First the warm start at the full load: callers that continue a load themselves end here.
  Iterate x = warm_start(p, full, near);
  // A warm start is meant for a small load increment: a root far from it belongs to another
  // equilibrium (Newton jumped branches), so it is not taken.
  bool converged = !guess.isZero() &&
                   newton(p, full, tol, 8, x, result.iterations, residual_norm) &&
                   (x.moments[0] - guess).norm() <= 0.1 + 0.25 * guess.norm();

  if (!converged && options.restart_from_rest) {
    // Continuation λ: 0 → 1 from the unloaded rod, whose solution is exact (m ≡ 0). Predictor for
    // m(0): the tangent of the solution path at λ = 0, −J0⁻¹·∂F/∂λ (J0 from one jet sweep, ∂F/∂λ
    // by a one-sided difference: F is smooth in λ and vanishes at λ = 0), then secants. Branch
    // guard: a level counts only if its m(0) lands within half the predicted increment of the
    // predictor; under large loads many equilibria (curled, looped) lie close together and Newton
    // would otherwise jump to one of them. The step doubles after an easy level, halves after a
    // failed one.
    Vec3 tangent = Vec3::Zero();
    {
      const Problem single{options, {0, options.segments}};
      const Level rest = level_at(model, terminal_force, terminal_torque, 0.0);
      Iterate zero = sweep(single, rest, Vec3::Zero());
      Eigen::VectorXd f0;
      Eigen::MatrixXd j0;
      residual_and_jacobian(single, rest, zero, f0, j0);
      const double epsilon = 1e-7;
      const Eigen::VectorXd rate =
          residual(single, level_at(model, terminal_force, terminal_torque, epsilon), zero) / epsilon;
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(j0);
      if (lu.isInvertible()) tangent = -lu.solve(rate);
      if (!tangent.allFinite()) tangent = Vec3::Zero();
    }
    double lambda = 0.0, previous_lambda = -1.0, step = 1.0;
    Iterate at = sweep(p, level_at(model, terminal_force, terminal_torque, 0.0), Vec3::Zero()), previous = at;
    while (lambda < 1.0 && step >= 1e-6 && result.iterations < options.max_iterations) {
      const double target = std::min(1.0, lambda + step);
      const Level level = level_at(model, terminal_force, terminal_torque, target);
      Iterate trial = at;
      if (previous_lambda < 0.0) {
        trial = sweep(p, level, target * tangent);
      } else {
        const double ratio = (target - lambda) / (lambda - previous_lambda);
        for (std::size_t k = 0; k < trial.moments.size(); ++k)
          trial.moments[k] += ratio * (at.moments[k] - previous.moments[k]);
      }
      const Vec3 predicted = trial.moments[0];
      const double radius = 0.5 * (predicted - at.moments[0]).norm() + 1e-6 * (1.0 + predicted.norm());
      const int before = result.iterations;
      if (newton(p, level, tol, 6, trial, result.iterations, residual_norm) &&
          (trial.moments[0] - predicted).norm() <= radius) {
        previous = at;
        previous_lambda = lambda;
        at = trial;
        lambda = target;
        if (result.iterations - before <= 3) step = std::min(1.0, 2.0 * step);
      } else {
        step *= 0.5;
      }
    }
    converged = lambda >= 1.0;
    // On failure keep the better of the warm-start iterate and the last level reached.
    if (converged || residual(p, full, at).norm() < residual(p, full, x).norm()) x = at;
  }

  Eigen::VectorXd f = residual(p, full, x);
  result.converged = converged;
  if (!f.allFinite()) {  // never hand out NaN: fall back to the unloaded start
    x = sweep(p, full, Vec3::Zero());
    f = residual(p, full, x);
    result.converged = false;
  }
  result.residual = f.norm();
  result.root_moment = x.moments[0];
  result.terminal_moment = f.tail<3>() + full.terminal_torque;
  result.breaks = p.breaks;
  result.terminal_force = terminal_force;
  result.terminal_torque = terminal_torque;
  result.force_per_length = model.force_per_length;
  result.frames = x.frames;
  result.moments = x.moments;
  return result;
}

std::vector<Eigen::Matrix<double, 6, 6>> shooting_sensitivity(const RodModel& model, const ShootingResult& solution,
                                                              const ShootingOptions& options) {
  Problem p{options, solution.breaks};
  const RodModel loaded = solved_model(model, solution);
  const Level level{loaded, solution.terminal_force, solution.terminal_torque};
  const Iterate x{solution.frames, solution.moments};
  Eigen::VectorXd f;
  Eigen::MatrixXd g_x;
  residual_and_jacobian(p, level, x, f, g_x);
  // G_(f_L, t_L): the force acts on every piece (jets over f_L, each piece from its fixed start);
  // the torque only in the last residual, m(1) − t_L.
  Eigen::MatrixXd g_load = Eigen::MatrixXd::Zero(p.size(), 6);
  using J3 = RodJet3;
  J3 force[3];
  for (int i = 0; i < 3; ++i) force[i] = J3(level.terminal_force[i], i);
  for (int k = 0; k < p.pieces(); ++k) {
    RodState<J3> state;
    Eigen::Map<Eigen::Matrix<J3, 3, 1>>(state.position).setZero();
    Eigen::Map<Eigen::Matrix<J3, 3, 3>>(state.frame) = x.frames[k].cast<J3>();
    Eigen::Map<Eigen::Matrix<J3, 3, 1>>(state.moment) = x.moments[k].cast<J3>();
    integrate_rod_steps<J3>(loaded, options.integrator, options.segments, p.breaks[k], p.breaks[k + 1], force, state,
                            RodTrace<J3>{});
    const Eigen::Map<const Eigen::Matrix<J3, 3, 3>> end_frame(state.frame);
    if (k + 1 < p.pieces()) {
      const Eigen::Matrix<J3, 3, 1> psi = cayley::log<J3>(x.frames[k + 1].transpose().cast<J3>() * end_frame);
      for (int i = 0; i < 3; ++i) {
        g_load.block<1, 3>(6 * k + i, 0) = psi[i].v.transpose();
        g_load.block<1, 3>(6 * k + 3 + i, 0) = state.moment[i].v.transpose();
      }
    } else {
      for (int i = 0; i < 3; ++i) g_load.block<1, 3>(6 * k + i, 0) = state.moment[i].v.transpose();
      g_load.block<3, 3>(6 * k, 3) = -Mat3::Identity();
    }
  }
  const BandLU lu(g_x, Problem::kBand, Problem::kBand);
  const Eigen::MatrixXd s = -lu.solve(g_load);
  if (!s.allFinite()) return {};
  std::vector<Eigen::Matrix<double, 6, 6>> blocks(p.pieces(), Eigen::Matrix<double, 6, 6>::Zero());
  blocks[0].bottomRows<3>() = s.topRows<3>();
  for (int k = 1; k < p.pieces(); ++k) blocks[k] = s.block<6, 6>(6 * k - 3, 0);
  return blocks;
}

void trace_pieces(const RodModel& model, RodIntegrator integrator, int segments, const ShootingResult& solution,
                  const std::vector<Eigen::Matrix<double, 6, 6>>& sensitivity, const RodTrace<RodJet6>& trace) {
  using J6 = RodJet6;
  const RodModel loaded = solved_model(model, solution);
  J6 force[3];
  for (int i = 0; i < 3; ++i) force[i] = J6(solution.terminal_force[i], i);
  RodState<J6> state;
  Eigen::Map<Eigen::Matrix<J6, 3, 1>>(state.position).setZero();
  for (std::size_t k = 0; k + 1 < solution.breaks.size(); ++k) {
    Eigen::Matrix<J6, 3, 1> phi, moment;
    for (int i = 0; i < 3; ++i) {
      phi[i] = J6(0.0);
      phi[i].v = sensitivity[k].row(i).transpose();
      moment[i] = J6(solution.moments[k][i]);
      moment[i].v = sensitivity[k].row(3 + i).transpose();
    }
    Eigen::Map<Eigen::Matrix<J6, 3, 3>>(state.frame) = solution.frames[k].cast<J6>() * cayley::matrix<J6>(phi);
    Eigen::Map<Eigen::Matrix<J6, 3, 1>>(state.moment) = moment;
    integrate_rod_steps<J6>(loaded, integrator, segments, solution.breaks[k], solution.breaks[k + 1], force, state, trace);
  }
}

}  // namespace hairfit
