// Derivatives of a multiple-shooting solution (rod_shooting.h) with respect to its terminal loads
// (f_L, t_L), for optimisers whose rods are too heavy for the initial-value form: there the shape
// is a function of the loads only through the boundary-value solve, and its derivative follows
// from the implicit function theorem on the shooting equations G(X; f_L, t_L) = 0:
//   dX/d(f_L, t_L) = −G_X⁻¹ · G_(f_L, t_L),
// X the start state (frame, moment) of every piece. Tracing each piece from its start state with
// jets seeded by these derivatives gives every node's exact derivative (to round-off), without
// the exponential growth of one long integration. Includes Ceres' jets: only for code that needs
// derivatives (the guide optimiser).
#pragma once
#include <Eigen/Core>
#include <vector>

#include "rod/rod_jet.h"
#include "rod/rod_shooting.h"

namespace hairfit {

// Per piece k, the 12×6 derivative of its start state (δr_k, δφ_k, δn_k, δm_k) — δφ the Cayley
// coordinates of the frame correction R_k·cay(δφ) — with respect to (f_L, t_L). The clamped root
// has δr = δφ = 0; without a support δr and δn are zero too (n is a closed form of the loads and
// the centreline runs on from piece to piece). Empty when the shooting Jacobian is singular.
using PieceSensitivity = Eigen::Matrix<double, 12, 6>;
std::vector<PieceSensitivity> shooting_sensitivity(const RodModel& model, const ShootingResult& solution,
                                                              const ShootingOptions& options);

// The first-order prediction of the solution at nearby loads (f_L, t_L): every piece's start state
// moved by its sensitivity times the load change. A warm start for shoot_root_moment whose error
// is quadratic in the change, where the solution itself as a start has a linear one.
ShootingResult predicted_solution(const ShootingResult& solution, const std::vector<PieceSensitivity>& sensitivity,
                                  const Vec3& terminal_force, const Vec3& terminal_torque);

// Traces the solution piece by piece with jets over (f_L, t_L): nodes, frames and curvature as in
// RodTrace, each carrying its derivative.
void trace_pieces(const RodModel& model, RodIntegrator integrator, int segments, const ShootingResult& solution,
                  const std::vector<PieceSensitivity>& sensitivity, const RodTrace<RodJet6>& trace);

}  // namespace hairfit
