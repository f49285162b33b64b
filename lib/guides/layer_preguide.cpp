#include "guides/layer_preguide.h"

#include <algorithm>
#include <array>
#include <vector>
#include <cmath>

#include <Eigen/Dense>

#include "core/smoothstep.h"

namespace hairfit {

namespace {

constexpr double kOutsidePenalty = 4.0;  // weight of an excursion below kMargin or above 1 − kMargin in λ
constexpr double kMargin = 0.15;         // the share of the layer kept clear at either side
constexpr double kLoadRegularisation = 1e-3;  // prefers the smaller load where the layer leaves a choice
constexpr int kIterations = 40;
constexpr double kFollowWeight = 0.5;  // the growth field's pull against the immersion depth's

using Load = Eigen::Matrix<double, 6, 1>;

struct LayerFit {
  const RodModel* model;
  const PreguideOptions* options;
  const Boundary* boundary;
  Vec3 root, bend, binormal;
  double length;
  double target;  // λ*
  double scale;  // cm: the layer coordinate's unit outside the layer (layer_coordinate)

  // x: the load in the root frame (d1, d2, d3): terminal force x[0..2], root couple x[3..5].
  FibreShape shape(const Load& x) const {
    const Mat3& frame = model->root_frame;
    return fibre_shape(*model, root, length, options->rod, frame * x.head<3>(), frame * x.tail<3>());
  }

  // Residuals: per node after the root, the weighted miss of λ and the two excursion penalties,
  // then the regularisation of the load.
  Eigen::VectorXd residuals(const FibreShape& s, const Load& x) const {
    const int n = static_cast<int>(s.nodes.size());
    const FlowLookup* flow = options->flow.get();
    Eigen::VectorXd r((flow ? 6 : 3) * (n - 1) + 6);
    for (int k = 1; k < n; ++k) {
      const double along = static_cast<double>(k) / (n - 1);
      const double lambda = layer_coordinate(*boundary, s.nodes[k], scale);
      const double w = smoothstep(along / 0.25) / std::sqrt(static_cast<double>(n - 1));
      r[3 * (k - 1)] = w * (lambda - target);
      r[3 * (k - 1) + 1] = kOutsidePenalty * std::max(0.0, lambda - (1.0 - kMargin));
      r[3 * (k - 1) + 2] = kOutsidePenalty * std::max(0.0, kMargin - lambda) * smoothstep(along / 0.25);
    }
    if (flow)  // the tangent's part along the scalp against the growth field there
      for (int k = 1; k < n; ++k) {
        const double along = static_cast<double>(k) / (n - 1);
        Vec3 normal;
        const Vec3 field = flow->at(s.nodes[k], &normal);
        Vec3 t = s.tangents[k] - s.tangents[k].dot(normal) * normal;
        const double m = t.norm();
        const Vec3 miss = field.isZero(0.0) || !(m > 1e-12) ? Vec3::Zero() : Vec3(t / m - field);
        r.segment<3>(3 * (n - 1) + 3 * (k - 1)) = kFollowWeight * smoothstep(along / 0.25) / std::sqrt(static_cast<double>(n - 1)) * miss;
      }
    r.tail<6>() = kLoadRegularisation * x;
    return r;
  }
};

}  // namespace

double layer_coordinate(const Boundary& b, const Vec3& p, double scale) {
  const double scalp = b.scalp->value(p), volume = b.volume->value(p);
  if (volume > 0.0) return 1.0 + volume / scale;  // beyond the hull
  if (scalp < 0.0) return scalp / scale;          // in the head
  return scalp / std::max(scalp - volume, 1e-12);
}

namespace {

// The pre-guide's root, its rod and the fit of its load.
struct LayerProblem {
  PreGuide g;
  RodModel model;
  LayerFit fit;
};

LayerProblem layer_problem(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& o) {
  LayerProblem p;
  p.g = preguide_root(roots, i);
  PreGuide& g = p.g;
  const Vec3 bend = bending_direction(g.normal, g.direction, o.down, o.front);
  const Mat3 frame = root_frame(g.direction, bend);
  p.model = make_rod_model(hair_rod(g.length, o.material), RodRoot{g.root, frame});
  g.thickness = std::max(0.0, -boundary.volume->value(g.root));
  const double share = o.depth_range[1] + (o.depth_range[0] - o.depth_range[1]) * std::clamp(g.height, 0.0, 1.0);
  g.target_depth = share * g.thickness;
  const double scale = std::max(g.thickness, 0.5 * boundary.volume->voxel());
  p.fit = LayerFit{nullptr, &o, &boundary, g.root, bend, frame.col(1), g.length, 1.0 - share, scale};
  return p;
}

}  // namespace

double layer_preguide_cost(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& o, double force,
                           double couple) {
  LayerProblem p = layer_problem(roots, i, boundary, o);
  p.fit.model = &p.model;
  Load x = Load::Zero();
  x[0] = force, x[4] = couple;
  return p.fit.residuals(p.fit.shape(x), x).squaredNorm();
}

PreGuide solve_layer_preguide(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& o) {
  LayerProblem problem = layer_problem(roots, i, boundary, o);
  problem.fit.model = &problem.model;
  PreGuide& g = problem.g;
  const LayerFit& fit = problem.fit;
  const double scale = fit.scale;

  // Levenberg–Marquardt with forward-difference Jacobians on (P, μ) from the straight rod; with
  // the growth field to follow, then on all six load components from there.
  Load x = Load::Zero();
  FibreShape shape = fit.shape(x);
  Eigen::VectorXd r = fit.residuals(shape, x);
  double cost = r.squaredNorm();
  int solves = 1;
  std::vector<std::vector<int>> stages{{0, 4}};
  if (o.flow) stages.push_back({0, 1, 2, 3, 4, 5});  // to follow the field it may bend sideways too
  for (const std::vector<int>& free : stages) {
    const int m = static_cast<int>(free.size());
    double damping = 1e-3;
    for (int it = 0; it < kIterations; ++it) {
      Eigen::MatrixXd jacobian(r.size(), m);
      for (int a = 0; a < m; ++a) {
        Load step = x;
        const double h = 1e-5 * (1.0 + std::fabs(x[free[a]]));
        step[free[a]] += h;
        jacobian.col(a) = (fit.residuals(fit.shape(step), step) - r) / h;
        ++solves;
      }
      const Eigen::MatrixXd normal = jacobian.transpose() * jacobian;
      const Eigen::VectorXd gradient = jacobian.transpose() * r;
      if (gradient.norm() <= 1e-10 * (1.0 + cost)) break;
      bool improved = false;
      while (damping < 1e8) {
        Eigen::MatrixXd damped = normal;
        damped.diagonal() += damping * normal.diagonal().cwiseMax(1e-12);
        const Eigen::VectorXd delta = damped.ldlt().solve(-gradient);
        if (!delta.allFinite()) break;
        Load trial = x;
        for (int a = 0; a < m; ++a) trial[free[a]] += delta[a];
        const FibreShape trial_shape = fit.shape(trial);
        ++solves;
        const Eigen::VectorXd trial_r = fit.residuals(trial_shape, trial);
        const double trial_cost = trial_r.squaredNorm();
        if (std::isfinite(trial_cost) && trial_cost < cost) {
          const double decrease = cost - trial_cost;
          x = trial, shape = trial_shape, r = trial_r, cost = trial_cost;
          damping = std::max(damping / 3.0, 1e-9);
          improved = true;
          if (decrease <= 1e-9 * cost) it = kIterations;  // converged
          break;
        }
        damping *= 4.0;
      }
      if (!improved) break;
    }
  }
  g.force = problem.model.root_frame * x.head<3>();
  g.root_moment = problem.model.root_frame * x.tail<3>();
  g.shape = std::move(shape);
  g.depth = -boundary.volume->value(g.shape.nodes.back());
  g.reached = std::fabs(layer_coordinate(boundary, g.shape.nodes.back(), scale) - fit.target) <= 0.1;
  g.solves = solves;
  return std::move(problem.g);
}

}  // namespace hairfit
