#include "guides/objective.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/compress_least_squares.h"
#include "core/error.h"
#include "guides/guide_cost.h"
#include "rod/rod_jet.h"
#include "rod/rod_sensitivity.h"

namespace hairfit {

namespace {

// The optimiser's coordinates x = (f_L, μ, F_1 … F_K) with m(0) = μ + c × f_L + Σ c_k × F_k + g,
// where c is the chord r(1) − r(0), c_k = r(s_k) − r(0) the lever of point force k and
// g = ∫(r − r(0)) ds × q the gravity moment of a reference shape (equilibrium:
// m(0) = t_L + ∫ d3 × n ds). Near the reference shape μ ≈ t_L, so the root moment no longer
// has to cancel the large moments of the forces to leave a small terminal torque. The
// Gauss–Newton step is the same in any linear coordinates, but the damping is not: fewer guides
// stop at the iteration cap in these coordinates (bench/results/guide_solver.md).
struct LoadCoordinates {
  Vec3 chord = Vec3::Zero();
  Vec3 gravity_moment = Vec3::Zero();
  int point_forces = 0;
  Vec3 levers[kMaxPointForces];

  LoadCoordinates(const GuideTargets& t, const double* loads) : point_forces(t.point_forces) {
    const int n = t.rod.segments + 1;
    std::vector<double> nodes(3 * n);
    double m1[3];
    integrate_rod_with_point_forces<double>(t.model, t.rod.integrator, t.rod.segments, loads, loads + 3, loads + 6,
                                            point_forces, m1,
                                            RodTrace<double>{nodes.data(), nullptr, nullptr, nullptr});
    const auto node = [&](int i) { return Vec3(nodes[3 * i], nodes[3 * i + 1], nodes[3 * i + 2]); };
    chord = node(n - 1);
    for (int k = 0; k < point_forces; ++k) levers[k] = node(point_force_node(k + 1, point_forces, t.rod.segments));
    Vec3 mean = Vec3::Zero();  // ∫ r ds by the trapezoidal rule (r(0) = 0)
    for (int i = 0; i < n; ++i) mean += (i == 0 || i == n - 1 ? 0.5 : 1.0) / (n - 1) * node(i);
    gravity_moment = mean.cross(t.model.force_per_length);
  }

  template <typename T>
  void to_loads(const T* x, T* loads) const {
    const int count = std::min(point_forces, kPointForcesCarried<T>);
    for (int a = 0; a < 3; ++a) loads[a] = x[a];
    for (int i = 6; i < 6 + 3 * count; ++i) loads[i] = x[i];
    T m[3] = {x[3] + T(gravity_moment.x()), x[4] + T(gravity_moment.y()), x[5] + T(gravity_moment.z())};
    add_moment(chord, x, m);
    for (int k = 0; k < count; ++k) add_moment(levers[k], x + 6 + 3 * k, m);
    for (int a = 0; a < 3; ++a) loads[3 + a] = m[a];
  }
  void from_loads(const double* loads, double* x) const {
    for (int a = 0; a < 3; ++a) x[a] = loads[a];
    for (int i = 6; i < 6 + 3 * point_forces; ++i) x[i] = loads[i];
    Vec3 m = Vec3(loads[3], loads[4], loads[5]) - chord.cross(Vec3(loads[0], loads[1], loads[2])) - gravity_moment;
    for (int k = 0; k < point_forces; ++k)
      m -= levers[k].cross(Vec3(loads[6 + 3 * k], loads[7 + 3 * k], loads[8 + 3 * k]));
    for (int a = 0; a < 3; ++a) x[3 + a] = m[a];
  }

 private:
  // m += c × f.
  template <typename T>
  static void add_moment(const Vec3& c, const T* f, T* m) {
    m[0] = m[0] + T(c.y()) * f[2] - T(c.z()) * f[1];
    m[1] = m[1] + T(c.z()) * f[0] - T(c.x()) * f[2];
    m[2] = m[2] + T(c.x()) * f[1] - T(c.y()) * f[0];
  }
};

class ReparameterisedCost {
 public:
  ReparameterisedCost(const GuideTargets& t, const LoadCoordinates& coordinates)
      : cost_(t, /*merged=*/true), coordinates_(coordinates) {}
  int residual_count() const { return cost_.residual_count(); }
  double merged_constant() const { return cost_.merged_constant(); }
  template <typename T>
  bool operator()(const T* x, T* residuals) const {
    T loads[kMaxGuideLoads];
    coordinates_.to_loads(x, loads);
    return cost_(loads, residuals);
  }

 private:
  GuideCost cost_;
  LoadCoordinates coordinates_;
};

// The reparameterised guide cost as Ceres sees it in its N loads (6, or 6 + 3K with K point
// forces): N + 1 residuals in place of a few hundred.
// Where the Jacobian is asked for, the residuals and their jets are compressed
// (compress_least_squares: the same cost, gradient, Gauss–Newton matrix and column norms), so
// Levenberg–Marquardt takes the same steps to round-off; Ceres formed JᵀJ for its normal
// equations anyway. What this saves is Ceres' own work on a 374 × 6 Jacobian at every evaluation
// (validating, zeroing, scaling and multiplying it), a fifth of the guide solves' instructions
// (bench/results/guide_solver.md). Where only the cost is asked for, the
// residuals are (0, …, 0, |r|). The residuals are the merged ones (MergedTargets: 160 in place
// of 374 at paper scale); their constant joins the last residual, so Ceres sees the full cost.
template <int N>
class CompressedGuideCost : public ceres::SizedCostFunction<N + 1, N> {
 public:
  explicit CompressedGuideCost(const ReparameterisedCost& cost) : cost_(cost) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* x = parameters[0];
    const int m = cost_.residual_count();
    thread_local std::vector<double> r, j;
    r.resize(m);
    if (!jacobians || !jacobians[0]) {
      if (!cost_(x, r.data())) return false;
      double squares = cost_.merged_constant();
      for (double v : r) squares += v * v;
      std::fill(residuals, residuals + N, 0.0);
      residuals[N] = std::sqrt(squares);
      return std::isfinite(residuals[N]);
    }
    thread_local std::vector<RodJet<N>> rj;
    rj.resize(m);
    j.resize(N * static_cast<std::size_t>(m));
    RodJet<N> xj[N];
    for (int i = 0; i < N; ++i) xj[i] = RodJet<N>(x[i], i);
    if (!cost_(xj, rj.data())) return false;
    for (int i = 0; i < m; ++i) {
      r[i] = rj[i].a;
      for (int k = 0; k < N; ++k) j[N * i + k] = rj[i].v[k];
    }
    if (!compress_least_squares<N>(m, r.data(), j.data(), residuals, jacobians[0])) return false;
    residuals[N] = std::sqrt(residuals[N] * residuals[N] + cost_.merged_constant());
    return true;
  }

 private:
  const ReparameterisedCost& cost_;
};

// `use(std::integral_constant<int, N>{})` for a guide's N loads (6, or 6 + 3K with K point
// forces): every jet width the guides instantiate, chosen once here.
template <class Use>
decltype(auto) with_load_count(int loads, Use&& use) {
  switch (loads) {
    case 6: return use(std::integral_constant<int, 6>{});
    case 9: return use(std::integral_constant<int, 9>{});
    case 12: return use(std::integral_constant<int, 12>{});
    default: return use(std::integral_constant<int, kMaxGuideLoads>{});
  }
}

// The single-shooting cost of these targets' load count.
ceres::CostFunction* compressed_guide_cost(const ReparameterisedCost& functor, int loads) {
  return with_load_count(loads, [&](auto n) -> ceres::CostFunction* { return new CompressedGuideCost<n()>(functor); });
}

// The guide objective of a rod too heavy for the initial-value form: the parameters are the
// terminal loads (f_L, t_L) themselves, the paper's six, and every evaluation solves the
// boundary-value problem by multiple shooting, warm-started from the previous evaluation's pieces;
// the Jacobian follows from shooting_sensitivity. A load whose solve does not converge is reported
// to Ceres as infeasible, and Levenberg–Marquardt shortens its step.
class HeavyGuideCost : public ceres::CostFunction {
 public:
  HeavyGuideCost(const GuideTargets& t, ShootingResult start) : cost_(t), t_(t), near_(std::move(start)) {
    set_num_residuals(cost_.residual_count());
    mutable_parameter_block_sizes()->push_back(6);
    static_cast<RodDiscretisation&>(options_) = t.rod;
    options_.max_iterations = 12;
    options_.restart_from_rest = false;
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* x = parameters[0];
    const ShootingResult s = solve(x);
    if (!s.converged) return false;
    near_ = s;
    sensitivity_.clear();
    if (!jacobians || !jacobians[0]) return cost_.residuals_of_solution(s, residuals);
    const int n = t_.rod.segments + 1;
    sensitivity_ = shooting_sensitivity(t_.model, s, options_);
    if (sensitivity_.empty()) return false;
    std::vector<Jet> nodes(3 * n), frames(9 * n), curvature(3 * n), r(num_residuals());
    trace_pieces(t_.model, t_.rod.integrator, t_.rod.segments, s, sensitivity_,
                 RodTrace<Jet>{nodes.data(), frames.data(), curvature.data(), nullptr});
    if (!cost_.residuals_of_shape(nodes.data(), frames.data(), curvature.data(), r.data())) return false;
    for (int i = 0; i < num_residuals(); ++i) {
      residuals[i] = r[i].a;
      for (int j = 0; j < 6; ++j) jacobians[0][6 * i + j] = r[i].v[j];
    }
    return true;
  }

  // The solution at x, warm-started from the last one; on a support, moved to first order in the
  // load change where its sensitivity is known (the last evaluation formed a Jacobian there).
  // Rods without a support start from the last solution itself, as they always have, so their
  // guides stay bit for bit what they were.
  ShootingResult solve(const double* x) const {
    const Vec3 force(x[0], x[1], x[2]), torque(x[3], x[4], x[5]);
    if (sensitivity_.empty() || !t_.model.support) return shoot_root_moment(t_.model, force, torque, near_, options_);
    return shoot_root_moment(t_.model, force, torque, predicted_solution(near_, sensitivity_, force, torque), options_);
  }

 private:
  GuideCost cost_;
  const GuideTargets& t_;
  ShootingOptions options_;
  mutable ShootingResult near_;  // Ceres evaluates one residual block from one thread
  mutable std::vector<PieceSensitivity> sensitivity_;  // of near_, when known
};

// Σ wᵢFᵢ and the unweighted terms from the residual vector (blocks as GuideCost writes them).
GuideTerms terms_of(const GuideTargets& targets, const std::vector<double>& r) {
  GuideTerms terms;
  const std::size_t block = targets.sample_nodes.size() * 3 * targets.neighbours.size();
  auto sum_squares = [&](std::size_t from, std::size_t to) {
    double s = 0.0;
    for (std::size_t i = from; i < to; ++i) s += r[i] * r[i];
    return s;
  };
  const GuideWeights& w = targets.weights;
  const std::size_t f3_end = 2 * block + 2 * targets.sample_nodes.size();
  const std::size_t f4_end = r.size() - 3 * static_cast<std::size_t>(targets.point_forces);
  const double e1 = sum_squares(0, block), e2 = sum_squares(block, 2 * block), e3 = sum_squares(2 * block, f3_end);
  const double e4 = sum_squares(f3_end, f4_end), e5 = sum_squares(f4_end, r.size());
  terms.f1 = w.direction > 0 ? e1 / w.direction : 0.0;
  terms.f2 = w.similarity > 0 ? e2 / w.similarity : 0.0;
  terms.f3 = w.boundary > 0 ? e3 / w.boundary : 0.0;
  if (targets.density && w.density > 0) terms.f4 = e4 / w.density;
  if (targets.point_force_weight > 0) terms.f5 = e5 / targets.point_force_weight;
  terms.total = e1 + e2 + e3 + e4 + e5;
  return terms;
}

// With a density grid but w4 = 0 the residuals carry no F4: evaluate it with w4 = 1 alone.
template <typename Shape>
GuideTerms with_unweighted_f4(const GuideTargets& targets, const Shape& shape, GuideTerms terms) {
  if (targets.density && !(targets.weights.density > 0)) {
    GuideTargets unit = targets;
    unit.weights = GuideWeights{0.0, 0.0, 0.0, 1.0};
    terms.f4 = evaluate_guide_terms(unit, shape).total;
  }
  return terms;
}


}  // namespace

GuideTerms evaluate_guide_terms(const GuideTargets& targets, const ShootingResult& solution) {
  const GuideCost cost(targets);
  std::vector<double> r(cost.residual_count());
  cost.residuals_of_solution(solution, r.data());
  return with_unweighted_f4(targets, solution, terms_of(targets, r));
}

GuideTerms evaluate_guide_terms(const GuideTargets& targets, const double* eta) {
  GuideCost cost(targets);
  std::vector<double> r(cost.residual_count());
  cost(eta, r.data());
  return with_unweighted_f4(targets, eta, terms_of(targets, r));
}

namespace {

template <int N>
std::vector<double> jet_residuals_of(const GuideCost& cost, const double* eta, std::vector<double>& jacobian) {
  std::vector<double> r(cost.residual_count());
  RodJet<N> x[N];
  for (int i = 0; i < N; ++i) x[i] = RodJet<N>(eta[i], i);
  std::vector<RodJet<N>> rj(r.size());
  cost(x, rj.data());
  jacobian.assign(N * r.size(), 0.0);
  for (std::size_t i = 0; i < r.size(); ++i) {
    r[i] = rj[i].a;
    for (int j = 0; j < N; ++j) jacobian[N * i + j] = rj[i].v[j];
  }
  return r;
}

std::vector<double> residuals_of(const GuideCost& cost, int loads, const double* eta, std::vector<double>* jacobian) {
  if (jacobian)
    return with_load_count(loads, [&](auto n) { return jet_residuals_of<n()>(cost, eta, *jacobian); });
  std::vector<double> r(cost.residual_count());
  cost(eta, r.data());
  return r;
}

}  // namespace

std::vector<double> guide_residuals(const GuideTargets& targets, const double* eta, std::vector<double>* jacobian) {
  return residuals_of(GuideCost(targets), targets.load_count(), eta, jacobian);
}

MergedGuideResiduals merged_guide_residuals(const GuideTargets& targets, const double* eta) {
  const GuideCost cost(targets, /*merged=*/true);
  MergedGuideResiduals m;
  m.residuals = residuals_of(cost, targets.load_count(), eta, &m.jacobian);
  m.constant = cost.merged_constant();
  return m;
}

namespace {

// Ends a solve at a stall (StallTest): from the costs of its iterations, accepted steps or not.
class StallCallback : public ceres::IterationCallback {
 public:
  explicit StallCallback(const StallTest& test) : test_(test) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    costs_.push_back(summary.cost);
    const std::size_t n = costs_.size(), window = static_cast<std::size_t>(test_.iterations);
    if (n > window && costs_[n - 1 - window] - summary.cost < test_.tolerance * summary.cost) {
      stalled_ = true;
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    return ceres::SOLVER_CONTINUE;
  }
  bool stalled() const { return stalled_; }

 private:
  StallTest test_;
  std::vector<double> costs_;  // at the current point after each iteration
  bool stalled_ = false;
};

// `dogleg`: Powell's dogleg in place of Levenberg–Marquardt. For the solves with the density term
// (they start at the density-free optimum, and F4 is rough at the voxel scale) it takes the
// Gauss–Newton step whenever the trust region holds it, where LM's damping crept: on the
// paper-scale scene 22.0 evaluations per guide instead of 28.9 with F4 10.6 instead of 12.5, a
// lower followed mismatch and a more even density; on the full head no guide at the cap instead of
// 7 (bench/results/density_dogleg.md). Without the density term LM stays: there dogleg took 22 %
// more evaluations (spheroid) and stopped 100 guides at the cap instead of 36 (straight).
ceres::Solver::Options solver_options(int max_iterations, double tolerance, bool dogleg) {
  ceres::Solver::Options options;
  // Six parameters against a few hundred residuals: the 6×6 normal equations cost a fraction of a
  // QR of the whole Jacobian (which takes 22 % of the guide solve's instructions, callgrind), and
  // the reparameterised loads keep them well conditioned; LM's damping adds to their diagonal.
  options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  if (dogleg) options.trust_region_strategy_type = ceres::DOGLEG;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = tolerance;
  options.gradient_tolerance = 1e-10;
  options.parameter_tolerance = 1e-10;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  // Ceres' first trust-region radius (10⁴) stays: 100 and 1000 moved the shares of guide nodes
  // inside by under 0.003 on every fixture but made the spheroid's guide stage up to 32 % slower
  // (more accepted steps, each with a Jacobian).
  return options;
}

// The trust-region solve of `problem`; true when the stall test ended it.
bool solve(ceres::Problem& problem, int max_iterations, double tolerance, const StallTest& stall,
           ceres::Solver::Summary& summary, bool dogleg = false) {
  ceres::Solver::Options options = solver_options(max_iterations, tolerance, dogleg);
  StallCallback stall_callback(stall);
  if (stall.iterations > 0) options.callbacks.push_back(&stall_callback);
  ceres::Solve(options, &problem, &summary);
  return stall_callback.stalled();
}

void record(const ceres::Solver::Summary& summary, bool finite, bool stalled, GuideSolve& result) {
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.evaluations = summary.num_residual_evaluations + summary.num_jacobian_evaluations;
  result.converged = finite && (summary.termination_type == ceres::CONVERGENCE || stalled);
  result.termination = stalled ? "STALL" : ceres::TerminationTypeToString(summary.termination_type);
  result.initial_cost = summary.initial_cost;
  result.final_cost = finite ? summary.final_cost : summary.initial_cost;
}

// Newton steps a heavy guide's first solve may take from a neighbour's pieces.
constexpr int kNearNewtonSteps = 12;

// Where a solve by multiple shooting stops when its caller sets no stall test: once 30 iterations
// (accepted or not) have lowered the cost by less than 1 %. Each of its evaluations solves a
// boundary-value problem, and the long tails of those solves crawl without bringing guides back
// inside; a shorter window stops solves that still do (bench/results/long_hair.md has the
// windows measured). Single-shooting solves run on to the tolerance.
constexpr StallTest kMultipleShootingStall{30, 1e-2};

// A rod solved by multiple shooting: Levenberg–Marquardt over x = (f_L, t_L) from (start force,
// zero torque) — a pre-guide's terminal torque is zero — or, when that load cannot be solved,
// from the rod hanging under its weight alone. The first solve starts from a solved neighbour's
// pieces where there is one, else continues the loads from the unloaded rod.
GuideSolve optimise_by_multiple_shooting(const GuideTargets& targets, const double start[6], int max_iterations,
                                         double tolerance, const StallTest& stall, const ShootingResult* near) {
  GuideSolve result;
  result.scheme = RodScheme::multiple_shooting;
  ShootingOptions first;
  static_cast<RodDiscretisation&>(first) = targets.rod;
  double x[6] = {start[0], start[1], start[2], 0.0, 0.0, 0.0};
  const Vec3 start_force(x[0], x[1], x[2]);
  ShootingResult at;
  if (near && near->converged) {
    // A neighbour's equilibrium is a few Newton steps from this rod's at nearby loads; the
    // continuation from rest (hundreds of steps under the weight) only where it is not.
    ShootingOptions warm = first;
    warm.max_iterations = kNearNewtonSteps;
    warm.restart_from_rest = false;
    at = shoot_root_moment(targets.model, start_force, Vec3::Zero(), *near, warm);
  }
  if (!at.converged) at = shoot_root_moment(targets.model, start_force, Vec3::Zero(), Vec3::Zero(), first);
  if (!at.converged) {
    std::fill(x, x + 6, 0.0);
    const HangingRod hanging = hang_under_weight(targets.model, targets.rod);
    at = hanging.solution;
    result.weight_share = hanging.weight_share;
  }
  result.solution = at;
  result.evaluations = 1;
  if (result.weight_share < 1.0) {  // not even the hanging rod: keep it at the share reached, flagged
    result.termination = "NO_START";
  } else {
    auto* cost = new HeavyGuideCost(targets, at);
    ceres::Problem problem;
    problem.AddResidualBlock(cost, nullptr, x);
    ceres::Solver::Summary summary;
    const bool stalled = solve(problem, max_iterations, tolerance, stall.iterations > 0 ? stall : kMultipleShootingStall, summary);
    bool finite = true;
    for (double v : x) finite = finite && std::isfinite(v);
    // The pieces at the accepted x (the last evaluation may have been a rejected trial).
    const ShootingResult final_solution = finite ? cost->solve(x) : ShootingResult{};
    if (final_solution.converged) result.solution = final_solution;
    record(summary, finite && final_solution.converged, stalled, result);
  }
  const ShootingResult& s = result.solution;
  for (int a = 0; a < 3; ++a) {
    result.eta[a] = s.terminal_force[a];
    result.eta[3 + a] = s.root_moment[a];
  }
  return result;
}

}  // namespace

GuideSolve optimise_guide(const GuideTargets& targets, const double* start, int max_iterations, double tolerance,
                          const StallTest& stall, const ShootingResult* near) {
  if (rod_scheme(targets.model) == RodScheme::multiple_shooting) {
    if (targets.point_forces > 0)
      throw InputError("guides.point_forces", "interior point forces act on rods solved by single shooting; a rod on "
                                              "the scalp as a support or this heavy is solved by multiple shooting: "
                                              "set guides.point_forces = 0");
    return optimise_by_multiple_shooting(targets, start, max_iterations, tolerance, stall, near);
  }
  const int loads = targets.load_count();
  GuideSolve result;
  std::copy(start, start + loads, result.eta);
  const LoadCoordinates coordinates(targets, start);
  double x[kMaxGuideLoads];
  coordinates.from_loads(start, x);

  const ReparameterisedCost functor(targets, coordinates);
  ceres::Problem problem;
  problem.AddResidualBlock(compressed_guide_cost(functor, loads), nullptr, x);
  ceres::Solver::Summary summary;
  const bool stalled = solve(problem, max_iterations, tolerance, stall, summary, targets.density.has_value());

  bool finite = true;
  for (int i = 0; i < loads; ++i) finite = finite && std::isfinite(x[i]);
  if (finite) coordinates.to_loads(x, result.eta);  // LM only ever accepts steps that lower the cost
  record(summary, finite, stalled, result);
  return result;
}

FibreShape solved_shape(const GuideTargets& t, const GuideSolve& s, Vec3& terminal_torque) {
  if (s.scheme == RodScheme::single_shooting)
    return fibre_shape(t.model, t.root, t.length, t.rod, s.eta, t.point_forces, &terminal_torque);
  terminal_torque = s.solution.terminal_torque;
  if (s.weight_share < 1.0) return fibre_shape(carrying_share(t.model, s.weight_share), t.root, t.length, t.rod, s.solution);
  return fibre_shape(t.model, t.root, t.length, t.rod, s.solution);
}

GuideTerms solved_terms(const GuideTargets& t, const GuideSolve& s) {
  if (s.scheme == RodScheme::single_shooting) return evaluate_guide_terms(t, s.eta);
  if (s.weight_share < 1.0) {  // the targets as the rod carries its weight: that share of it
    GuideTargets carrying = t;
    carrying.model = carrying_share(t.model, s.weight_share);
    return evaluate_guide_terms(carrying, s.solution);
  }
  return evaluate_guide_terms(t, s.solution);
}

int start_loads_read(RodScheme scheme) { return scheme == RodScheme::single_shooting ? 6 : 3; }

}  // namespace hairfit
