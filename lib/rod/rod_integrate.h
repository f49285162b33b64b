// Forward integration of the static Kirchhoff rod in dimensionless form (docs/design.md §1, paper §3.1):
//   r' = d3,  R' = R [κ]×,  κ = κ̂ + C⁻¹ Rᵀ m,  n(s) = f_L + f·(1 − s),  m' = −d3 × n,
// on s ∈ [0, 1] with r(0) = 0, R(0) = R0 and m(0) given (the initial-value form). The terminal
// moment m(1) is an output. Lengths are in units of L, forces of EI/L², moments of EI/L (rod.h
// converts from cgs).
//
// The integrator is a Runge–Kutta–Munthe-Kaas scheme in Cayley coordinates: within a step
// R = R_n·cay(θ) with θ' = dcay⁻¹(κ), which is exact (no truncated series) and needs no
// trigonometry; every frame is a product of exact rotations, so it stays orthonormal to round-off.
//
// The function is a template on the scalar (double, and ceres::Jet for derivatives) defined in
// rod_integrate.cpp and instantiated there for double, Jet<double, 3> and Jet<double, 6>. This
// header names no Ceres type; code that needs the jets includes rod/rod_jet.h.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/types.h"
#include "rod/rod_support.h"

namespace hairfit {

// The schemes selectable by the scene key rod.integrator: "rk2" (explicit midpoint, order 2) and
// "rk4" (classical Runge–Kutta, order 4), both in their Lie-group (Munthe-Kaas) form.
enum class RodIntegrator { rk2, rk4 };

// Throws InputError for a name other than "rk2" or "rk4".
RodIntegrator parse_rod_integrator(const std::string& name);
const char* rod_integrator_name(RodIntegrator integrator);
int rod_integrator_order(RodIntegrator integrator);

// How a rod is discretised: the scheme and its N steps over the length. Every solver's options
// extend it (RodOptions, ShootingOptions), so one assignment hands it on.
struct RodDiscretisation {
  RodIntegrator integrator = RodIntegrator::rk4;
  int segments = 64;
};

// A rod made dimensionless (make_rod_model in rod.h builds one from cgs values).
struct RodModel {
  Vec3 compliance{1.0, 1.0, 1.0};  // EI_ref·diag(C⁻¹) = (EI_ref/EI1, EI_ref/EI2, EI_ref/GJ)
  // κ̂·L in the material frame: empty = straight; one value = constant; n ≥ 2 values = samples at
  // s = i/(n−1), linearly interpolated in between.
  std::vector<Vec3> kappa_hat;
  Vec3 force_per_length = Vec3::Zero();  // f·L³/EI_ref, world axes (gravity ρ·A·g)
  Mat3 root_frame = Mat3::Identity();    // R(0) = [d1 d2 d3], world axes
  // A support force c(r) along the rod (contact), scaled by support_scale (load continuations
  // scale it with the other loads). With a support, n(s) is a state integrated from n(0), and
  // the initial-value form (integrate_rod) does not apply: solve by shooting (rod_shooting.h).
  std::shared_ptr<const RodSupport> support;
  double support_scale = 1.0;
};

// Where integrate_rod writes its per-node results (node i at s = i/N, N = segments). Every
// pointer may be null; each must otherwise hold (N+1)·3 (or ·9 for frames) scalars.
template <typename T>
struct RodTrace {
  T* nodes = nullptr;      // r(s_i), root at the origin: [x y z] per node
  T* frames = nullptr;     // R(s_i) column-major: d1, d2, d3 (9 scalars per node)
  T* curvature = nullptr;  // κ(s_i) = κ̂ + C⁻¹Rᵀm, material frame (κ1, κ2, τ)
  T* moments = nullptr;    // m(s_i), world axes
  // When set, only the nodes i with only[i] ≠ 0 are written (the guide objective reads its
  // samples alone); the others keep whatever the arrays held.
  const unsigned char* only = nullptr;
};

// One forward integration with `segments` equal steps (segments ≥ 1; not checked here).
// terminal_force f_L[3] and root_moment m(0)[3] in world axes; writes m(1)[3] to
// terminal_moment and whatever `trace` asks for. Allocates nothing.
template <typename T>
void integrate_rod(const RodModel& model, RodIntegrator integrator, int segments, const T* terminal_force,
                   const T* root_moment, T* terminal_moment, const RodTrace<T>& trace);

// The state carried from step to step (world axes, dimensionless): r, R (column-major), m, and
// with a support n (without one, n(s) = f_L + f·(1 − s) in closed form and `force` is not used).
template <typename T>
struct RodState {
  T position[3];
  T frame[9];
  T moment[3];
  T force[3];
};

// Steps first … last−1 of the same N-step grid (s_i = i/N), from `state` at s = first/N; leaves
// the state at s = last/N and writes nodes first … last to `trace` (indexed on the whole grid).
// integrate_rod is this over all steps from (0, R0, m(0)); multiple shooting uses pieces. With a
// support, the state's force n is integrated too (terminal_force is then not read) and its
// position is where the support is evaluated.
template <typename T>
void integrate_rod_steps(const RodModel& model, RodIntegrator integrator, int segments, int first, int last,
                         const T* terminal_force, RodState<T>& state, const RodTrace<T>& trace);

}  // namespace hairfit
