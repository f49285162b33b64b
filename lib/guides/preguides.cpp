#include "guides/preguides.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include <Eigen/LU>

#include "rod/rod_jet.h"

namespace hairfit {

FibreShape fibre_shape(const RodModel& model, const Vec3& root, double length, const RodDiscretisation& rod,
                       const Vec3& force, const Vec3& root_moment) {
  const int n = rod.segments + 1;
  std::vector<double> nodes(3 * n), frames(9 * n), curvature(3 * n);
  Vec3 m1;
  integrate_rod<double>(model, rod.integrator, rod.segments, force.data(), root_moment.data(), m1.data(),
                        RodTrace<double>{nodes.data(), frames.data(), curvature.data(), nullptr});
  FibreShape shape;
  shape.nodes.resize(n);
  shape.tangents.resize(n);
  shape.darboux.resize(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Map<const Mat3> frame(&frames[9 * i]);
    shape.nodes[i] = root + length * Eigen::Map<const Vec3>(&nodes[3 * i]);
    shape.tangents[i] = frame.col(2);
    shape.darboux[i] = frame * Eigen::Map<const Vec3>(&curvature[3 * i]);
  }
  return shape;
}

namespace {

// Natural-parameter continuation of the cantilever m(1; P·b̂, m(0)) = 0 (t_L = 0) in the load P:
// Newton on m(0) with the 3×3 Jacobian from jets, from a secant predictor. Several equilibria
// exist at the same load (curled rods); a step is accepted only when Newton lands near the
// predictor and the tip turns by less than kMaxTipTurn, else the load step is halved, so the
// path stays on the branch connected to the unloaded rod.
class Cantilever {
 public:
  Cantilever(const RodModel& model, const Vec3& bend, const RodDiscretisation& rod)
      : model_(model), bend_(bend), rod_(rod) {}

  // Newton from `m0` at load P; true when |m(1)| ≤ 1e-10·max(1, P).
  bool solve(double load, Vec3& m0, int& solves) const {
    const double tolerance = 1e-10 * std::max(1.0, load);
    for (int iteration = 0; iteration < 10; ++iteration) {
      ++solves;
      RodJet3 force[3], moment[3], m1[3];
      for (int k = 0; k < 3; ++k) {
        force[k] = RodJet3(load * bend_[k]);
        moment[k] = RodJet3(m0[k], k);
      }
      integrate_rod<RodJet3>(model_, rod_.integrator, rod_.segments, force, moment, m1, RodTrace<RodJet3>{});
      Vec3 residual;
      Mat3 jacobian;
      for (int k = 0; k < 3; ++k) {
        residual[k] = m1[k].a;
        jacobian.row(k) = m1[k].v.transpose();
      }
      if (!residual.allFinite()) return false;
      if (residual.norm() <= tolerance) return true;
      const Vec3 step = jacobian.fullPivLu().solve(-residual);
      if (!step.allFinite()) return false;
      m0 += step;
    }
    return false;
  }

 private:
  const RodModel& model_;
  Vec3 bend_;
  RodDiscretisation rod_;
};

constexpr double kMaxTipTurn = 0.26;  // radians (15°) of tip rotation per accepted load step

PreGuide solve_preguide(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& o) {
  PreGuide g;
  g.root = roots.positions[i];
  g.normal = roots.normals[i];
  g.direction = roots.directions[i];
  g.length = roots.lengths[i];
  g.height = roots.heights[i];
  const Vec3 bend = bending_direction(g.normal, g.direction, o.down, o.front);
  const RodModel model = make_rod_model(hair_rod(g.length, o.material), RodRoot{g.root, root_frame(g.direction, bend)});
  const Cantilever cantilever(model, bend, o.rod);

  g.thickness = std::max(0.0, -boundary.volume->value(g.root));
  const double share = o.depth_range[1] + (o.depth_range[0] - o.depth_range[1]) * std::clamp(g.height, 0.0, 1.0);
  g.target_depth = share * g.thickness;
  // miss > 0: the tip is not yet deep enough.

  struct State {
    double load = 0.0;
    Vec3 m0 = Vec3::Zero();
    double miss = 0.0;
    Vec3 tip_tangent = Vec3::Zero();
  };
  auto settle = [&](State& st) {
    const FibreShape shape = fibre_shape(model, g.root, g.length, o.rod, st.load * bend, st.m0);
    st.miss = boundary.volume->value(shape.nodes.back()) + g.target_depth;
    st.tip_tangent = shape.tangents.back();
  };
  State current, previous;
  // The unloaded rod (with gravity, if any) needs its own root moment first.
  if (!cantilever.solve(0.0, current.m0, g.solves)) current.m0.setZero();
  settle(current);
  previous = current;
  State best = current;
  const double tolerance = 1e-3 * std::max(g.thickness, 1e-2);
  double step = 0.25;
  bool bracketed = current.miss <= 0.0;
  State above = current, below = current;  // miss > 0 and miss ≤ 0 ends of the bracket
  // The march ends at the target, at max_load, or where the branch cannot be followed further
  // (load steps below 1e-4 of the load, or the Newton budget spent): the best tip so far is kept.
  constexpr int kNewtonBudget = 250;
  while (!bracketed && current.load < o.max_load && step > 1e-4 * (1.0 + current.load) && g.solves < kNewtonBudget) {
    State next;
    next.load = std::min(o.max_load, current.load + step);
    const Vec3 predictor = current.load > previous.load
                               ? Vec3(current.m0 + (current.m0 - previous.m0) * ((next.load - current.load) /
                                                                                  (current.load - previous.load)))
                               : current.m0;
    next.m0 = predictor;
    bool accepted = cantilever.solve(next.load, next.m0, g.solves) &&
                    (next.m0 - predictor).norm() <= 0.1 * (1.0 + current.m0.norm());
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
    previous = current;
    current = next;
    step = std::min(step * 1.5, 0.3 * (1.0 + current.load));
  }
  // Bisection on the load inside the bracket, each solve warm-started from the shallower end.
  for (int k = 0; bracketed && k < 60 && std::fabs(best.miss) > tolerance && below.load > above.load &&
                  g.solves < 2 * kNewtonBudget;
       ++k) {
    State mid = above;
    mid.load = 0.5 * (above.load + below.load);
    if (!cantilever.solve(mid.load, mid.m0, g.solves)) break;
    settle(mid);
    if (std::fabs(mid.miss) < std::fabs(best.miss)) best = mid;
    (mid.miss > 0.0 ? above : below) = mid;
  }
  g.force = best.load * bend;
  g.root_moment = best.m0;
  g.shape = fibre_shape(model, g.root, g.length, o.rod, g.force, g.root_moment);
  g.depth = -boundary.volume->value(g.shape.nodes.back());
  g.reached = best.miss <= tolerance;
  return g;
}

}  // namespace

PreGuides make_preguides(const RootSet& roots, const Boundary& boundary, const PreguideOptions& options) {
  PreGuides result;
  result.items.resize(roots.size());
  parallel_for(roots.size(), options.threads, [&](int i) { result.items[i] = solve_preguide(roots, i, boundary, options); });
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
