#include "guides/layer_preguide.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "core/smoothstep.h"
#include "guides/styled_rest.h"

namespace hairfit {

namespace {

constexpr double kOutsidePenalty = 4.0;  // weight of an excursion below kMargin or above 1 − kMargin in λ
constexpr double kMargin = 0.15;         // the share of the layer kept clear at either side
constexpr double kLoadRegularisation = 1e-3;  // prefers the smaller load where the layer leaves a choice
constexpr int kIterations = 40;
constexpr double kFollowWeight = 0.5;  // the growth field's pull against the immersion depth's
// A styled rod's pull toward its rest tangents (3D, climb included): at the field's 0.5, the fit
// traded the rest shape's flow for depth, rods climbed and dived by up to 45° across each other,
// and the plain sculpted bust's pre-guides crossed at 0.093; at 1 / 2 / 4 they cross at 0.064 /
// 0.041 / 0.020 with 414 / 417 / 373 of 438 at their depth (bench/results/prepare.md).
constexpr double kStyledFollowWeight = 2.0;

using Load = Eigen::Matrix<double, 6, 1>;

// The fit of one pre-guide's load: its rod, where it is to run, and the residuals of a shape.
struct LayerFit {
  RodModel model;
  const PreguideOptions* options;
  const Boundary* boundary;
  Vec3 root;
  double length;
  double target;  // λ*
  double scale;   // cm: the layer coordinate's unit outside the layer (layer_coordinate)
  // Styled along the flow (PreguideOptions::styled): the unloaded rod's tangents, which the loaded
  // one follows in place of the field (so it keeps the rest shape's gentle climb, too); else empty.
  std::vector<Vec3> rest_tangents;

  // x: the load in the root frame (d1, d2, d3): terminal force x[0..2], root couple x[3..5].
  FibreShape shape(const Load& x) const {
    const Mat3& frame = model.root_frame;
    return fibre_shape(model, root, length, options->rod, frame * x.head<3>(), frame * x.tail<3>());
  }

  // Residuals: per node after the root, the weighted miss of λ and the two excursion penalties;
  // with the growth field, per node the tangent's part along the scalp against the field there;
  // then the regularisation of the load. Past the root the first quarter ramps in (smoothstep).
  Eigen::VectorXd residuals(const FibreShape& s, const Load& x) const {
    const int n = static_cast<int>(s.nodes.size());
    const FlowLookup* flow = options->flow.get();
    Eigen::VectorXd r((flow ? 6 : 3) * (n - 1) + 6);
    const double root_n = std::sqrt(static_cast<double>(n - 1));
    for (int k = 1; k < n; ++k) {
      const double ramp = smoothstep((static_cast<double>(k) / (n - 1)) / 0.25);
      const double lambda = layer_coordinate(*boundary, s.nodes[k], scale);
      r[3 * (k - 1)] = ramp / root_n * (lambda - target);
      r[3 * (k - 1) + 1] = kOutsidePenalty * std::max(0.0, lambda - (1.0 - kMargin));
      r[3 * (k - 1) + 2] = kOutsidePenalty * std::max(0.0, kMargin - lambda) * ramp;
      if (!rest_tangents.empty()) {
        r.segment<3>(3 * (n - 1) + 3 * (k - 1)) = kStyledFollowWeight * ramp / root_n * (s.tangents[k] - rest_tangents[k]);
        continue;
      }
      if (!flow) continue;
      Vec3 normal;
      const Vec3 field = flow->at(s.nodes[k], &normal);
      const Vec3 t = s.tangents[k] - s.tangents[k].dot(normal) * normal;
      const double m = t.norm();
      const Vec3 miss = field.isZero(0.0) || !(m > 1e-12) ? Vec3::Zero() : Vec3(t / m - field);
      r.segment<3>(3 * (n - 1) + 3 * (k - 1)) = kFollowWeight * ramp / root_n * miss;
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

LayerFit layer_fit(const PreGuide& g, const Boundary& boundary, const PreguideOptions& o) {
  const Mat3 frame = root_frame(g.direction, bending_direction(g.normal, g.direction, o.down, o.front));
  RodModel model = make_rod_model(hair_rod(g.length, o.material), RodRoot{g.root, frame});
  const bool styled = o.styled && o.flow;
  if (styled)
    model.kappa_hat = styled_rest(*o.flow, boundary, g.root, frame, g.length, immersion_share(o, g.height), o.rod.segments);
  LayerFit fit{std::move(model),
               &o,
               &boundary,
               g.root,
               g.length,
               1.0 - immersion_share(o, g.height),
               std::max(g.thickness, 0.5 * boundary.volume->voxel()),
               {}};
  if (styled) fit.rest_tangents = fit.shape(Load::Zero()).tangents;
  return fit;
}

}  // namespace

double layer_preguide_cost(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& o, double force,
                           double couple) {
  const LayerFit fit = layer_fit(preguide_start(roots, i, boundary, o), boundary, o);
  Load x = Load::Zero();
  x[0] = force, x[4] = couple;
  return fit.residuals(fit.shape(x), x).squaredNorm();
}

PreGuide solve_layer_preguide(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& o) {
  PreGuide g = preguide_start(roots, i, boundary, o);
  const LayerFit fit = layer_fit(g, boundary, o);

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
  g.force = fit.model.root_frame * x.head<3>();
  g.root_moment = fit.model.root_frame * x.tail<3>();
  g.shape = std::move(shape);
  g.depth = -boundary.volume->value(g.shape.nodes.back());
  g.reached = std::fabs(layer_coordinate(boundary, g.shape.nodes.back(), fit.scale) - fit.target) <= 0.1;
  g.solves = solves;
  return g;
}

}  // namespace hairfit
