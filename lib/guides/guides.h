// Principal guides (paper §3.4, eq. 6–9): one per cluster, the rod whose six load parameters
// minimise Σ wᵢ·Fᵢ, optimised with Ceres (Levenberg–Marquardt; Powell's dogleg for the solves with
// the density term; automatic differentiation through the rod integrator). The loads are parameterised in the initial-value form η̃ = (f_L, m(0))
// (docs/design.md §1): every evaluation is one forward integration and t_L = m(L) is an output.
#pragma once
#include <string>
#include <vector>

#include "core/curves.h"
#include "core/digest.h"
#include "density/grid.h"
#include "guides/density_term.h"
#include "guides/preguides.h"

namespace hairfit {

enum class BoundaryForm {
  smooth,  // flat deep inside, the step of c_d smoothed over the last boundary_width inside the
           // surface, a Huber ramp outside: C¹, what the optimiser should see
  paper,   // eq. 9 exactly: |d| inside, c_d + |d| outside (for comparison)
  layer,   // the ramp narrowed to a quarter of the local layer thickness Φ_S − Φ_V where that is
           // thinner than 4·boundary_width, rising as x² and on beyond the surface with the slope
           // it reaches: a thin shell keeps a penalty-free middle and no flat step at its surfaces
};

struct GuideWeights {
  double direction = 0.4;   // w1, F1 (eq. 7)
  double similarity = 0.2;  // w2, F2² (eq. 8, squared)
  double boundary = 0.4;    // w3, F3 (eq. 9)
  double density = 0.0;     // w4, F4 (§3.5)
};

struct GuideOptions {
  HairMaterial material;
  RodDiscretisation rod;
  int samples = 16;            // residual samples K along each guide (normalised arc length)
  int neighbours = 3;          // pre-guides each guide follows
  int max_iterations = 100;
  double tolerance = 1e-6;     // Ceres function tolerance (relative cost decrease)
  BoundaryForm boundary = BoundaryForm::smooth;
  double outside_penalty = 3.0;   // c_d, cm
  double boundary_width = 1.0;    // cm
  GuideWeights weights;
  // Interior point forces per guide (0–3, rod_point_forces.h): where the layer holds the hair
  // along its length, not only at its end. 0 is the paper's terminal load alone. w5 weighs
  // F5 = Σ|F_k|² (dimensionless forces), so that the layer pushes no harder than it must.
  int point_forces = 0;
  double point_force_weight = 1e-4;
  bool warm_start = true;      // start from the neighbours' loads (else straight, the paper)
  // hair.rest_shape = "flow": the growth field each guide rests along (guides/styled_rest.h), at
  // its pre-guides' immersion depth (depth_range); null: straight at rest.
  std::shared_ptr<const FlowLookup> styled;
  std::array<double, 2> depth_range{0.15, 0.6};
  Vec3 down{0, -1, 0};
  Vec3 front{0, 0, 1};
};

struct Guide {
  Vec3 root = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  Vec3 direction = Vec3::Zero();
  double length = 0.0;              // cm
  Vec3 force = Vec3::Zero();        // f_L, dimensionless (F·L²/EI), world axes
  Vec3 root_moment = Vec3::Zero();  // m(0), dimensionless (M·L/EI)
  Vec3 terminal_torque = Vec3::Zero();  // m(L), dimensionless: the paper's t_L
  // F_1 … F_K, dimensionless, world axes, at nodes point_force_node(k, K, segments); empty
  // without guides.point_forces.
  std::vector<Vec3> point_forces;
  double force_scale = 1.0;         // EI/L², dyn: multiply dimensionless forces by it for cgs
  double moment_scale = 1.0;        // EI/L, dyn·cm
  FibreShape shape;
  std::vector<int> neighbours;            // pre-guide indices followed
  std::vector<double> neighbour_weights;  // their weights (sum 1)
  int iterations = 0;     // Levenberg–Marquardt iterations
  int evaluations = 0;    // cost evaluations (residual-only and with Jacobian)
  bool converged = false;
  std::string termination;  // Ceres' word for why it stopped
  double initial_cost = 0.0;
  double cost = 0.0;        // Σ wᵢ·Fᵢ at the result (as least squares: ½Σr² = ½·Σ wᵢFᵢ)
  double f1 = 0.0, f2 = 0.0, f3 = 0.0, f4 = 0.0, f5 = 0.0;  // unweighted terms at the result
  // With effects.contact: the largest support force per length the scalp exerts on the guide
  // (dyn/cm) and the share of its nodes beyond the first tenth of its length (the root's own
  // region) within the contact layer; 0 without contact.
  double contact_force = 0.0;
  double contact_share = 0.0;
};

// Whether the layer holds a guide: one of its interior point forces is not zero.
inline bool held_by_layer(const Guide& g) {
  for (const Vec3& f : g.point_forces)
    if (!f.isZero(0.0)) return true;
  return false;
}

struct Guides {
  std::vector<Guide> items;
  int size() const { return static_cast<int>(items.size()); }
  Curves curves() const;  // one polyline per guide, guide id = index
};

// Optimises one guide per base. `bases` are the cluster centres (scalp/roots.h RootSet).
Guides make_guides(const RootSet& bases, const PreGuides& preguides, const Boundary& boundary, const GuideOptions& options,
                   const Exec& exec = {});

// With a density model (paper §3.5, docs/design.md §6): guides in index order, in batches of
// density.batch; each batch is optimised in parallel (exec.threads) with the F4 term against
// the frozen density of all earlier batches (each guide continued from its solve without F4, and
// GuideTargets::density_ceiling the batch's density_ceiling), then its guides deposit into
// the grid in index order (grow_guide_fibres for CDM, guide_tube for BOM). Byte-identical for any thread count.
// `density` is the grid after the last batch (BOM occupancy 0/1, CDM cell diagonals).
struct DensityGuides {
  Guides guides;
  DensityGrid density;
  int batches = 0;
  // CDM: the fibres deposited, every pore's as make_strands grows it for these guides before the
  // head exit and the cut (fibre_point_count(density.wisp) points per pore, pore order), which
  // make_strands can take over (its `grown`) instead of growing them again. BOM: empty.
  std::vector<Vec3> fibres;
};
DensityGuides make_guides_with_density(const RootSet& bases, const PreGuides& preguides, const Boundary& boundary,
                                       const GuideOptions& options, const GuideDensityOptions& density,
                                       const Exec& exec = {});

// The figures report.json carries for the stage.
struct GuideFigures {
  int guides = 0;
  int failures = 0;  // not converged
  double mean_iterations = 0.0;
  int max_iterations = 0;
  double mean_evaluations = 0.0;
  double inside_fraction = 0.0;       // share of the guide nodes after the root in the acceptable region
  double inside_head_fraction = 0.0;  // share behind the scalp
  double outside_volume_fraction = 0.0;
  // Of those, the nodes on a guide's last stretch outside the volume, from its last node inside to
  // its tip: hair longer than the volume holds along its path (cutting shortens its strands), and
  // the guides that end so.
  double outside_tip_fraction = 0.0;
  int guides_ending_outside = 0;
  double mean_direction_mismatch = 0.0;  // mean 1 − cos φ to the followed pre-guides
  // The same weighted by how far each pre-guide node is followed (1 inside the acceptable region,
  // 0 a boundary width beyond it): the mismatch where the guides are asked to follow at all.
  double followed_direction_mismatch = 0.0;
  // Rods at the edge of what the discretisation resolves: the dimensionless weight w = ρA|g|L³/EI
  // (0 without gravity) and the guides whose bending layer under their weight, L/√w, is shorter
  // than one rod segment (w > segments²): finite, but coarse where they leave the root.
  double max_weight = 0.0;
  int unresolved_weight = 0;
  int shorter_than_voxel = 0;  // shorter than one voxel of the fields, which cannot shape them
  // With effects.contact: the largest guide's contact force (dyn/cm), the mean share of guide
  // nodes in contact (as Guide::contact_share), and the guides resting on the scalp beyond their
  // root's tenth.
  double max_contact_force = 0.0;
  double contact_share = 0.0;
  int guides_in_contact = 0;
  // With guides.point_forces: the guides the layer had to hold (a non-zero point force) and the
  // largest point force (dyn).
  int guides_held = 0;
  double max_point_force = 0.0;
};
// `voxel` is the distance fields' voxel edge (cm).
GuideFigures guide_figures(const Guides& guides, const PreGuides& preguides, const Boundary& boundary,
                           const GuideOptions& options, double voxel);

Digest digest(const Guides& guides);

}  // namespace hairfit
