// Hair styled along its flow (hair.rest_shape = "flow"): a fibre whose rest shape is the path it
// would take through the layer along the growth field, so that the unloaded rod already follows
// the flow and lies at its immersion depth, and its loads only correct that. The paper's fibres
// are straight at rest (or curled uniformly); with loads at the tip and a couple at the root alone
// such a rod cannot follow a flow that turns within the layer (a whorl, hair swept round the
// head), and rods from neighbouring roots run straight across each other.
//
// The path: from the root along its growth direction, in N steps of h = L/N, the tangent turning
// at each step toward the desired direction by the share 1 − exp(−h/ℓ), ℓ = kStyleRelaxation·L
// (a tensorline: dt/ds = (d − t)/ℓ, a fibre too stiff to take the field's turns sharper than
// about 1/ℓ, and no kink at the root). The desired direction is the growth field there, tilted
// along the scalp normal by the miss of the layer coordinate λ from its target,
// (λ* − λ)·T/kStyleDepthReach, T the layer's thickness there, the slope at most 1. The rest
// curvature is the rotation of the parallel-transported frame from each node's tangent to the
// next, in the frame's own axes (κ̂·L, as RodModel::kappa_hat holds it).
//
// Measured on the sculpted busts (bench/results/prepare.md): a streamline that takes the field's
// turns at once (midpoint rule, the tangent blended in from the root over ℓ) ran its hair into
// the whorl's tightening turns, and the guides crossed at 0.10–0.19 against 0.008–0.077.
// Internal to lib/guides.
#pragma once
#include <vector>

#include "guides/boundary.h"
#include "scalp/flow_lookup.h"

namespace hairfit {

// ℓ/L: the length over which the path's tangent takes up a turn of the field, as a share of the hair's.
constexpr double kStyleRelaxation = 0.1;
// How far along the path (cm) a miss of the whole layer's thickness in depth is made up.
constexpr double kStyleDepthReach = 2.0;

// The rest path's tangents at its N + 1 nodes (the first is the root frame's d3) and its nodes.
struct StyledPath {
  std::vector<Vec3> nodes;
  std::vector<Vec3> tangents;
};
StyledPath styled_path(const FlowLookup& flow, const Boundary& boundary, const Vec3& root, const Vec3& direction,
                       double length, double target, double thickness, int segments);

// κ̂·L at the N + 1 nodes of the rod (RodModel::kappa_hat) whose unloaded shape, clamped in
// `root_frame` (d3 the path's first tangent), follows the path's tangents.
std::vector<Vec3> rest_curvature(const StyledPath& path, const Mat3& root_frame);

// The rest curvature of a hair rooted at `root` with clamp `root_frame`, styled along `flow` at
// the depth share `immersion` of its layer: rest_curvature of its styled_path.
std::vector<Vec3> styled_rest(const FlowLookup& flow, const Boundary& boundary, const Vec3& root,
                              const Mat3& root_frame, double length, double immersion, int segments);

}  // namespace hairfit
