// The principal-guide objective (paper eq. 6–9, docs/design.md §5) as least-squares residuals, and its
// minimisation with Ceres. Internal to lib/guides: Ceres and jets stay in objective.cpp.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "density/grid.h"
#include "guides/density_term.h"
#include "guides/guides.h"
#include "rod/rod_jet.h"
#include "rod/rod_shooting.h"

namespace hairfit {

// A guide's loads: the paper's six (f_L, m(0)) and, with guides.point_forces, up to three interior
// point forces F_k (rod_point_forces.h), three scalars each, after them.
constexpr int kMaxPointForces = 3;
constexpr int kMaxGuideLoads = 6 + 3 * kMaxPointForces;
// The point forces a load vector of scalar T carries: (N − 6)/3 for jets with one tangent per
// load, up to the most for double. Loops over a guide's point forces are bounded by it, so that a
// jet's load array is never read past its end.
template <typename T>
constexpr int kPointForcesCarried = kMaxPointForces;
template <int N>
constexpr int kPointForcesCarried<ceres::Jet<double, N>> = (N - 6) / 3;

// Everything one guide's objective reads; sampled at K+1 nodes of the rod (normalised arc length
// s_k = k/K), the pre-guides at the same normalised arc lengths.
struct GuideTargets {
  RodModel model;
  Vec3 root = Vec3::Zero();
  double length = 1.0;  // cm
  RodDiscretisation rod;
  // Interior point forces (0: the paper's terminal load alone; weightless or weighted single
  // shooting only) and w5, the weight of F5 = Σ|F_k|² on them.
  int point_forces = 0;
  double point_force_weight = 0.0;
  int load_count() const { return 6 + 3 * point_forces; }
  std::vector<int> sample_nodes;       // node index of each sample
  std::vector<double> sample_weights;  // trapezoidal Δs of each sample (sum 1)
  struct Neighbour {
    double weight = 0.0;          // ω_j, Σ ω_j = 1
    std::vector<Vec3> tangents;   // at the samples
    std::vector<Vec3> darboux;    // at the samples
    // Per sample, in [0, 1]: how far the pre-guide is to be followed there (empty: everywhere).
    std::vector<double> trust;
    double weight_at(std::size_t k) const { return trust.empty() ? weight : weight * trust[k]; }
  };
  std::vector<Neighbour> neighbours;
  const Boundary* boundary = nullptr;
  GuideWeights weights;
  BoundaryForm form = BoundaryForm::smooth;
  double outside_penalty = 10.0;
  double boundary_width = 0.1;
  // The density of the earlier guides (paper §3.5); null: no density model, no F4 residual.
  std::optional<DensityGrid> density;  // the F4 term's grid (sharing its cells), or none
  DensityTermOptions density_term;
  // The F4 integrand a sample pays once it lies a voxel or more beyond the scalp or the volume
  // boundary: the ceiling of the grid the guide is optimised against (DensityCeiling, one per
  // batch). Outside the acceptable region F4 is then never lower than anywhere inside, so leaving
  // the region cannot lower F4 and the boundary term F3 alone decides, as without a density model.
  // 0: the outside residual is zero.
  double density_ceiling = 0.0;
};

// The unweighted terms: F1 = Σ_j ω_j ∫(1 − cos φ_j) ds, F2 = Σ_j ω_j ∫|Δu_j|² ds (F2² of eq. 8),
// F3 = ∫ penalty ds over both surfaces, and with a density grid (otherwise F4 = 0):
//   CDM: F4 = c_ρ ∫⟨∇Φρ, t⟩² ds (∇Φρ by central differences of the grid),
//   BOM: F4 = ∫ o² ds + c_BOM ∫ S(o)² ds, o the trilinear occupancy at the guide, S the smoothed
//        surcharge step around the threshold (surcharge_step): the paper's ∫δ ds where o is 0 or
//        1, plus c_BOM where the guide runs through a region denser than the threshold;
//   both plus ∫ F4max·(H(u_S) + H(u_V))² ds, F4max = density_ceiling (the grid's largest
//        integrand, density_ceiling), u_S/u_V how far the sample lies behind the scalp/beyond the
//        volume, H the C¹ step from 0 at the surface to 1 a density voxel beyond it: outside the
//        acceptable region F4 is never lower than anywhere inside.
// F5 = Σ_k |F_k|² over the interior point forces (dimensionless), weighted by w5.
// Quadrature is the trapezoidal rule on the samples, exactly what the residuals sum to.
struct GuideTerms {
  double f1 = 0.0, f2 = 0.0, f3 = 0.0, f4 = 0.0, f5 = 0.0;
  double total = 0.0;       // Σ wᵢFᵢ
};
// eta: targets.load_count() loads (f_L, m(0), F_1 … F_K).
GuideTerms evaluate_guide_terms(const GuideTargets& targets, const double* eta);
// The same for a heavy rod's multiple-shooting solution (GuideSolve::solution).
GuideTerms evaluate_guide_terms(const GuideTargets& targets, const ShootingResult& solution);

// The residuals the optimiser sees at eta (blocks F1, F2, F3, then F4 when targets.density is
// set, then F5 with point forces), and, when `jacobian` is given, their derivatives in eta by
// automatic differentiation (row-major, targets.load_count() per residual). For tests of the
// residuals and their jets.
std::vector<double> guide_residuals(const GuideTargets& targets, const double* eta, std::vector<double>* jacobian = nullptr);

// The residuals as the optimiser sees them: the F1 and F2 residuals of all neighbours at a sample
// merged into one residual per sample and term (their sum of squares then falls short of the full
// one by `constant`, whatever the shape). Same Jacobian layout. For tests of the merging.
struct MergedGuideResiduals {
  std::vector<double> residuals, jacobian;
  double constant = 0.0;
};
MergedGuideResiduals merged_guide_residuals(const GuideTargets& targets, const double* eta);

struct GuideSolve {
  double eta[kMaxGuideLoads] = {};  // best (f_L, m(0), F_1 … F_K), dimensionless
  // The rod's scheme (rod_scheme of the targets' model). With multiple shooting the rod is
  // optimised in its terminal loads, `solution` holds the pieces its shape is traced from (one
  // integration from eta would not reproduce it), and solution.terminal_torque is t_L.
  RodScheme scheme = RodScheme::single_shooting;
  ShootingResult solution;
  // 1, or less for a rod whose weight could not be followed to the full weight (a fold, see
  // hang_under_weight): then `solution` is the hanging rod at this share, termination "NO_START".
  double weight_share = 1.0;
  int iterations = 0;
  int evaluations = 0;
  bool converged = false;
  std::string termination;
  double initial_cost = 0.0, final_cost = 0.0;  // Ceres' ½Σr²
};

// A trust-region solve (normal equations, one thread) from `start`, stopped by the relative
// tolerance, the iteration cap or `stall` (then termination "STALL", converged): Levenberg–
// Marquardt, or Powell's dogleg when targets.density is set (see solver_options in objective.cpp).
// A solve by multiple shooting given no stall test stops at a stall of 30 iterations that lowered
// its cost by under 1 % (kMultipleShootingStall in objective.cpp).
// Never returns NaN: a failed solve keeps the best finite iterate (or the start).
// `near`: for a heavy rod, the shooting pieces of a solved neighbour, from which the first solve
// at the start loads is tried before the load continuation from rest (null: from rest only).
// `start`: targets.load_count() loads.
GuideSolve optimise_guide(const GuideTargets& targets, const double* start, int max_iterations, double tolerance,
                          const StallTest& stall = {}, const ShootingResult* near = nullptr);

// What a solve's scheme makes of it. The shape and m(1): one integration from (f_L, m(0)), or the
// multiple-shooting solution traced piece by piece, under the share of its weight it carries.
FibreShape solved_shape(const GuideTargets& targets, const GuideSolve& solve, Vec3& terminal_torque);
// Its terms F1–F4, on that shape.
GuideTerms solved_terms(const GuideTargets& targets, const GuideSolve& solve);
// How many of a start's six loads the scheme reads: all of (f_L, m(0)) for single shooting; only
// f_L for multiple shooting, whose terminal torque starts at zero (a pre-guide's).
int start_loads_read(RodScheme scheme);

}  // namespace hairfit
