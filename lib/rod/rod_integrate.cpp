#include "rod/rod_integrate.h"

#include <algorithm>
#include <array>
#include <type_traits>

#include <ceres/jet.h>

#include "core/error.h"
#include "rod/cayley.h"
#include "rod/rod_point_forces.h"

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

// A forward-mode dual number with N tangents. The integrator runs on it in place of
// ceres::Jet<double, N>, whose Eigen expression templates GCC left as out-of-line calls here
// (~25× the double cost). The tangents are held in explicit SIMD packs P (GCC vector extension:
// two doubles for SSE2, four for AVX2; unused slots of the last pack stay zero), so they are
// vectorised the same way whatever the inliner decides. The value part does exactly the double
// operations, so a jet run's values are bit for bit the double run's.
typedef double Pair2 __attribute__((vector_size(16)));
typedef double Pair4 __attribute__((vector_size(32)));
typedef double Pair8 __attribute__((vector_size(64)));

template <int N, typename P>
struct Dual {
  static constexpr int W = sizeof(P) / sizeof(double);
  static constexpr int K = (N + W - 1) / W;
  P v[K];
  double a;
};

template <int N, typename P>
inline Dual<N, P> operator+(const Dual<N, P>& x, const Dual<N, P>& y) {
  Dual<N, P> z;
  z.a = x.a + y.a;
  for (int k = 0; k < Dual<N, P>::K; ++k) z.v[k] = x.v[k] + y.v[k];
  return z;
}
template <int N, typename P>
inline Dual<N, P> operator-(const Dual<N, P>& x, const Dual<N, P>& y) {
  Dual<N, P> z;
  z.a = x.a - y.a;
  for (int k = 0; k < Dual<N, P>::K; ++k) z.v[k] = x.v[k] - y.v[k];
  return z;
}
template <int N, typename P>
inline Dual<N, P> operator-(const Dual<N, P>& x) {
  Dual<N, P> z;
  z.a = -x.a;
  for (int k = 0; k < Dual<N, P>::K; ++k) z.v[k] = -x.v[k];
  return z;
}
template <int N, typename P>
inline Dual<N, P> operator*(const Dual<N, P>& x, const Dual<N, P>& y) {
  Dual<N, P> z;
  z.a = x.a * y.a;
  for (int k = 0; k < Dual<N, P>::K; ++k) z.v[k] = x.a * y.v[k] + x.v[k] * y.a;
  return z;
}
template <int N, typename P>
inline Dual<N, P> operator*(double s, const Dual<N, P>& x) {
  Dual<N, P> z;
  z.a = s * x.a;
  for (int k = 0; k < Dual<N, P>::K; ++k) z.v[k] = s * x.v[k];
  return z;
}
template <int N, typename P>
inline Dual<N, P> operator*(const Dual<N, P>& x, double s) {
  Dual<N, P> z;
  z.a = x.a * s;
  for (int k = 0; k < Dual<N, P>::K; ++k) z.v[k] = x.v[k] * s;
  return z;
}
template <int N, typename P>
inline Dual<N, P> operator+(double s, const Dual<N, P>& x) {
  Dual<N, P> z = x;
  z.a = s + x.a;
  return z;
}
template <int N, typename P>
inline Dual<N, P> operator+(const Dual<N, P>& x, double s) {
  Dual<N, P> z = x;
  z.a = x.a + s;
  return z;
}
template <int N, typename P>
inline Dual<N, P> operator-(double s, const Dual<N, P>& x) {
  Dual<N, P> z;
  z.a = s - x.a;
  for (int k = 0; k < Dual<N, P>::K; ++k) z.v[k] = -x.v[k];
  return z;
}
template <int N, typename P>
inline Dual<N, P> operator-(const Dual<N, P>& x, double s) {
  Dual<N, P> z = x;
  z.a = x.a - s;
  return z;
}
template <int N, typename P>
inline Dual<N, P> square(const Dual<N, P>& x) {  // x·x with half the tangent work, same bits as x * x
  Dual<N, P> z;
  z.a = x.a * x.a;
  const double d = 2.0 * x.a;
  for (int k = 0; k < Dual<N, P>::K; ++k) z.v[k] = d * x.v[k];
  return z;
}
inline double square(double x) { return x * x; }
template <int N, typename P>
inline Dual<N, P> operator/(double s, const Dual<N, P>& x) {  // d(s/x) = −(s/x)/x·dx
  Dual<N, P> z;
  z.a = s / x.a;
  const double d = -z.a / x.a;
  for (int k = 0; k < Dual<N, P>::K; ++k) z.v[k] = d * x.v[k];
  return z;
}

// Between the public scalar T and the working scalar S (double stays double, Jet becomes Dual).
inline void to_work(double x, double& out) { out = x; }
inline void to_public(double x, double& out) { out = x; }
template <int N, typename P>
inline void to_work(const ceres::Jet<double, N>& x, Dual<N, P>& z) {
  z.a = x.a;
  z.v[Dual<N, P>::K - 1] = P{};
  for (int k = 0; k < N; ++k) z.v[k / Dual<N, P>::W][k % Dual<N, P>::W] = x.v[k];
}
template <int N, typename P>
inline void to_public(const Dual<N, P>& x, ceres::Jet<double, N>& out) {
  out.a = x.a;
  for (int k = 0; k < N; ++k) out.v[k] = x.v[k / Dual<N, P>::W][k % Dual<N, P>::W];
}
template <typename T, typename P>
struct Work {
  using type = double;
};
template <int N, typename P>
struct Work<ceres::Jet<double, N>, P> {
  using type = Dual<N, P>;
};

// 3-vectors and column-major 3×3 matrices on the scalar, as plain arrays.
template <typename S>
using V = std::array<S, 3>;
template <typename S>
using M = std::array<S, 9>;

template <typename S>
inline V<S> cross(const V<S>& a, const V<S>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
template <typename S>
inline S dot(const V<S>& a, const V<S>& b) {
  return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}
template <typename S>
inline V<S> times(const M<S>& r, const V<S>& v) {  // R·v
  return {(r[0] * v[0] + r[3] * v[1]) + r[6] * v[2], (r[1] * v[0] + r[4] * v[1]) + r[7] * v[2],
          (r[2] * v[0] + r[5] * v[1]) + r[8] * v[2]};
}
template <typename S, typename U>
inline V<S> transpose_times(const M<S>& r, const V<U>& v) {  // Rᵀ·v, v on S or double
  return {(r[0] * v[0] + r[1] * v[1]) + r[2] * v[2], (r[3] * v[0] + r[4] * v[1]) + r[5] * v[2],
          (r[6] * v[0] + r[7] * v[1]) + r[8] * v[2]};
}
template <typename S>
inline M<S> times(const M<S>& a, const M<S>& b) {  // A·B
  M<S> c;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) c[3 * j + i] = (a[i] * b[3 * j] + a[3 + i] * b[3 * j + 1]) + a[6 + i] * b[3 * j + 2];
  return c;
}

// What stays fixed over one call, in double.
struct Constants {
  const std::vector<Vec3>& kappa_hat;
  Vec3 compliance;
  Vec3 f;        // force per length, world axes
  bool gravity;  // f ≠ 0: n varies along the rod
};

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

// κ = κ̂ + C⁻¹·(body components of m).
template <typename S>
inline V<S> curvature(const Constants& k, const V<S>& body, double s) {
  V<S> kappa{k.compliance[0] * body[0], k.compliance[1] * body[1], k.compliance[2] * body[2]};
  if (!k.kappa_hat.empty()) {
    const Vec3 kh = kappa_hat_at(k.kappa_hat, s);
    for (int i = 0; i < 3; ++i) kappa[i] = kh[i] + kappa[i];
  }
  return kappa;
}

// The loads seen from the step's start frame R_n (its body coordinates). Every stage of the step
// works in these coordinates, so a stage needs no product with R_n; the step maps its increments
// back to world axes once.
template <typename S>
struct Local {
  V<S> mu;   // R_nᵀ m
  V<S> nu;   // R_nᵀ n(0) = R_nᵀ (f_L + f)
  V<S> phi;  // R_nᵀ f (only with gravity)
};

template <typename S>
inline void local_loads(const Constants& k, const M<S>& frame, const V<S>& m, const V<S>& force_at, Local<S>& local) {
  local.mu = transpose_times(frame, m);
  local.nu = transpose_times(frame, force_at);
  if (k.gravity) local.phi = transpose_times(frame, V<double>{k.f[0], k.f[1], k.f[2]});
}

template <typename S>
inline V<S> force(const Constants& k, const Local<S>& local, double s) {  // R_nᵀ n(s), n = n(0) − s·f
  if (!k.gravity) return local.nu;
  return {local.nu[0] - s * local.phi[0], local.nu[1] - s * local.phi[1], local.nu[2] - s * local.phi[2]};
}

// The rates at one Runge–Kutta stage, where the frame is R_n·cay(θ), in R_n's body coordinates.
template <typename S>
struct Rate {
  V<S> theta;  // θ' = dcay⁻¹_{−θ}(κ) = κ + θ×κ/2 + θ(θ·κ)/4 (exact for the Cayley map)
  V<S> t;      // R_nᵀ r' = cay(θ)·e3
  V<S> mu;     // R_nᵀ m' = −t × R_nᵀ n
};

// The first stage (θ = 0): cay = I, so κ comes from μ directly and t = e3 (not stored).
// n = R_nᵀ n(s) at the stage's arc length s.
template <typename S>
inline Rate<S> first_rate(const Constants& k, const V<S>& mu, const V<S>& n, double s) {
  Rate<S> rate;
  rate.theta = curvature(k, mu, s);
  rate.mu = {n[1], -n[0], S{}};  // −e3 × n
  return rate;
}

template <typename S>
inline Rate<S> stage_rate(const Constants& k, const V<S>& theta, const V<S>& mu, const V<S>& n, double s) {
  const S xx = square(theta[0]), yy = square(theta[1]);
  const S c = 4.0 / (4.0 + ((xx + yy) + square(theta[2])));
  const S ch = 0.5 * c;
  // Body components of m in the stage frame: cay(−θ)μ = μ + c·(θ×(θ×μ)/2 − θ×μ).
  const V<S> tm = cross(theta, mu);
  const V<S> ttm = cross(theta, tm);
  V<S> body;
  for (int i = 0; i < 3; ++i) body[i] = mu[i] + c * (0.5 * ttm[i] - tm[i]);
  const V<S> kappa = curvature(k, body, s);
  Rate<S> rate;
  const V<S> tk = cross(theta, kappa);
  const S d = 0.25 * dot(theta, kappa);
  for (int i = 0; i < 3; ++i) rate.theta[i] = (kappa[i] + 0.5 * tk[i]) + d * theta[i];
  // cay(θ)e3 = e3 + c·θ×e3 + c/2·θ×(θ×e3), with θ×e3 = (θ1, −θ0, 0).
  rate.t = {c * theta[1] + ch * (theta[0] * theta[2]), ch * (theta[1] * theta[2]) - c * theta[0],
            1.0 - ch * (xx + yy)};
  rate.mu = cross(n, rate.t);
  return rate;
}

template <typename S>
inline V<S> advance(const V<S>& x, double step, const V<S>& rate) {  // x + step·rate
  return {x[0] + step * rate[0], x[1] + step * rate[1], x[2] + step * rate[2]};
}
template <typename S>
inline V<S> scaled(double step, const V<S>& rate) {
  return {step * rate[0], step * rate[1], step * rate[2]};
}

// The classical RK4 increment w·(k1 + 2·(k2 + k3) + k4) of one 3-vector, w = h/6; and of r, whose
// first stage rate is e3 in the step's own frame.
template <typename S>
inline V<S> rk4_increment(double w, const V<S>& k1, const V<S>& k2, const V<S>& k3, const V<S>& k4) {
  V<S> out;
  for (int a = 0; a < 3; ++a) out[a] = w * ((k1[a] + 2.0 * (k2[a] + k3[a])) + k4[a]);
  return out;
}
template <typename S>
inline V<S> rk4_position_increment(double w, const Rate<S>& k2, const Rate<S>& k3, const Rate<S>& k4) {
  return {w * (2.0 * (k2.t[0] + k3.t[0]) + k4.t[0]), w * (2.0 * (k2.t[1] + k3.t[1]) + k4.t[1]),
          w * ((1.0 + 2.0 * (k2.t[2] + k3.t[2])) + k4.t[2])};
}

template <typename T, typename S>
inline void write_node(const Constants& k, const RodTrace<T>& trace, int i, double s, const V<S>& r, const M<S>& frame,
                       const V<S>& m, const Local<S>& local) {
  if (trace.only && !trace.only[i]) return;
  if (trace.nodes)
    for (int a = 0; a < 3; ++a) to_public(r[a], trace.nodes[3 * i + a]);
  if (trace.frames)
    for (int a = 0; a < 9; ++a) to_public(frame[a], trace.frames[9 * i + a]);
  if (trace.moments)
    for (int a = 0; a < 3; ++a) to_public(m[a], trace.moments[3 * i + a]);
  if (trace.curvature) {
    const V<S> kappa = curvature(k, local.mu, s);
    for (int a = 0; a < 3; ++a) to_public(kappa[a], trace.curvature[3 * i + a]);
  }
}

// A constant on the working scalar (no tangents).
template <typename S>
inline S constant(double x) {
  S z{};
  if constexpr (std::is_same_v<S, double>) z = x; else z.a = x;
  return z;
}

// The support's force c(r) on the working scalar: for jets, its tangents follow from ∂c/∂r by the
// chain rule, so the support itself sees doubles only.
inline V<double> support_force(const RodModel& model, const V<double>& r) {
  V<double> c;
  model.support->force(r.data(), c.data(), nullptr);
  return {model.support_scale * c[0], model.support_scale * c[1], model.support_scale * c[2]};
}
template <int N, typename P>
inline V<Dual<N, P>> support_force(const RodModel& model, const V<Dual<N, P>>& r) {
  const double at[3] = {r[0].a, r[1].a, r[2].a};
  double c[3], jacobian[9];
  model.support->force(at, c, jacobian);
  V<Dual<N, P>> out;
  for (int i = 0; i < 3; ++i) {
    const double j0 = model.support_scale * jacobian[i], j1 = model.support_scale * jacobian[3 + i],
                 j2 = model.support_scale * jacobian[6 + i];
    out[i].a = model.support_scale * c[i];
    for (int k = 0; k < Dual<N, P>::K; ++k) out[i].v[k] = (j0 * r[0].v[k] + j1 * r[1].v[k]) + j2 * r[2].v[k];
  }
  return out;
}

// The steps of a rod on a support: n joins the state, n' = −f − c(r), its stages in R_n's body
// coordinates like μ's; the support is evaluated at each stage's position r_n + R_n·Δr, where Δr
// is the stage's increment of r (the same tableau as every other component).
template <typename T, typename P>
inline void supported_steps(const RodModel& model, RodIntegrator integrator, int segments, int first, int last,
                            RodState<T>& state, const RodTrace<T>& trace) {
  using S = typename Work<T, P>::type;
  const Constants k{model.kappa_hat, model.compliance, model.force_per_length, !model.force_per_length.isZero(0.0)};
  V<S> r, m, n;
  M<S> frame;
  for (int a = 0; a < 3; ++a) {
    to_work(state.position[a], r[a]);
    to_work(state.moment[a], m[a]);
    to_work(state.force[a], n[a]);
  }
  for (int a = 0; a < 9; ++a) to_work(state.frame[a], frame[a]);
  const double h = 1.0 / segments, hh = 0.5 * h, w = h / 6.0;
  Local<S> local;
  local.phi = {};
  local_loads(k, frame, m, n, local);
  // R_nᵀ n' at the stage whose position is r_n + R_n·Δr (Δr in body coordinates).
  auto force_rate = [&](const V<S>& dr) {
    V<S> at = times(frame, dr);
    for (int a = 0; a < 3; ++a) at[a] = r[a] + at[a];
    const V<S> c = transpose_times(frame, support_force(model, at));
    return V<S>{-(local.phi[0] + c[0]), -(local.phi[1] + c[1]), -(local.phi[2] + c[2])};
  };
  write_node(k, trace, first, first * h, r, frame, m, local);
  for (int i = first; i < last; ++i) {
    const double s = i * h;
    V<S> theta, dr, dm, dn;
    const Rate<S> k1 = first_rate(k, local.mu, local.nu, s);
    const V<S> n1 = force_rate(V<S>{S{}, S{}, S{}});
    const V<S> up_half{S{}, S{}, constant<S>(hh)};
    if (integrator == RodIntegrator::rk2) {
      const Rate<S> k2 = stage_rate(k, scaled(hh, k1.theta), advance(local.mu, hh, k1.mu), advance(local.nu, hh, n1), s + hh);
      const V<S> n2 = force_rate(up_half);
      theta = scaled(h, k2.theta);
      dr = scaled(h, k2.t);
      dm = scaled(h, k2.mu);
      dn = scaled(h, n2);
    } else {
      const Rate<S> k2 = stage_rate(k, scaled(hh, k1.theta), advance(local.mu, hh, k1.mu), advance(local.nu, hh, n1), s + hh);
      const V<S> n2 = force_rate(up_half);
      const Rate<S> k3 = stage_rate(k, scaled(hh, k2.theta), advance(local.mu, hh, k2.mu), advance(local.nu, hh, n2), s + hh);
      const V<S> n3 = force_rate(scaled(hh, k2.t));
      const Rate<S> k4 = stage_rate(k, scaled(h, k3.theta), advance(local.mu, h, k3.mu), advance(local.nu, h, n3), s + h);
      const V<S> n4 = force_rate(scaled(h, k3.t));
      theta = rk4_increment(w, k1.theta, k2.theta, k3.theta, k4.theta);
      dm = rk4_increment(w, k1.mu, k2.mu, k3.mu, k4.mu);
      dn = rk4_increment(w, n1, n2, n3, n4);
      dr = rk4_position_increment(w, k2, k3, k4);
    }
    const V<S> dr_world = times(frame, dr), dm_world = times(frame, dm), dn_world = times(frame, dn);
    for (int a = 0; a < 3; ++a) {
      r[a] = r[a] + dr_world[a];
      m[a] = m[a] + dm_world[a];
      n[a] = n[a] + dn_world[a];
    }
    M<S> q;
    cayley::fill_matrix<S>(theta.data(), q.data());
    frame = times(frame, q);
    local_loads(k, frame, m, n, local);
    write_node(k, trace, i + 1, (i + 1) * h, r, frame, m, local);
  }
  for (int a = 0; a < 3; ++a) {
    to_public(r[a], state.position[a]);
    to_public(m[a], state.moment[a]);
    to_public(n[a], state.force[a]);
  }
  for (int a = 0; a < 9; ++a) to_public(frame[a], state.frame[a]);
}

// integrate_rod_steps on the working scalar with tangent packs P (compiled twice, see below).
template <typename T, typename P>
inline void steps(const RodModel& model, RodIntegrator integrator, int segments, int first, int last,
                  const T* terminal_force, RodState<T>& state, const RodTrace<T>& trace) {
  if (model.support) return supported_steps<T, P>(model, integrator, segments, first, last, state, trace);
  using S = typename Work<T, P>::type;
  const Constants k{model.kappa_hat, model.compliance, model.force_per_length, !model.force_per_length.isZero(0.0)};
  V<S> r, m, force_at;
  M<S> frame;
  for (int a = 0; a < 3; ++a) {
    to_work(state.position[a], r[a]);
    to_work(state.moment[a], m[a]);
    to_work(terminal_force[a], force_at[a]);
    force_at[a] = force_at[a] + k.f[a];
  }
  for (int a = 0; a < 9; ++a) to_work(state.frame[a], frame[a]);
  const double h = 1.0 / segments, hh = 0.5 * h, w = h / 6.0;
  Local<S> local;
  if (!k.gravity) local.phi = {};
  local_loads(k, frame, m, force_at, local);
  write_node(k, trace, first, first * h, r, frame, m, local);
  for (int i = first; i < last; ++i) {
    const double s = i * h;
    // θ, R_nᵀΔr and R_nᵀΔm over the step.
    V<S> theta, dr, dm;
    const Rate<S> k1 = first_rate(k, local.mu, force(k, local, s), s);
    const V<S> n_mid = force(k, local, s + hh);
    if (integrator == RodIntegrator::rk2) {  // explicit midpoint
      const Rate<S> k2 = stage_rate(k, scaled(hh, k1.theta), advance(local.mu, hh, k1.mu), n_mid, s + hh);
      theta = scaled(h, k2.theta);
      dr = scaled(h, k2.t);
      dm = scaled(h, k2.mu);
    } else {  // classical RK4 tableau
      const Rate<S> k2 = stage_rate(k, scaled(hh, k1.theta), advance(local.mu, hh, k1.mu), n_mid, s + hh);
      const Rate<S> k3 = stage_rate(k, scaled(hh, k2.theta), advance(local.mu, hh, k2.mu), n_mid, s + hh);
      const Rate<S> k4 = stage_rate(k, scaled(h, k3.theta), advance(local.mu, h, k3.mu), force(k, local, s + h), s + h);
      theta = rk4_increment(w, k1.theta, k2.theta, k3.theta, k4.theta);
      dm = rk4_increment(w, k1.mu, k2.mu, k3.mu, k4.mu);
      dr = rk4_position_increment(w, k2, k3, k4);
    }
    const V<S> dr_world = times(frame, dr), dm_world = times(frame, dm);
    for (int a = 0; a < 3; ++a) {
      r[a] = r[a] + dr_world[a];
      m[a] = m[a] + dm_world[a];
    }
    M<S> q;
    cayley::fill_matrix<S>(theta.data(), q.data());
    frame = times(frame, q);
    if (i + 1 < last || trace.curvature) local_loads(k, frame, m, force_at, local);
    write_node(k, trace, i + 1, (i + 1) * h, r, frame, m, local);
  }
  for (int a = 0; a < 3; ++a) {
    to_public(r[a], state.position[a]);
    to_public(m[a], state.moment[a]);
  }
  for (int a = 0; a < 9; ++a) to_public(frame[a], state.frame[a]);
}

// The integrator compiled for the baseline x86-64 (SSE2, tangents in pairs), for AVX2 (tangents
// in fours) and, for the guides' six tangents, for AVX-512 (all six in one pack: half the tangent
// instructions of two AVX2 packs; the guide solves' Jacobians are the largest single cost of a
// run), chosen at run time. -ffp-contract=off keeps FMA out even where the target has it, so all
// variants do the same IEEE operations in the same order: the results are bit for bit the same.
// flatten inlines the stages, so that all of a variant is compiled for its target.
#if defined(__GNUC__) && defined(__x86_64__)
#define HAIRFIT_ROD_AVX2 1
template <typename T>
__attribute__((target("avx2"), flatten)) void steps_avx2(const RodModel& model, RodIntegrator integrator,
                                                         int segments, int first, int last, const T* terminal_force,
                                                         RodState<T>& state, const RodTrace<T>& trace) {
  steps<T, Pair4>(model, integrator, segments, first, last, terminal_force, state, trace);
}
__attribute__((target("avx512f"), flatten)) void steps_avx512(const RodModel& model, RodIntegrator integrator,
                                                              int segments, int first, int last,
                                                              const ceres::Jet<double, 6>* terminal_force,
                                                              RodState<ceres::Jet<double, 6>>& state,
                                                              const RodTrace<ceres::Jet<double, 6>>& trace) {
  steps<ceres::Jet<double, 6>, Pair8>(model, integrator, segments, first, last, terminal_force, state, trace);
}
template <typename T>
constexpr bool kSixTangents = std::is_same_v<T, ceres::Jet<double, 6>>;
#endif

}  // namespace

template <typename T>
void integrate_rod_steps(const RodModel& model, RodIntegrator integrator, int segments, int first, int last,
                         const T* terminal_force, RodState<T>& state, const RodTrace<T>& trace) {
#ifdef HAIRFIT_ROD_AVX2
  if constexpr (kSixTangents<T>)
    if (__builtin_cpu_supports("avx512f"))
      return steps_avx512(model, integrator, segments, first, last, terminal_force, state, trace);
  if (__builtin_cpu_supports("avx2"))
    return steps_avx2<T>(model, integrator, segments, first, last, terminal_force, state, trace);
#endif
  steps<T, Pair2>(model, integrator, segments, first, last, terminal_force, state, trace);
}

// The rod without interior point forces: one piece.
template <typename T>
void integrate_rod(const RodModel& model, RodIntegrator integrator, int segments, const T* terminal_force,
                   const T* root_moment, T* terminal_moment, const RodTrace<T>& trace) {
  integrate_rod_with_point_forces<T>(model, integrator, segments, terminal_force, root_moment, nullptr, 0,
                                     terminal_moment, trace);
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

// The guides' loads with 1, 2 or 3 interior point forces (rod_point_forces.h): 9, 12, 15 tangents.
#define HAIRFIT_ROD_STEPS(N)                                                                          \
  template void integrate_rod_steps<ceres::Jet<double, N>>(const RodModel&, RodIntegrator, int, int, int, \
      const ceres::Jet<double, N>*, RodState<ceres::Jet<double, N>>&, const RodTrace<ceres::Jet<double, N>>&);
HAIRFIT_ROD_STEPS(9)
HAIRFIT_ROD_STEPS(12)
HAIRFIT_ROD_STEPS(15)
#undef HAIRFIT_ROD_STEPS

}  // namespace hairfit
