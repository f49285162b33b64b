// Static Cosserat (Kirchhoff) rods in cgs units (paper §3.1, docs/design.md §1): the description of one
// rod, its clamp and loads, and the solved rod. Inextensible, unshearable, hyper-elastic; clamped
// at s = 0, loaded at s = L by a force f_L and a torque t_L, and optionally along its length by a
// constant force per length f (gravity). Internally the rod is dimensionless (rod_integrate.h).
#pragma once
#include <vector>

#include "core/types.h"
#include "rod/rod_integrate.h"

namespace hairfit {

// The rod itself (material and rest shape).
struct Rod {
  double length = 1.0;                  // L, cm
  Vec3 stiffness{1.0, 1.0, 1.0};        // C = diag(E·I1, E·I2, G·J), dyn·cm²
  // κ̂ = (κ̂1, κ̂2, τ̂), 1/cm, material frame: empty = straight; one value = constant; n ≥ 2 values
  // = samples at s = i·L/(n−1), linear in between.
  std::vector<Vec3> natural_curvature;
  Vec3 force_per_length = Vec3::Zero();  // f, dyn/cm, world axes (gravity: ρ·A·g)
};

// A straight rod of circular section: I1 = I2 = A²/(4π), J = 2·I. E, G in dyn/cm², A in cm², L in
// cm. Human hair (paper): E = 3.89e10, G = 0.89e10, A ≈ 1.5e-5.
Rod make_circular_rod(double length, double youngs_modulus, double shear_modulus, double area);

// Throws InputError naming the field when the rod is unusable (non-positive or non-finite length
// or stiffness, non-finite curvature or force).
void validate_rod(const Rod& rod);

// The units of the dimensionless rod: lengths by L, forces by EI/L², moments by EI/L, where EI is
// the reference bending stiffness E·I1 (stiffness[0]).
struct RodScales {
  double length;  // cm
  double force;   // dyn
  double moment;  // dyn·cm
};
RodScales rod_scales(const Rod& rod);

// Where the rod is clamped: r(0) and R(0) = [d1 d2 d3] (orthonormal, d3 the tangent).
struct RodRoot {
  Vec3 position = Vec3::Zero();  // cm
  Mat3 frame = Mat3::Identity();
};

// The dimensionless model of a clamped rod (validates the rod).
RodModel make_rod_model(const Rod& rod, const RodRoot& root);

enum class RodSolver {
  shooting,       // given f_L and t_L: Newton on m(0) with load continuation
  initial_value,  // given f_L and m(0): one forward integration; t_L = m(L) is an output
};

// The loads, world axes. Which of the two moments is given depends on the solver.
struct RodLoad {
  Vec3 terminal_force = Vec3::Zero();   // f_L = n(L), dyn
  Vec3 terminal_torque = Vec3::Zero();  // t_L = m(L), dyn·cm: the target of shooting
  Vec3 root_moment = Vec3::Zero();      // m(0), dyn·cm: given (initial-value) or warm start (shooting)
};

struct RodOptions : RodDiscretisation {
  RodSolver solver = RodSolver::shooting;
  // Shooting converges when |m(L) − t_L|·L/EI ≤ tolerance·max(1, |dimensionless loads|).
  double tolerance = 1e-11;
  int max_iterations = 400;  // Newton steps in total, over all continuation levels
};

// A solved rod: N+1 nodes at s = i·L/N.
struct SolvedRod {
  std::vector<Vec3> nodes;      // r(s_i), cm, world
  std::vector<Mat3> frames;     // R(s_i) = [d1 d2 d3]
  std::vector<Vec3> curvature;  // κ(s_i) = κ̂ + C⁻¹Rᵀm, 1/cm, material frame (κ1, κ2, τ)
  Vec3 terminal_force = Vec3::Zero();   // f_L, dyn
  Vec3 root_moment = Vec3::Zero();      // m(0), dyn·cm
  Vec3 terminal_torque = Vec3::Zero();  // m(L), dyn·cm, as integrated
  int iterations = 0;     // Newton steps (0 for the initial-value form)
  double residual = 0.0;  // |m(L) − t_L|·L/EI (dimensionless; 0 for the initial-value form)
  bool converged = true;  // false: shooting kept its best iterate (finite, but t_L not met)

  const Vec3& tip() const { return nodes.back(); }
  const Mat3& tip_frame() const { return frames.back(); }
};

// Solves one rod with the scheme options.solver selects (docs/design.md §1 eq. r' = d3, R' = R[κ]×,
// n(s) = f_L + f·(L − s), m' = −d3 × n). Throws InputError for a bad rod, non-finite loads or
// segments < 1. Never returns NaN: a shooting solve that fails keeps its best finite iterate and
// says converged = false.
SolvedRod solve_rod(const Rod& rod, const RodRoot& root, const RodLoad& load, const RodOptions& options = {});

}  // namespace hairfit
