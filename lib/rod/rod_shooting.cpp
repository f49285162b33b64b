#include "rod/rod_shooting.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

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
  loaded.support_scale = solution.support_scale;
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
    if (model.support) {
      Eigen::Map<Vec3>(state.position) = solution.positions[k];
      Eigen::Map<Vec3>(state.force) = solution.forces[k];
    }
    integrate_rod_steps<double>(loaded, integrator, segments, solution.breaks[k], solution.breaks[k + 1],
                                solution.terminal_force.data(), state, trace);
  }
  return Eigen::Map<const Vec3>(state.moment);
}

int shooting_pieces(const RodModel& model, const Vec3& terminal_force, int segments) {
  const double tension = terminal_force.norm() + model.force_per_length.norm();
  double rate = std::sqrt(tension);
  // On a support of stiffness k the equations grow like exp(β·s), β = (k/4)^¼ (the beam on an
  // elastic foundation).
  if (model.support) rate = std::max(rate, std::sqrt(std::sqrt(0.25 * model.support_scale * model.support->stiffness())));
  const int pieces = static_cast<int>(std::ceil(rate / 3.0));
  return std::clamp(pieces, 1, std::min(segments, 48));
}

namespace {

// The unknowns: the state at the start of every piece. frames[0] is the clamp and never moves;
// the other frames are updated multiplicatively, R ← R·cay(δφ), so they stay rotations. On a
// support also the positions (positions[0] = 0, the root) and forces.
struct Iterate {
  std::vector<Mat3> frames;
  std::vector<Vec3> moments;
  std::vector<Vec3> positions;
  std::vector<Vec3> forces;
};

// The problem at one continuation level λ: loads (and the support) scaled by λ.
struct Level {
  RodModel model;
  Vec3 terminal_force;
  Vec3 terminal_torque;
};

Level level_at(const RodModel& model, const Vec3& force, const Vec3& torque, double lambda) {
  Level level{model, lambda * force, lambda * torque};
  level.model.force_per_length = lambda * model.force_per_length;
  level.model.support_scale = lambda * model.support_scale;
  return level;
}

// The start state of a piece as 12 components: r (0–2), the frame correction φ (3–5), n (6–8),
// m (9–11). The unknowns of piece k ≥ 1 are all 12 on a support, else (φ, m); the root's are
// (n, m) on a support, else m. The residuals of piece k's end are the mismatches with piece k+1's
// start in the same order; the tip's are (n − f_L, m − t_L) on a support, else m − t_L.
constexpr int kR = 0, kPhi = 3, kN = 6, kM = 9;

struct Problem {
  const ShootingOptions& options;
  std::vector<int> breaks;  // K+1 step indices
  bool supported = false;
  int pieces() const { return static_cast<int>(breaks.size()) - 1; }
  int root_size() const { return supported ? 6 : 3; }
  int break_size() const { return supported ? 12 : 6; }
  int size() const { return root_size() + (pieces() - 1) * break_size(); }
  // The Jacobian's band: piece k's residual rows touch its own start and piece k+1's.
  int lower() const { return 2 * break_size() - root_size() - 1; }
  int upper() const { return root_size() + break_size() - 1; }
  int column(int k) const { return k == 0 ? 0 : root_size() + (k - 1) * break_size(); }
  int row(int k) const { return k * break_size(); }
  // The components piece k solves for, in column order.
  std::vector<int> unknowns(int k) const {
    if (k == 0) return supported ? std::vector<int>{kN, kN + 1, kN + 2, kM, kM + 1, kM + 2} : std::vector<int>{kM, kM + 1, kM + 2};
    if (supported) return {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
    return {kPhi, kPhi + 1, kPhi + 2, kM, kM + 1, kM + 2};
  }
};

// The start state of piece k (position zero without a support: the centreline is not a state).
template <typename T>
RodState<T> start_state(const Problem& p, const Iterate& x, int k) {
  RodState<T> state{};
  for (int a = 0; a < 9; ++a) state.frame[a] = T(x.frames[k].data()[a]);
  for (int a = 0; a < 3; ++a) {
    state.moment[a] = T(x.moments[k][a]);
    state.position[a] = T(p.supported ? x.positions[k][a] : 0.0);
    state.force[a] = T(p.supported ? x.forces[k][a] : 0.0);
  }
  return state;
}

// The state at the end of piece k from its start (double).
RodState<double> piece_end(const Problem& p, const Level& level, const Iterate& x, int k) {
  RodState<double> state = start_state<double>(p, x, k);
  integrate_rod_steps<double>(level.model, p.options.integrator, p.options.segments, p.breaks[k], p.breaks[k + 1],
                              level.terminal_force.data(), state, RodTrace<double>{});
  return state;
}

Iterate with_end(Iterate x, int k, const RodState<double>& end) {  // piece k+1 starts where k ends
  x.frames[k + 1] = Eigen::Map<const Mat3>(end.frame);
  x.moments[k + 1] = Eigen::Map<const Vec3>(end.moment);
  if (!x.positions.empty()) {
    x.positions[k + 1] = Eigen::Map<const Vec3>(end.position);
    x.forces[k + 1] = Eigen::Map<const Vec3>(end.force);
  }
  return x;
}

// All mismatches (see the layout above).
Eigen::VectorXd residual(const Problem& p, const Level& level, const Iterate& x) {
  Eigen::VectorXd f(p.size());
  for (int k = 0; k < p.pieces(); ++k) {
    const RodState<double> end = piece_end(p, level, x, k);
    const Mat3 frame = Eigen::Map<const Mat3>(end.frame);
    const Vec3 moment = Eigen::Map<const Vec3>(end.moment);
    const int at = p.row(k);
    if (k + 1 < p.pieces()) {
      if (p.supported) {
        f.segment<3>(at + kR) = Eigen::Map<const Vec3>(end.position) - x.positions[k + 1];
        f.segment<3>(at + kPhi) = cayley::log<double>(x.frames[k + 1].transpose() * frame);
        f.segment<3>(at + kN) = Eigen::Map<const Vec3>(end.force) - x.forces[k + 1];
        f.segment<3>(at + kM) = moment - x.moments[k + 1];
      } else {
        f.segment<3>(at) = cayley::log<double>(x.frames[k + 1].transpose() * frame);
        f.segment<3>(at + 3) = moment - x.moments[k + 1];
      }
    } else if (p.supported) {
      f.segment<3>(at) = Eigen::Map<const Vec3>(end.force) - level.terminal_force;
      f.segment<3>(at + 3) = moment - level.terminal_torque;
    } else {
      f.segment<3>(at) = moment - level.terminal_torque;
    }
  }
  return f;
}

// Residual and its Jacobian with respect to the corrections u = (root unknowns, piece 1's, …):
// piece k's end state by jets over up to 6 of its own start components at a time; the dependence
// on the next break's corrections directly (−I, and for the frame jets over its 3 coordinates
// with the end state held fixed).
void residual_and_jacobian(const Problem& p, const Level& level, const Iterate& x, Eigen::VectorXd& f,
                           Eigen::MatrixXd& jacobian) {
  using J6 = RodJet6;
  using J3 = RodJet3;
  f.resize(p.size());
  jacobian.setZero(p.size(), p.size());
  J6 force[3];
  for (int i = 0; i < 3; ++i) force[i] = J6(level.terminal_force[i]);
  for (int k = 0; k < p.pieces(); ++k) {
    const std::vector<int> own = p.unknowns(k);
    const int rows = k + 1 < p.pieces() ? p.break_size() : p.root_size();
    Mat3 end_frame_value;
    for (std::size_t pass = 0; pass < own.size(); pass += 6) {
      const int seeded = static_cast<int>(std::min<std::size_t>(6, own.size() - pass));
      J6 start[12];
      for (int c = 0; c < 12; ++c) start[c] = J6(0.0);
      for (int j = 0; j < seeded; ++j) start[own[pass + j]] = J6(0.0, j);
      Eigen::Matrix<J6, 3, 1> phi(start[kPhi], start[kPhi + 1], start[kPhi + 2]);
      RodState<J6> state;
      for (int a = 0; a < 3; ++a) {
        state.position[a] = start[kR + a] + J6(p.supported ? x.positions[k][a] : 0.0);
        state.force[a] = start[kN + a] + J6(p.supported ? x.forces[k][a] : 0.0);
        state.moment[a] = J6(x.moments[k][a]) + start[kM + a];
      }
      Eigen::Map<Eigen::Matrix<J6, 3, 3>>(state.frame) = x.frames[k].cast<J6>() * cayley::matrix<J6>(phi);
      integrate_rod_steps<J6>(level.model, p.options.integrator, p.options.segments, p.breaks[k], p.breaks[k + 1],
                              force, state, RodTrace<J6>{});
      const Eigen::Map<const Eigen::Matrix<J6, 3, 3>> end_frame(state.frame);
      if (pass == 0)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) end_frame_value(r, c) = end_frame(r, c).a;
      J6 mismatch[12];
      int count = 0;
      if (k + 1 < p.pieces()) {
        const Eigen::Matrix<J6, 3, 1> psi = cayley::log<J6>(x.frames[k + 1].transpose().cast<J6>() * end_frame);
        if (p.supported)
          for (int a = 0; a < 3; ++a) mismatch[count++] = state.position[a] - J6(x.positions[k + 1][a]);
        for (int a = 0; a < 3; ++a) mismatch[count++] = psi[a];
        if (p.supported)
          for (int a = 0; a < 3; ++a) mismatch[count++] = state.force[a] - J6(x.forces[k + 1][a]);
        for (int a = 0; a < 3; ++a) mismatch[count++] = state.moment[a] - J6(x.moments[k + 1][a]);
      } else {
        if (p.supported)
          for (int a = 0; a < 3; ++a) mismatch[count++] = state.force[a] - J6(level.terminal_force[a]);
        for (int a = 0; a < 3; ++a) mismatch[count++] = state.moment[a] - J6(level.terminal_torque[a]);
      }
      for (int i = 0; i < rows; ++i) {
        if (pass == 0) f[p.row(k) + i] = mismatch[i].a;
        for (int j = 0; j < seeded; ++j) jacobian(p.row(k) + i, p.column(k) + static_cast<int>(pass) + j) = mismatch[i].v[j];
      }
    }
    if (k + 1 < p.pieces()) {
      // ∂/∂δφ_{k+1} of log(cay(δφ)ᵀ·R_next⁻¹·R_end), and −I for the next start's other components.
      const Mat3 a = x.frames[k + 1].transpose() * end_frame_value;
      Eigen::Matrix<J3, 3, 1> next_phi;
      for (int i = 0; i < 3; ++i) next_phi[i] = J3(0.0, i);
      const Eigen::Matrix<J3, 3, 1> psi_next =
          cayley::log<J3>(cayley::matrix<J3>(next_phi).transpose() * a.cast<J3>());
      const int next = p.column(k + 1), at = p.row(k);
      const int phi = p.supported ? kPhi : 0, moment = p.supported ? kM : 3;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) jacobian(at + phi + i, next + phi + j) = psi_next[i].v[j];
        jacobian(at + moment + i, next + moment + i) = -1.0;
        if (p.supported) {
          jacobian(at + kR + i, next + kR + i) = -1.0;
          jacobian(at + kN + i, next + kN + i) = -1.0;
        }
      }
    }
  }
}

Iterate moved(const Problem& p, const Iterate& x, const Eigen::VectorXd& step) {
  Iterate y = x;
  if (p.supported) {
    y.forces[0] += step.head<3>();
    y.moments[0] += step.segment<3>(3);
  } else {
    y.moments[0] += step.head<3>();
  }
  for (int k = 1; k < p.pieces(); ++k) {
    const int at = p.column(k);
    if (p.supported) {
      y.positions[k] += step.segment<3>(at + kR);
      y.frames[k] = x.frames[k] * cayley::matrix<double>(step.segment<3>(at + kPhi));
      y.forces[k] += step.segment<3>(at + kN);
      y.moments[k] += step.segment<3>(at + kM);
    } else {
      y.frames[k] = x.frames[k] * cayley::matrix<double>(step.segment<3>(at));
      y.moments[k] += step.segment<3>(at + 3);
    }
  }
  return y;
}

// A forward sweep from the root's unknowns gives the other start states (exact when the load is
// zero). `root` holds (n(0), m(0)) on a support, else m(0); a support's n(0) defaults to f_L + f.
Iterate sweep(const Problem& p, const Level& level, const Vec3& root_moment, const Vec3* root_force = nullptr) {
  Iterate x;
  x.frames.assign(p.pieces(), level.model.root_frame);
  x.moments.assign(p.pieces(), root_moment);
  if (p.supported) {
    x.positions.assign(p.pieces(), Vec3::Zero());
    x.forces.assign(p.pieces(), root_force ? *root_force : Vec3(level.terminal_force + level.model.force_per_length));
  }
  for (int k = 0; k + 1 < p.pieces(); ++k) x = with_end(x, k, piece_end(p, level, x, k));
  return x;
}

// Damped Newton at one level from x; true (x updated) when the residual is below tol. The
// residual of each accepted iterate comes from the backtracking that accepted it (no jets): a
// Jacobian is formed only for an iterate that needs a step.
bool newton(const Problem& p, const Level& level, double tol, int max_steps, Iterate& x, int& iterations,
            double& residual_norm) {
  Eigen::VectorXd f;
  Eigen::MatrixXd jacobian;
  double norm = residual(p, level, x).norm();
  for (int step = 0; step <= max_steps; ++step) {
    if (!std::isfinite(norm)) return false;
    residual_norm = norm;
    if (norm <= tol) return true;
    if (step == max_steps || iterations >= p.options.max_iterations) return false;
    ++iterations;
    residual_and_jacobian(p, level, x, f, jacobian);
    const BandLU lu(jacobian, p.lower(), p.upper());
    const Eigen::VectorXd delta = -lu.solve(f);
    if (!delta.allFinite()) return false;
    // Backtracking on the residual: full Newton steps near the root, shorter ones far from it.
    double alpha = 1.0;
    bool accepted = false;
    for (int trial = 0; trial < 20 && !accepted; ++trial, alpha *= 0.5) {
      const Iterate candidate = moved(p, x, alpha * delta);
      const double n = residual(p, level, candidate).norm();
      if (std::isfinite(n) && n <= (1.0 - 1e-4 * alpha) * norm) {
        x = candidate;
        norm = n;
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
                      near.moments.size() == near.frames.size() && near.breaks.back() == p.options.segments &&
                      (!p.supported || (near.positions.size() == near.frames.size() && near.forces.size() == near.frames.size()));
  if (!usable) {
    const Vec3 n0 = root_force(near);
    return sweep(p, level, m0, p.supported && near.forces.size() == 1 && n0.allFinite() ? &n0 : nullptr);
  }
  const RodModel earlier = solved_model(level.model, near);
  Iterate near_x{near.frames, near.moments, near.positions, near.forces};
  const Problem near_p{p.options, near.breaks, p.supported};
  Iterate x;
  for (int k = 0; k < p.pieces(); ++k) {
    const int at = p.breaks[k];
    std::size_t j = 0;
    while (j + 2 < near.breaks.size() && near.breaks[j + 1] <= at) ++j;
    RodState<double> state = start_state<double>(near_p, near_x, static_cast<int>(j));
    integrate_rod_steps<double>(earlier, p.options.integrator, p.options.segments, near.breaks[j], at,
                                near.terminal_force.data(), state, RodTrace<double>{});
    x.frames.push_back(k == 0 ? level.model.root_frame : Mat3(Eigen::Map<const Mat3>(state.frame)));
    x.moments.push_back(Eigen::Map<const Vec3>(state.moment));
    if (p.supported) {
      x.positions.push_back(k == 0 ? Vec3::Zero() : Vec3(Eigen::Map<const Vec3>(state.position)));
      x.forces.push_back(Eigen::Map<const Vec3>(state.force));
    }
  }
  if (!x.moments[0].allFinite()) return sweep(p, level, m0);
  return x;
}

}  // namespace

Vec3 root_force(const ShootingResult& solution) {
  if (!solution.forces.empty()) return solution.forces[0];
  return solution.terminal_force + solution.force_per_length;
}

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
  const bool supported = model.support != nullptr;
  Problem p{options, {}, supported};
  for (int k = 0; k <= pieces; ++k)
    p.breaks.push_back(static_cast<int>((static_cast<long long>(k) * options.segments) / pieces));
  const double scale =
      std::max({1.0, terminal_force.norm(), terminal_torque.norm(), model.force_per_length.norm()});
  const double tol = options.tolerance * scale;
  const Level full = level_at(model, terminal_force, terminal_torque, 1.0);
  ShootingResult result;
  double residual_norm = 0.0;
  // A sweep from the root's unknowns (n(0), m(0)) on a support, m(0) otherwise.
  auto sweep_from = [&](const Problem& q, const Level& level, const Eigen::VectorXd& root) {
    if (!q.supported) return sweep(q, level, root.head<3>());
    const Vec3 n0 = root.head<3>();
    return sweep(q, level, root.tail<3>(), &n0);
  };

  // First the warm start at the full load: callers that continue a load themselves end here.
  Iterate x = warm_start(p, full, near);
  // A warm start is meant for a small load increment: a root far from it belongs to another
  // equilibrium (Newton jumped branches), so it is not taken.
  bool converged = !guess.isZero() &&
                   newton(p, full, tol, 8, x, result.iterations, residual_norm) &&
                   (x.moments[0] - guess).norm() <= 0.1 + 0.25 * guess.norm();

  if (!converged && options.restart_from_rest) {
    // Continuation λ: 0 → 1 from the unloaded rod, whose solution is exact (m ≡ 0, and n ≡ 0 on
    // a support, which λ scales too). Predictor for the root's unknowns: the tangent of the
    // solution path at λ = 0, −J0⁻¹·∂F/∂λ (J0 from one jet sweep, ∂F/∂λ by a one-sided
    // difference: F is smooth in λ and vanishes at λ = 0), then secants. Branch guard: a level
    // counts only if its m(0) lands within half the predicted increment of the predictor; under
    // large loads many equilibria (curled, looped) lie close together and Newton would otherwise
    // jump to one of them. The step doubles after an easy level, halves after a failed one.
    Eigen::VectorXd tangent = Eigen::VectorXd::Zero(p.root_size());
    {
      const Problem single{options, {0, options.segments}, supported};
      const Level rest = level_at(model, terminal_force, terminal_torque, 0.0);
      Iterate zero = sweep_from(single, rest, tangent);
      Eigen::VectorXd f0;
      Eigen::MatrixXd j0;
      residual_and_jacobian(single, rest, zero, f0, j0);
      const double epsilon = 1e-7;
      const Eigen::VectorXd rate =
          residual(single, level_at(model, terminal_force, terminal_torque, epsilon), zero) / epsilon;
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(j0);
      if (lu.isInvertible()) tangent = -lu.solve(rate);
      if (!tangent.allFinite()) tangent.setZero();
    }
    // Under a weight or on a support the path from the unloaded rod may buckle (hair growing up
    // falls over) and jump to a standing or curled equilibrium if taken in one stride: the first
    // level is then a dimensionless load of about 5, and the step grows from there.
    double lambda = 0.0, previous_lambda = -1.0, step = 1.0;
    if (supported || !model.force_per_length.isZero(0.0)) {
      double load = terminal_force.norm() + model.force_per_length.norm();
      if (supported) load = std::max(load, std::sqrt(model.support_scale * model.support->stiffness()));
      step = std::min(1.0, 5.0 / std::max(load, 1.0));
    }
    Iterate at = sweep_from(p, level_at(model, terminal_force, terminal_torque, 0.0), 0.0 * tangent), previous = at;
    // On a support, after a rejected secant the path bends more than the secant saw (contact
    // engages along it): the predictor becomes the path's tangent at the last solution,
    // −J⁻¹·∂F/∂λ, whose miss shrinks with the step squared. Rods without a support keep their
    // secants, and so their solutions bit for bit.
    Eigen::VectorXd path_tangent;
    while (lambda < 1.0 && step >= 1e-6 && result.iterations < options.max_iterations) {
      const double target = std::min(1.0, lambda + step);
      const Level level = level_at(model, terminal_force, terminal_torque, target);
      Iterate trial = at;
      if (previous_lambda < 0.0) {
        trial = sweep_from(p, level, target * tangent);
      } else if (path_tangent.size() > 0) {
        trial = moved(p, at, (target - lambda) * path_tangent);
      } else {
        const double ratio = (target - lambda) / (lambda - previous_lambda);
        for (std::size_t k = 0; k < trial.moments.size(); ++k)
          trial.moments[k] += ratio * (at.moments[k] - previous.moments[k]);
        for (std::size_t k = 0; k < trial.forces.size(); ++k) {
          trial.forces[k] += ratio * (at.forces[k] - previous.forces[k]);
          trial.positions[k] += ratio * (at.positions[k] - previous.positions[k]);
        }
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
        path_tangent.resize(0);
        if (result.iterations - before <= 3) step = std::min(1.0, 2.0 * step);
      } else {
        step *= 0.5;
        if (p.supported && previous_lambda >= 0.0 && path_tangent.size() == 0) {
          const Level here = level_at(model, terminal_force, terminal_torque, lambda);
          Eigen::VectorXd f;
          Eigen::MatrixXd jacobian;
          residual_and_jacobian(p, here, at, f, jacobian);
          const double epsilon = 1e-7;
          const Eigen::VectorXd rate =
              (residual(p, level_at(model, terminal_force, terminal_torque, lambda + epsilon), at) - f) / epsilon;
          path_tangent = -BandLU(jacobian, p.lower(), p.upper()).solve(rate);
          if (!path_tangent.allFinite()) path_tangent.resize(0);
        }
      }
    }
    converged = lambda >= 1.0;
    // On failure keep the better of the warm-start iterate and the last level reached.
    if (converged || residual(p, full, at).norm() < residual(p, full, x).norm()) x = at;
  }

  Eigen::VectorXd f = residual(p, full, x);
  result.converged = converged;
  if (!f.allFinite()) {  // never hand out NaN: fall back to the unloaded start
    const Vec3 zero = Vec3::Zero();
    x = sweep(p, full, zero, &zero);
    f = residual(p, full, x);
    if (!f.allFinite()) {  // a support so stiff that even the straight rod's sweep overflows
      x = Iterate{};
      x.frames.assign(p.pieces(), model.root_frame);
      x.moments.assign(p.pieces(), Vec3::Zero());
      if (supported) {
        x.forces.assign(p.pieces(), Vec3::Zero());
        for (int k = 0; k < p.pieces(); ++k)
          x.positions.push_back(model.root_frame.col(2) * (static_cast<double>(p.breaks[k]) / options.segments));
      }
      f = residual(p, full, x);
      for (int i = 0; i < f.size(); ++i)
        if (!std::isfinite(f[i])) f[i] = std::numeric_limits<double>::max();
    }
    result.converged = false;
  }
  result.residual = f.norm();
  if (!std::isfinite(result.residual)) result.residual = std::numeric_limits<double>::max();
  result.root_moment = x.moments[0];
  result.terminal_moment = f.tail<3>() + full.terminal_torque;
  if (!result.terminal_moment.allFinite()) result.terminal_moment = Vec3::Zero();
  result.breaks = p.breaks;
  result.terminal_force = terminal_force;
  result.terminal_torque = terminal_torque;
  result.force_per_length = model.force_per_length;
  result.support_scale = model.support_scale;
  result.frames = x.frames;
  result.moments = x.moments;
  result.positions = x.positions;
  result.forces = x.forces;
  return result;
}

std::vector<PieceSensitivity> shooting_sensitivity(const RodModel& model, const ShootingResult& solution,
                                                   const ShootingOptions& options) {
  const bool supported = model.support != nullptr;
  Problem p{options, solution.breaks, supported};
  const RodModel loaded = solved_model(model, solution);
  const Level level{loaded, solution.terminal_force, solution.terminal_torque};
  const Iterate x{solution.frames, solution.moments, solution.positions, solution.forces};
  Eigen::VectorXd f;
  Eigen::MatrixXd g_x;
  residual_and_jacobian(p, level, x, f, g_x);
  Eigen::MatrixXd g_load = Eigen::MatrixXd::Zero(p.size(), 6);
  const int tip = p.row(p.pieces() - 1);
  if (supported) {
    // On a support f_L and t_L enter only the tip's residuals, n(1) − f_L and m(1) − t_L.
    g_load.block<3, 3>(tip, 0) = -Mat3::Identity();
    g_load.block<3, 3>(tip + 3, 3) = -Mat3::Identity();
  } else {
    // The force acts on every piece through n(s) = f_L + f·(1 − s) (jets over f_L, each piece
    // from its fixed start); the torque only in the last residual, m(1) − t_L.
    using J3 = RodJet3;
    J3 force[3];
    for (int i = 0; i < 3; ++i) force[i] = J3(level.terminal_force[i], i);
    for (int k = 0; k < p.pieces(); ++k) {
      RodState<J3> state;
      Eigen::Map<Eigen::Matrix<J3, 3, 1>>(state.position).setZero();
      Eigen::Map<Eigen::Matrix<J3, 3, 3>>(state.frame) = x.frames[k].cast<J3>();
      Eigen::Map<Eigen::Matrix<J3, 3, 1>>(state.moment) = x.moments[k].cast<J3>();
      integrate_rod_steps<J3>(loaded, options.integrator, options.segments, p.breaks[k], p.breaks[k + 1], force,
                              state, RodTrace<J3>{});
      const Eigen::Map<const Eigen::Matrix<J3, 3, 3>> end_frame(state.frame);
      if (k + 1 < p.pieces()) {
        const Eigen::Matrix<J3, 3, 1> psi = cayley::log<J3>(x.frames[k + 1].transpose().cast<J3>() * end_frame);
        for (int i = 0; i < 3; ++i) {
          g_load.block<1, 3>(p.row(k) + i, 0) = psi[i].v.transpose();
          g_load.block<1, 3>(p.row(k) + 3 + i, 0) = state.moment[i].v.transpose();
        }
      } else {
        for (int i = 0; i < 3; ++i) g_load.block<1, 3>(tip + i, 0) = state.moment[i].v.transpose();
        g_load.block<3, 3>(tip, 3) = -Mat3::Identity();
      }
    }
  }
  const BandLU lu(g_x, p.lower(), p.upper());
  const Eigen::MatrixXd s = -lu.solve(g_load);
  if (!s.allFinite()) return {};
  std::vector<PieceSensitivity> blocks(p.pieces(), PieceSensitivity::Zero());
  for (int k = 0; k < p.pieces(); ++k) {
    const std::vector<int> own = p.unknowns(k);
    for (std::size_t j = 0; j < own.size(); ++j) blocks[k].row(own[j]) = s.row(p.column(k) + static_cast<int>(j));
  }
  return blocks;
}

ShootingResult predicted_solution(const ShootingResult& solution, const std::vector<PieceSensitivity>& sensitivity,
                                  const Vec3& terminal_force, const Vec3& terminal_torque) {
  ShootingResult out = solution;
  if (sensitivity.size() != solution.frames.size()) return out;
  Eigen::Matrix<double, 6, 1> change;
  change << terminal_force - solution.terminal_force, terminal_torque - solution.terminal_torque;
  for (std::size_t k = 0; k < sensitivity.size(); ++k) {
    const Eigen::Matrix<double, 12, 1> d = sensitivity[k] * change;
    if (k > 0) out.frames[k] = solution.frames[k] * cayley::matrix<double>(Vec3(d.segment<3>(kPhi)));
    out.moments[k] += d.segment<3>(kM);
    if (!out.forces.empty()) {
      if (k > 0) out.positions[k] += d.segment<3>(kR);
      out.forces[k] += d.segment<3>(kN);
    }
  }
  out.root_moment = out.moments[0];
  out.terminal_force = terminal_force;
  out.terminal_torque = terminal_torque;
  return out;
}

void trace_pieces(const RodModel& model, RodIntegrator integrator, int segments, const ShootingResult& solution,
                  const std::vector<PieceSensitivity>& sensitivity, const RodTrace<RodJet6>& trace) {
  using J6 = RodJet6;
  const RodModel loaded = solved_model(model, solution);
  J6 force[3];
  for (int i = 0; i < 3; ++i) force[i] = J6(solution.terminal_force[i], i);
  RodState<J6> state;
  Eigen::Map<Eigen::Matrix<J6, 3, 1>>(state.position).setZero();
  auto seeded = [&](double value, int row, std::size_t k) {
    J6 z(value);
    z.v = sensitivity[k].row(row).transpose();
    return z;
  };
  for (std::size_t k = 0; k + 1 < solution.breaks.size(); ++k) {
    Eigen::Matrix<J6, 3, 1> phi, moment;
    for (int i = 0; i < 3; ++i) {
      phi[i] = seeded(0.0, kPhi + i, k);
      moment[i] = seeded(solution.moments[k][i], kM + i, k);
    }
    if (model.support)
      for (int i = 0; i < 3; ++i) {
        state.position[i] = seeded(solution.positions[k][i], kR + i, k);
        state.force[i] = seeded(solution.forces[k][i], kN + i, k);
      }
    Eigen::Map<Eigen::Matrix<J6, 3, 3>>(state.frame) = solution.frames[k].cast<J6>() * cayley::matrix<J6>(phi);
    Eigen::Map<Eigen::Matrix<J6, 3, 1>>(state.moment) = moment;
    integrate_rod_steps<J6>(loaded, integrator, segments, solution.breaks[k], solution.breaks[k + 1], force, state, trace);
  }
}

namespace {

// One forward integration from the root (as integrate_rod does it) that keeps the end state.
template <class T>
RodState<T> integrate_from_root(const RodModel& model, const RodDiscretisation& rod, const T* force, const T* root_moment) {
  RodState<T> state;
  for (int a = 0; a < 3; ++a) {
    state.position[a] = T(0.0);
    state.moment[a] = root_moment[a];
  }
  for (int a = 0; a < 9; ++a) state.frame[a] = T(model.root_frame.data()[a]);
  integrate_rod_steps<T>(model, rod.integrator, rod.segments, 0, rod.segments, force, state, RodTrace<T>{});
  return state;
}

double value_of(double x) { return x; }
double value_of(const RodJet3& x) { return x.a; }

template <class T>
void keep_end(const RodState<T>& state, SingleShot& shot) {
  shot.converged = true;
  shot.end_position = Vec3(value_of(state.position[0]), value_of(state.position[1]), value_of(state.position[2]));
  shot.end_tangent = Vec3(value_of(state.frame[6]), value_of(state.frame[7]), value_of(state.frame[8]));
}

}  // namespace

SingleShot shoot_single(const RodModel& model, const RodDiscretisation& rod, const Vec3& terminal_force,
                        const Vec3& terminal_torque, const Vec3& guess, double tolerance, int max_steps) {
  SingleShot shot;
  Vec3& m0 = shot.root_moment;
  m0 = guess;
  double residual_before = 0.0, residual_last = 0.0;  // |m(1) − t_L| at the last two iterates
  for (int iteration = 0; iteration < max_steps; ++iteration) {
    ++shot.integrations;
    if (residual_before > 0.0 &&
        residual_last * residual_last * (residual_last / (residual_before * residual_before)) <= tolerance) {
      const RodState<double> state = integrate_from_root<double>(model, rod, terminal_force.data(), m0.data());
      const Vec3 residual = Vec3(state.moment[0], state.moment[1], state.moment[2]) - terminal_torque;
      if (!residual.allFinite()) return shot;
      if (residual.norm() <= tolerance) {
        keep_end(state, shot);
        return shot;
      }
    }
    RodJet3 jet_force[3], moment[3];
    for (int k = 0; k < 3; ++k) {
      jet_force[k] = RodJet3(terminal_force[k]);
      moment[k] = RodJet3(m0[k], k);
    }
    const RodState<RodJet3> state = integrate_from_root<RodJet3>(model, rod, jet_force, moment);
    Vec3 residual;
    Mat3 jacobian;
    for (int k = 0; k < 3; ++k) {
      residual[k] = state.moment[k].a - terminal_torque[k];
      jacobian.row(k) = state.moment[k].v.transpose();
    }
    if (!residual.allFinite()) return shot;
    if (residual.norm() <= tolerance) {
      keep_end(state, shot);
      return shot;
    }
    const Vec3 step = jacobian.fullPivLu().solve(-residual);
    if (!step.allFinite()) return shot;
    m0 += step;
    residual_before = residual_last;
    residual_last = residual.norm();
  }
  return shot;
}

}  // namespace hairfit
