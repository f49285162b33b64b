#include "rod/rod_integrate.h"

#include <ceres/jet.h>

#include "core/error.h"
#include "rod/cayley.h"

namespace hairfit {

RodIntegrator parse_rod_integrator(const std::string& name) {
  if (name == "rk2") return RodIntegrator::rk2;
  if (name == "rk4") return RodIntegrator::rk4;
  throw InputError("rod", "unknown integrator \"" + name + "\"; use rk2 (2nd order) or rk4 (4th order)");
}

const char* rod_integrator_name(RodIntegrator integrator) {
  return integrator == RodIntegrator::rk2 ? "rk2" : "rk4";
}

int rod_integrator_order(RodIntegrator integrator) { return integrator == RodIntegrator::rk2 ? 2 : 4; }

namespace {

template <typename T>
using V3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using M3 = Eigen::Matrix<T, 3, 3>;

// κ̂ at arc length s ∈ [0, 1]: constant, or linear between equally spaced samples.
Vec3 kappa_hat_at(const std::vector<Vec3>& kappa_hat, double s) {
  const std::size_t n = kappa_hat.size();
  if (n == 0) return Vec3::Zero();
  if (n == 1) return kappa_hat[0];
  const double x = std::clamp(s, 0.0, 1.0) * static_cast<double>(n - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), n - 2);
  const double t = x - static_cast<double>(i);
  return (1.0 - t) * kappa_hat[i] + t * kappa_hat[i + 1];
}

// Right-hand side at one Runge–Kutta stage, where the frame is R_n·cay(θ) and the moment m.
template <typename T>
struct StageRate {
  V3<T> theta;  // θ' = dcay⁻¹_{−θ}(κ) = κ + θ×κ/2 + θ(θ·κ)/4 (exact for the Cayley map)
  V3<T> r;      // r' = d3
  V3<T> m;      // m' = −d3 × n
};

template <typename T>
struct StepContext {
  const RodModel& model;
  M3<T> frame;     // R_n
  V3<T> force_at;  // n(0) = f_L + f: n(s) = force_at − f·s
  V3<T> f;         // f (dimensionless), as T
  V3<T> compliance;
};

template <typename T>
StageRate<T> stage_rate(const StepContext<T>& ctx, const V3<T>& theta, const V3<T>& m, double s) {
  // Body components of m in the stage frame: cay(θ)ᵀ·R_nᵀ·m = cay(−θ)·(R_nᵀ m).
  const V3<T> body = cayley::apply<T>(-theta, ctx.frame.transpose() * m);
  const V3<T> kappa = ctx.model.kappa_hat.empty()
                          ? V3<T>(ctx.compliance.cwiseProduct(body))
                          : V3<T>(kappa_hat_at(ctx.model.kappa_hat, s).template cast<T>() +
                                  ctx.compliance.cwiseProduct(body));
  StageRate<T> rate;
  rate.theta = kappa + T(0.5) * theta.cross(kappa) + T(0.25) * theta.dot(kappa) * theta;
  rate.r = ctx.frame * cayley::apply<T>(theta, V3<T>::UnitZ());
  const V3<T> n = ctx.force_at - T(s) * ctx.f;  // the stage's own arc length: gravity makes n vary
  rate.m = -rate.r.cross(n);
  return rate;
}

template <typename T>
void write_node(const RodModel& model, const RodTrace<T>& trace, int i, double s, const V3<T>& r, const M3<T>& frame,
                const V3<T>& m, const V3<T>& compliance) {
  if (trace.nodes) Eigen::Map<V3<T>>(trace.nodes + 3 * i) = r;
  if (trace.frames) Eigen::Map<M3<T>>(trace.frames + 9 * i) = frame;
  if (trace.moments) Eigen::Map<V3<T>>(trace.moments + 3 * i) = m;
  if (trace.curvature)
    Eigen::Map<V3<T>>(trace.curvature + 3 * i) =
        kappa_hat_at(model.kappa_hat, s).template cast<T>() + compliance.cwiseProduct(frame.transpose() * m);
}

}  // namespace

template <typename T>
void integrate_rod_steps(const RodModel& model, RodIntegrator integrator, int segments, int first, int last,
                         const T* terminal_force, RodState<T>& state, const RodTrace<T>& trace) {
  const V3<T> f = model.force_per_length.template cast<T>();
  StepContext<T> ctx{model, Eigen::Map<const M3<T>>(state.frame), Eigen::Map<const V3<T>>(terminal_force) + f, f,
                     model.compliance.template cast<T>()};
  V3<T> r = Eigen::Map<const V3<T>>(state.position);
  V3<T> m = Eigen::Map<const V3<T>>(state.moment);
  const double h = 1.0 / segments;
  const V3<T> zero = V3<T>::Zero();
  write_node(model, trace, first, first * h, r, ctx.frame, m, ctx.compliance);
  for (int i = first; i < last; ++i) {
    const double s = i * h;
    V3<T> theta;
    if (integrator == RodIntegrator::rk2) {  // explicit midpoint
      const StageRate<T> k1 = stage_rate(ctx, zero, m, s);
      const StageRate<T> k2 = stage_rate<T>(ctx, T(0.5 * h) * k1.theta, m + T(0.5 * h) * k1.m, s + 0.5 * h);
      theta = T(h) * k2.theta;
      r += T(h) * k2.r;
      m += T(h) * k2.m;
    } else {  // classical RK4 tableau
      const StageRate<T> k1 = stage_rate(ctx, zero, m, s);
      const StageRate<T> k2 = stage_rate<T>(ctx, T(0.5 * h) * k1.theta, m + T(0.5 * h) * k1.m, s + 0.5 * h);
      const StageRate<T> k3 = stage_rate<T>(ctx, T(0.5 * h) * k2.theta, m + T(0.5 * h) * k2.m, s + 0.5 * h);
      const StageRate<T> k4 = stage_rate<T>(ctx, T(h) * k3.theta, m + T(h) * k3.m, s + h);
      const T w = T(h / 6.0);
      theta = w * (k1.theta + T(2.0) * (k2.theta + k3.theta) + k4.theta);
      r += w * (k1.r + T(2.0) * (k2.r + k3.r) + k4.r);
      m += w * (k1.m + T(2.0) * (k2.m + k3.m) + k4.m);
    }
    ctx.frame = ctx.frame * cayley::matrix<T>(theta);
    write_node(model, trace, i + 1, (i + 1) * h, r, ctx.frame, m, ctx.compliance);
  }
  Eigen::Map<V3<T>>(state.position) = r;
  Eigen::Map<M3<T>>(state.frame) = ctx.frame;
  Eigen::Map<V3<T>>(state.moment) = m;
}

template <typename T>
void integrate_rod(const RodModel& model, RodIntegrator integrator, int segments, const T* terminal_force,
                   const T* root_moment, T* terminal_moment, const RodTrace<T>& trace) {
  RodState<T> state;
  Eigen::Map<V3<T>>(state.position) = V3<T>::Zero();
  Eigen::Map<M3<T>>(state.frame) = model.root_frame.template cast<T>();
  for (int k = 0; k < 3; ++k) state.moment[k] = root_moment[k];
  integrate_rod_steps(model, integrator, segments, 0, segments, terminal_force, state, trace);
  for (int k = 0; k < 3; ++k) terminal_moment[k] = state.moment[k];
}

template void integrate_rod<double>(const RodModel&, RodIntegrator, int, const double*, const double*, double*,
                                    const RodTrace<double>&);
template void integrate_rod<ceres::Jet<double, 3>>(const RodModel&, RodIntegrator, int, const ceres::Jet<double, 3>*,
                                                   const ceres::Jet<double, 3>*, ceres::Jet<double, 3>*,
                                                   const RodTrace<ceres::Jet<double, 3>>&);
template void integrate_rod<ceres::Jet<double, 6>>(const RodModel&, RodIntegrator, int, const ceres::Jet<double, 6>*,
                                                   const ceres::Jet<double, 6>*, ceres::Jet<double, 6>*,
                                                   const RodTrace<ceres::Jet<double, 6>>&);

template void integrate_rod_steps<double>(const RodModel&, RodIntegrator, int, int, int, const double*,
    RodState<double>&, const RodTrace<double>&);
template void integrate_rod_steps<ceres::Jet<double, 3>>(const RodModel&, RodIntegrator, int, int, int, const ceres::Jet<double, 3>*,
    RodState<ceres::Jet<double, 3>>&, const RodTrace<ceres::Jet<double, 3>>&);
template void integrate_rod_steps<ceres::Jet<double, 6>>(const RodModel&, RodIntegrator, int, int, int, const ceres::Jet<double, 6>*,
    RodState<ceres::Jet<double, 6>>&, const RodTrace<ceres::Jet<double, 6>>&);

}  // namespace hairfit
