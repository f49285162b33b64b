// Shooting for the dimensionless rod (docs/design.md §1): given the terminal force f_L and torque t_L,
// find the root moment m(0) with m(1; f_L, m(0)) = t_L.
//
// Under a large load the map m(0) ↦ m(1) is exponentially sensitive (a rod under tension T
// amplifies a root perturbation by about exp(√T)), so plain shooting loses all digits past
// T ≈ 10². We therefore shoot over K pieces of the N-step grid (multiple shooting; K grows like
// √load so each piece amplifies by at most ≈ e³): the unknowns are m(0) and the frame and moment
// at each interior break, the residuals the mismatches at the breaks and m(1) − t_L. Damped
// Newton with the exact Jacobian from jets (6 parameters per piece), backtracking on the
// residual, and load continuation λ: 0 → 1 on (f_L, t_L, f) from the unloaded rod (whose
// solution is exact: m ≡ 0), the step doubling after an easy level and halving after a failure.
//
// On a support (RodModel::support) n(s) is no longer known in closed form: the state at a break
// also holds r and n (12 parameters a piece), the root's unknowns are n(0) and m(0), and the tip
// adds n(1) − f_L to the residuals. The continuation scales the support with the loads.
#pragma once
#include <vector>

#include "rod/rod_integrate.h"

namespace hairfit {

struct ShootingOptions : RodDiscretisation {
  double tolerance = 1e-11;  // on the residual norm, relative to max(1, |f_L|, |t_L|, |f|)
  int max_iterations = 400;  // Newton steps in total
  // When the warm start fails: continue the load from the unloaded rod (true), or give up at once
  // (false: for callers that continue the load themselves and would rather shorten their step).
  bool restart_from_rest = true;
};

struct ShootingResult {
  Vec3 root_moment = Vec3::Zero();      // m(0), the best iterate (always finite)
  Vec3 terminal_moment = Vec3::Zero();  // m(1) reached by the last piece
  // The pieces: step indices 0 = breaks[0] < … < breaks[K] = N, and the state (frame, moment)
  // at the start of each piece (frames[0] = R0, moments[0] = m(0)). Tracing each piece from its
  // own start reproduces the solution without the exponential growth of one long integration.
  std::vector<int> breaks;
  std::vector<Mat3> frames;
  std::vector<Vec3> moments;
  // On a support, also r and n at the start of each piece (positions[0] = 0, forces[0] = n(0));
  // otherwise empty.
  std::vector<Vec3> positions;
  std::vector<Vec3> forces;
  Vec3 terminal_force = Vec3::Zero();    // the loads solved for (a later warm start retraces with them)
  Vec3 terminal_torque = Vec3::Zero();
  Vec3 force_per_length = Vec3::Zero();
  double support_scale = 1.0;
  int iterations = 0;      // Newton steps (Jacobian evaluations)
  double residual = 0.0;   // norm of all mismatches and m(1) − t_L
  bool converged = false;
};

// All quantities dimensionless (rod_integrate.h). `guess` is the warm start for m(0) (zero: none).
ShootingResult shoot_root_moment(const RodModel& model, const Vec3& terminal_force, const Vec3& terminal_torque,
                                 const Vec3& guess, const ShootingOptions& options);

// n(0) of a solution: its first piece's force on a support, else f_L + f.
Vec3 root_force(const ShootingResult& solution);

// The same from an earlier solution at a nearby load (its pieces and their start states), which
// unlike m(0) alone stays a good start under large loads, where a sweep from m(0) diverges.
ShootingResult shoot_root_moment(const RodModel& model, const Vec3& terminal_force, const Vec3& terminal_torque,
                                 const ShootingResult& near, const ShootingOptions& options);

// Traces a solution piece by piece from its start states (one long integration from m(0) would
// amplify its last bit by exp(√tension)); the centreline runs on continuously. Returns m(1).
Vec3 trace_pieces(const RodModel& model, RodIntegrator integrator, int segments, const ShootingResult& solution,
                  const RodTrace<double>& trace);

// Single shooting for a light rod, where one integration from the root keeps its digits (no
// support, loads up to about 50: m(1) depends on m(0) like exp(√load)): undamped Newton on m(0)
// with the 3×3 Jacobian from jets, from `guess`, until |m(1) − t_L| ≤ tolerance or max_steps
// Jacobians. Where Newton's quadratic convergence (|r'| ≈ C·|r|², C from the last two iterates)
// predicts that an iterate meets the tolerance, an integration without jets checks it first: its
// m(1) is bit for bit the jets' value part, so the iterates are the same, and the last one needs
// no Jacobian (jets cost three times as much). Several equilibria exist at the same load (curled
// rods): the caller keeps to one branch by continuing its loads from a nearby solution.
struct SingleShot {
  bool converged = false;           // false: a non-finite step or residual, or max_steps spent
  Vec3 root_moment = Vec3::Zero();  // m(0): the solution when converged, else the last iterate
  Vec3 end_position = Vec3::Zero();  // r(1) and d3(1) of the converged rod (root at the origin)
  Vec3 end_tangent = Vec3::Zero();
  int integrations = 0;             // forward integrations (Newton steps and checks)
};
SingleShot shoot_single(const RodModel& model, const RodDiscretisation& rod, const Vec3& terminal_force,
                        const Vec3& terminal_torque, const Vec3& guess, double tolerance, int max_steps);

// The number of pieces shooting uses for a load: 1 up to |f_L| + |f| ≈ 9, then ≈ √(|f_L| + |f|)/3,
// or on a support ≈ k^¼/3 where its stiffness k makes the equations stiffer still; at most
// min(segments, 48).
int shooting_pieces(const RodModel& model, const Vec3& terminal_force, int segments);

}  // namespace hairfit
