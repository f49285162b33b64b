// Pre-guides (paper §3.4): sparse fibres that sample the main flow. Each starts straight along its
// growth direction and is bent by a terminal force normal to that direction (in the plane of the
// surface normal and the growth direction) whose magnitude grows by continuation until the tip is
// immersed in the hair volume at a target depth: shallow at the top of the head, deeper for lower
// roots, as a share of the local thickness of the hair layer.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "core/digest.h"
#include "core/exec.h"
#include "guides/boundary.h"
#include "guides/hair_rod.h"
#include "rod/rod_shooting.h"
#include "scalp/flow_lookup.h"
#include "scalp/roots.h"

namespace hairfit {

// How a pre-guide is bent into the hair: the paper's terminal force normal to the initial axis,
// grown until the tip is immersed (tip), or a terminal force and a root couple in that plane that
// keep the whole rod nearest its immersion depth in the layer (layer, guides/layer_preguide.h;
// weightless rods: under gravity the tip construction is used). With layer, a root that hangs
// (scalp/roots.h hangs) still takes the tip construction: it falls free of the skull.
enum class PreguideImmersion { tip, layer };

struct PreguideOptions {
  HairMaterial material;
  RodDiscretisation rod;
  std::array<double, 2> depth_range{0.15, 0.6};  // share of the local thickness: top of head → lowest roots
  double max_load = 40.0;                         // largest dimensionless terminal force F·L²/EI tried
  PreguideImmersion immersion = PreguideImmersion::tip;
  // With immersion = layer: the growth field, which each pre-guide then follows along its length
  // as well (a streamline in the layer); null: only its root direction comes from it.
  std::shared_ptr<const FlowLookup> flow;
  // With immersion = layer and the growth field: the rods rest along their path in the layer
  // (hair.rest_shape = "flow", guides/styled_rest.h) instead of straight.
  bool styled = false;
  Vec3 down{0, -1, 0};
  Vec3 front{0, 0, 1};
};

// A solved rod shape as the guide objective compares it: per node, in world axes.
struct FibreShape {
  std::vector<Vec3> nodes;     // cm, segments + 1, root first
  std::vector<Vec3> tangents;  // d3, unit
  std::vector<Vec3> darboux;   // R·κ·L: the frame's rotation rate per unit normalised arc length
};

struct PreGuide {
  Vec3 root = Vec3::Zero();       // cm
  Vec3 normal = Vec3::Zero();
  Vec3 direction = Vec3::Zero();  // growth direction at the root
  double length = 0.0;            // cm
  double height = 0.0;            // [0, 1] on the head
  Vec3 force = Vec3::Zero();        // terminal force f_L, dimensionless (F·L²/EI), world axes
  Vec3 root_moment = Vec3::Zero();  // m(0), dimensionless (M·L/EI), world axes
  FibreShape shape;
  double thickness = 0.0;     // cm from the root to the volume boundary
  double target_depth = 0.0;  // cm below the volume boundary the tip should reach
  double depth = 0.0;         // cm below the volume boundary the tip reached (−Φ_volume(tip))
  bool reached = false;       // the tip met its target depth (tip: within 1e-3 of the thickness;
                              // layer: its layer coordinate within 0.1 of the target)
  int solves = 0;             // forward integrations with jets (Newton steps) spent
  // The share of its weight the pre-guide carries: 1, or less where the weight continuation met a
  // fold before the full weight (then the shape is that equilibrium's, and `reached` is false).
  double weight_share = 1.0;
};

struct PreGuides {
  std::vector<PreGuide> items;
  // Newton steps of the load marches the pre-guides share (make_preguides: rods with their loads
  // at the tip and a straight natural shape follow one march per compliance); not in any item's
  // `solves`.
  int shared_solves = 0;
  int size() const { return static_cast<int>(items.size()); }
};

// The share of the local thickness a pre-guide rooted at this height (0 lowest, 1 top of the
// head) is to be immersed to: depth_range from the top of the head to the lowest roots.
double immersion_share(const std::array<double, 2>& depth_range, double height);
inline double immersion_share(const PreguideOptions& options, double height) {
  return immersion_share(options.depth_range, height);
}

// A pre-guide as it starts, from root i of the set: root, normal, direction, length, height, the
// layer's thickness at the root and the depth its tip is to reach (immersion_share of it).
PreGuide preguide_start(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& options);

// A rod under its own weight alone, with no terminal load, on the branch that falls over and hangs
// (as every pre-guide under gravity starts): the continuation in the weight, first from rest
// under the full weight, then, where that stalls, in shares held to a tip turn of 15°. Where a
// fold ends the branch short of the full weight, `solution` is the last equilibrium reached, at
// `weight_share` of the weight (its force_per_length says which).
struct HangingRod {
  ShootingResult solution;
  double weight_share = 0.0;
};
HangingRod hang_under_weight(const RodModel& model, const RodDiscretisation& rod);

// The model a solution at `weight_share` of the weight is traced with: the weight scaled, and at
// share 0 (nothing carried) no support either, so that the solution is the straight unloaded rod.
RodModel carrying_share(const RodModel& model, double weight_share);

// One pre-guide per root, in root order; the same for any thread count. Rods loaded only at the
// tip with a straight natural shape (no weight, no curl) solve one dimensionless problem in their
// root frame, so the load march is followed once per compliance and replayed, rotated, by each.
PreGuides make_preguides(const RootSet& roots, const Boundary& boundary, const PreguideOptions& options,
                         const Exec& exec = {});
// Root i's pre-guide on its own, following its own load march: make_preguides' item i, to
// round-off where make_preguides replays a shared march.
PreGuide solve_preguide_alone(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& options);

// The shape of a rod with dimensionless loads (initial-value form: one forward integration), and,
// if asked, the moment m(1) that integration ends with.
FibreShape fibre_shape(const RodModel& model, const Vec3& root, double length, const RodDiscretisation& rod,
                       const Vec3& force, const Vec3& root_moment, Vec3* terminal_moment = nullptr);
// The same with `point_forces` interior point forces (rod_point_forces.h): loads = (f_L, m(0),
// F_1 … F_K), 6 + 3K scalars.
FibreShape fibre_shape(const RodModel& model, const Vec3& root, double length, const RodDiscretisation& rod,
                       const double* loads, int point_forces, Vec3* terminal_moment = nullptr);

// The same from a shooting solution, traced piece by piece when it has pieces (heavy rods).
FibreShape fibre_shape(const RodModel& model, const Vec3& root, double length, const RodDiscretisation& rod,
                       const ShootingResult& solution);

Digest digest(const PreGuides& preguides);

}  // namespace hairfit
