#include "guides/preguides.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/parallel.h"
#include <Eigen/LU>

#include "rod/rod_jet.h"
#include "rod/rod_shooting.h"

namespace hairfit {

namespace {

FibreShape shape_of(const Vec3& root, double length, int nodes_count, const std::vector<double>& nodes,
                    const std::vector<double>& frames, const std::vector<double>& curvature) {
  FibreShape shape;
  shape.nodes.resize(nodes_count);
  shape.tangents.resize(nodes_count);
  shape.darboux.resize(nodes_count);
  for (int i = 0; i < nodes_count; ++i) {
    const Eigen::Map<const Mat3> frame(&frames[9 * i]);
    shape.nodes[i] = root + length * Eigen::Map<const Vec3>(&nodes[3 * i]);
    shape.tangents[i] = frame.col(2);
    shape.darboux[i] = frame * Eigen::Map<const Vec3>(&curvature[3 * i]);
  }
  return shape;
}

}  // namespace

FibreShape fibre_shape(const RodModel& model, const Vec3& root, double length, const RodDiscretisation& rod,
                       const Vec3& force, const Vec3& root_moment, Vec3* terminal_moment) {
  const int n = rod.segments + 1;
  std::vector<double> nodes(3 * n), frames(9 * n), curvature(3 * n);
  Vec3 m1;
  integrate_rod<double>(model, rod.integrator, rod.segments, force.data(), root_moment.data(), m1.data(),
                        RodTrace<double>{nodes.data(), frames.data(), curvature.data(), nullptr});
  if (terminal_moment) *terminal_moment = m1;
  return shape_of(root, length, n, nodes, frames, curvature);
}

FibreShape fibre_shape(const RodModel& model, const Vec3& root, double length, const RodDiscretisation& rod,
                       const ShootingResult& solution) {
  if (solution.breaks.size() < 2) return fibre_shape(model, root, length, rod, solution.terminal_force, solution.root_moment);
  const int n = rod.segments + 1;
  std::vector<double> nodes(3 * n), frames(9 * n), curvature(3 * n);
  trace_pieces(model, rod.integrator, rod.segments, solution,
               RodTrace<double>{nodes.data(), frames.data(), curvature.data(), nullptr});
  return shape_of(root, length, n, nodes, frames, curvature);
}

namespace {

// The free end of a solved rod in rod units (the root at the origin, lengths in L): position r(1)
// and tangent d3(1), which is all a load step needs of the shape.
struct RodEnd {
  Vec3 position;
  Vec3 tangent;
};

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
RodEnd end_of(const RodState<T>& state) {
  return RodEnd{Vec3(value_of(state.position[0]), value_of(state.position[1]), value_of(state.position[2])),
                Vec3(value_of(state.frame[6]), value_of(state.frame[7]), value_of(state.frame[8]))};
}

// Natural-parameter continuation of the cantilever m(1; P·b̂, m(0)) = 0 (t_L = 0) in the load P:
// Newton on m(0) with the 3×3 Jacobian from jets, from a secant predictor. Several equilibria
// exist at the same load (curled rods); a step is accepted only when Newton lands near the
// predictor and the tip turns by less than kMaxTipTurn, else the load step is halved, so the
// path stays on the branch connected to the unloaded rod.
class Cantilever {
 public:
  Cantilever(const Vec3& bend, const RodDiscretisation& rod) : bend_(bend), rod_(rod) {}

  // Solves at load P from `at` (its m(0), and its pieces when it has them); on success `at` becomes
  // the solution. Single shooting (Newton until |m(1)| ≤ 1e-10·max(1, P)) up to kHeavyRod; beyond,
  // m(1) depends on m(0) like exp(√P) and the rod library's multiple shooting takes over, warm
  // started from the pieces of the nearby solution, which stay a good start where a sweep from
  // m(0) alone would diverge. A single-shooting solution also hands back its rod's end (the
  // integration that confirmed it traced it), bit for bit what fibre_shape would trace again.
  bool solve(const RodModel& model, double load, ShootingResult& at, int& solves, std::optional<RodEnd>& end) const {
    end.reset();
    const Vec3 force = load * bend_;
    if (model.force_per_length.norm() > kHeavyRod || load > kHeavyRod) {
      ShootingOptions options;
      options.integrator = rod_.integrator;
      options.segments = rod_.segments;
      // A solve from nothing (the rod under its weight alone) continues from the unloaded rod; a
      // failed warm start returns at once, and the caller shortens its load step.
      options.restart_from_rest = at.breaks.empty() && at.root_moment.isZero();
      options.max_iterations = options.restart_from_rest ? 40 : 10;
      const ShootingResult r = shoot_root_moment(model, force, Vec3::Zero(), at, options);
      solves += std::max(1, r.iterations);
      if (r.converged) at = r;
      return r.converged;
    }
    Vec3 m0 = at.root_moment;
    const double tolerance = 1e-10 * std::max(1.0, load);
    auto converged = [&](const RodEnd& rod_end) {
      at = ShootingResult{};  // one piece: the shape is one integration from m(0)
      at.root_moment = m0;
      at.terminal_force = force;
      at.force_per_length = model.force_per_length;
      at.converged = true;
      end = rod_end;
      return true;
    };
    double residual_before = 0.0, residual_last = 0.0;  // |m(1)| at the last two iterates
    for (int iteration = 0; iteration < 10; ++iteration) {
      ++solves;
      // Where Newton's quadratic convergence (|r'| ≈ C·|r|², C from the last two iterates)
      // predicts that this iterate meets the tolerance, an integration without jets checks it
      // first: its m(1) is bit for bit the jets' value part, so the iterates are the same, and
      // the last one needs no Jacobian (jets cost three times as much).
      if (residual_before > 0.0 &&
          residual_last * residual_last * (residual_last / (residual_before * residual_before)) <= tolerance) {
        const RodState<double> state = integrate_from_root<double>(model, rod_, force.data(), m0.data());
        const Vec3 residual(state.moment[0], state.moment[1], state.moment[2]);
        if (!residual.allFinite()) return false;
        if (residual.norm() <= tolerance) return converged(end_of(state));
      }
      RodJet3 jet_force[3], moment[3];
      for (int k = 0; k < 3; ++k) {
        jet_force[k] = RodJet3(force[k]);
        moment[k] = RodJet3(m0[k], k);
      }
      const RodState<RodJet3> state = integrate_from_root<RodJet3>(model, rod_, jet_force, moment);
      Vec3 residual;
      Mat3 jacobian;
      for (int k = 0; k < 3; ++k) {
        residual[k] = state.moment[k].a;
        jacobian.row(k) = state.moment[k].v.transpose();
      }
      if (!residual.allFinite()) return false;
      if (residual.norm() <= tolerance) return converged(end_of(state));
      const Vec3 step = jacobian.fullPivLu().solve(-residual);
      if (!step.allFinite()) return false;
      m0 += step;
      residual_before = residual_last;
      residual_last = residual.norm();
    }
    return false;
  }

 private:
  Vec3 bend_;
  RodDiscretisation rod_;
};

constexpr double kMaxTipTurn = 0.26;  // radians (15°) of tip rotation per accepted load step
constexpr int kNewtonBudget = 250;    // Newton steps per pre-guide for following its branch

// A guess for `next` from the solution `at`: its pieces, with m(0) replaced by a predictor.
ShootingResult predicted(const ShootingResult& at, const Vec3& root_moment) {
  ShootingResult guess = at;
  guess.root_moment = root_moment;
  return guess;
}

PreGuide solve_preguide(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& o) {
  PreGuide g;
  g.root = roots.positions[i];
  g.normal = roots.normals[i];
  g.direction = roots.directions[i];
  g.length = roots.lengths[i];
  g.height = roots.heights[i];
  const Vec3 bend = bending_direction(g.normal, g.direction, o.down, o.front);
  const RodModel model = make_rod_model(hair_rod(g.length, o.material), RodRoot{g.root, root_frame(g.direction, bend)});
  const Cantilever cantilever(bend, o.rod);

  g.thickness = std::max(0.0, -boundary.volume->value(g.root));
  const double share = o.depth_range[1] + (o.depth_range[0] - o.depth_range[1]) * std::clamp(g.height, 0.0, 1.0);
  g.target_depth = share * g.thickness;
  // miss > 0: the tip is not yet deep enough.

  struct State {
    double load = 0.0;
    ShootingResult solution;  // m(0), and the pieces of a heavy rod
    double miss = 0.0;
    Vec3 tip_tangent = Vec3::Zero();
    Vec3 chord = Vec3::Zero();  // r(1) − r(0) in rod units: the tip force's moment arm about the root
    std::optional<RodEnd> end;  // the solution's rod end, when its solve traced it
    const Vec3& m0() const { return solution.root_moment; }
  };
  auto settle = [&](State& st) {
    if (st.end) {  // the tip as fibre_shape places it: root + length · r(1)
      st.miss = boundary.volume->value(g.root + g.length * st.end->position) + g.target_depth;
      st.tip_tangent = st.end->tangent;
      st.chord = st.end->position;
      return;
    }
    const FibreShape shape = fibre_shape(model, g.root, g.length, o.rod, st.solution);
    st.miss = boundary.volume->value(shape.nodes.back()) + g.target_depth;
    st.tip_tangent = shape.tangents.back();
    st.chord = (shape.nodes.back() - g.root) / g.length;
  };
  // m(0) at `load` extrapolated along the branch from the solutions a, b, c (loads increasing):
  // the parabola through all three where their loads differ, else the line through the last two,
  // else, from c alone, c's m(0) plus the moment of the added tip force about the root with c's
  // shape held (m(0) = m(1) + ∫ d3 × n ds, n the tip force: the chord × the force), which is
  // m(0)'s derivative in the load up to the shape's own response. Quadratic prediction starts
  // Newton nearer its root than the line did; the first step from the unloaded rod, predicted as
  // m(0) unchanged, was rejected twice (Newton landed beyond 0.1 of it) before 1/16 was taken.
  auto extrapolated = [&bend](const State& a, const State& b, const State& c, double load) -> Vec3 {
    if (c.load > b.load && b.load > a.load) {
      const double wa = ((load - b.load) * (load - c.load)) / ((a.load - b.load) * (a.load - c.load));
      const double wb = ((load - a.load) * (load - c.load)) / ((b.load - a.load) * (b.load - c.load));
      const double wc = ((load - a.load) * (load - b.load)) / ((c.load - a.load) * (c.load - b.load));
      return wa * a.m0() + wb * b.m0() + wc * c.m0();
    }
    if (c.load > b.load) return c.m0() + (c.m0() - b.m0()) * ((load - c.load) / (c.load - b.load));
    return c.m0() + (load - c.load) * c.chord.cross(bend);
  };
  State current, previous;
  // The rod under its own weight first, by continuation in the weight from the straight rod: a
  // heavy hair (ρAgL³/EI is ~10³ for 30 cm of hair) has many equilibria, and only this path finds
  // the drooping one. Beyond kHeavyRod each level starts from the pieces of the one before.
  {
    RodModel scaled = model;
    double share = 0.0, share_step = model.force_per_length.norm() > 0.0 ? 0.05 : 1.0;
    Vec3 m_prev = Vec3::Zero(), tip_prev = g.direction;
    double share_prev = 0.0;
    while (share < 1.0 && share_step > 1e-5 && g.solves < kNewtonBudget) {
      const double next = std::min(1.0, share + share_step);
      scaled.force_per_length = next * model.force_per_length;
      const Vec3 predictor = share > share_prev ? Vec3(current.m0() + (current.m0() - m_prev) * ((next - share) / (share - share_prev)))
                                                : current.m0();
      ShootingResult trial = predicted(current.solution, predictor);
      std::optional<RodEnd> end;
      bool accepted = cantilever.solve(scaled, 0.0, trial, g.solves, end) &&
                      (trial.root_moment - predictor).norm() <= 0.1 * (1.0 + current.m0().norm());
      Vec3 tip = tip_prev;
      if (accepted) {
        tip = end ? end->tangent : fibre_shape(scaled, g.root, g.length, o.rod, trial).tangents.back();
        accepted = std::acos(std::clamp(tip.dot(tip_prev), -1.0, 1.0)) <= kMaxTipTurn;
      }
      if (!accepted) {
        share_step *= 0.5;
        continue;
      }
      m_prev = current.m0();
      share_prev = share;
      current.solution = trial;
      current.end = end;  // traced under the full weight once share reaches 1, as settle needs it
      tip_prev = tip;
      share = next;
      share_step = std::min(share_step * 1.5, 0.25);
    }
    if (share < 1.0) {  // could not follow the weight: flagged below by the miss
      current.solution = ShootingResult{};
      current.end.reset();
    }
    current.solution.force_per_length = model.force_per_length;
  }
  settle(current);
  previous = current;
  State earliest = current;  // the solution before `previous`, for the predictor
  State best = current;
  const double tolerance = 1e-3 * std::max(g.thickness, 1e-2);
  double step = 0.25;
  bool bracketed = current.miss <= 0.0;
  State above = current, below = current;  // miss > 0 and miss ≤ 0 ends of the bracket
  // The march ends at the target, at max_load, or where the branch cannot be followed further
  // (load steps below 1e-4 of the load, or the Newton budget spent): the best tip so far is kept.
  while (!bracketed && current.load < o.max_load && step > 1e-4 * (1.0 + current.load) && g.solves < kNewtonBudget) {
    State next;
    next.load = std::min(o.max_load, current.load + step);
    const Vec3 predictor = extrapolated(earliest, previous, current, next.load);
    next.solution = predicted(current.solution, predictor);
    bool accepted = cantilever.solve(model, next.load, next.solution, g.solves, next.end) &&
                    (next.m0() - predictor).norm() <= 0.1 * (1.0 + current.m0().norm());
    if (accepted) {
      settle(next);
      // On the branch of the unloaded rod the tip turns steadily toward the pull, never back.
      accepted = std::acos(std::clamp(next.tip_tangent.dot(current.tip_tangent), -1.0, 1.0)) <= kMaxTipTurn &&
                 next.tip_tangent.dot(bend) >= current.tip_tangent.dot(bend) - 1e-9;
    }
    if (!accepted) {
      step *= 0.5;
      continue;
    }
    if (std::fabs(next.miss) < std::fabs(best.miss)) best = next;
    if (next.miss <= 0.0) {
      above = current;
      below = next;
      bracketed = true;
    }
    earliest = previous;
    previous = current;
    current = next;
    step = std::min(step * 1.5, 0.3 * (1.0 + current.load));
  }
  // Regula falsi on the load inside the bracket, Illinois' variant (an end kept twice in a row has
  // its miss halved, so both ends move), each solve started from m(0) interpolated between the
  // ends, or, should that fail, from the shallower end. On the paper-scale scene this took
  // 11 Newton steps a pre-guide where bisection from the shallower end took 28.
  double above_miss = above.miss, below_miss = below.miss;  // the ends' misses as the secant weighs them
  int kept = 0;  // the end kept by the last step: +1 above, −1 below
  for (int k = 0; bracketed && k < 60 && std::fabs(best.miss) > tolerance && below.load > above.load &&
                  g.solves < 2 * kNewtonBudget;
       ++k) {
    const double t = std::clamp(above_miss / (above_miss - below_miss), 0.0, 1.0);
    State mid = above;
    mid.load = above.load + t * (below.load - above.load);
    mid.solution = predicted(above.solution, above.m0() + t * (below.m0() - above.m0()));
    if (!cantilever.solve(model, mid.load, mid.solution, g.solves, mid.end)) {
      mid.solution = above.solution;
      if (!cantilever.solve(model, mid.load, mid.solution, g.solves, mid.end)) break;
    }
    settle(mid);
    if (std::fabs(mid.miss) < std::fabs(best.miss)) best = mid;
    if (mid.miss > 0.0) {
      above = mid;
      above_miss = mid.miss;
      if (kept == -1) below_miss *= 0.5;
      kept = -1;
    } else {
      below = mid;
      below_miss = mid.miss;
      if (kept == 1) above_miss *= 0.5;
      kept = 1;
    }
  }
  g.force = best.load * bend;
  g.root_moment = best.m0();
  g.shape = fibre_shape(model, g.root, g.length, o.rod, best.solution);
  g.depth = -boundary.volume->value(g.shape.nodes.back());
  g.reached = best.miss <= tolerance;
  return g;
}

}  // namespace

PreGuides make_preguides(const RootSet& roots, const Boundary& boundary, const PreguideOptions& options) {
  PreGuides result;
  result.items.resize(roots.size());
  ProgressCounter progress(options.progress);
  parallel_for(roots.size(), options.threads, [&](int i) {
    result.items[i] = solve_preguide(roots, i, boundary, options);
    progress.item_done();
  });
  return result;
}

Digest digest(const PreGuides& preguides) {
  Digest d;
  for (const PreGuide& g : preguides.items) {
    d.add(g.force).add(g.root_moment).add(g.shape.nodes);
    d.add(static_cast<std::int64_t>(g.reached));
  }
  return d;
}

}  // namespace hairfit
