// Hanging hair at rest along its fall (issue 47): a hair that hangs (scalp/roots.h hangs) rests
// along the way it falls through the region (scalp/fall.h), so that the unloaded rod already runs
// down the skull, hangs, and ends on the layer's floor, and its loads only correct that. A rod
// straight at rest, bent by a load at its tip and a couple at its root, cannot lie on the skull and
// then hang: the paper's pre-guide construction left 317 of the straight fixture's 435 pre-guides
// short of their depth, standing off the crown.
//
// The rest path pursues the fall: from the root along its growth direction, in N steps of
// h = L/N, the tangent turning at each step toward the point of the fall kFallLookAhead further
// along it than the path has come, by the share 1 − exp(−h/kFallRelaxation) (no kink at the
// root; the path joins the fall within a few relaxation lengths and then runs along it, its
// corners rounded). Past the fall's end it runs on along its last tangent. Internal to lib/guides.
#pragma once
#include <array>
#include <vector>

#include "guides/boundary.h"
#include "guides/styled_rest.h"
#include "scalp/fall.h"

namespace hairfit {

// cm: how far ahead on the fall the rest path aims, and the length over which it turns.
constexpr double kFallLookAhead = 1.0;
constexpr double kFallRelaxation = 0.5;

// The region the fall moves in, seen through the two fields: the scalp field as the skin, the
// volume field as the hull.
FallRegion fall_region(const Boundary& boundary, const Vec3& down, const Vec3& front);

// The rest path (N + 1 nodes and tangents, the first tangent `direction`) of a hair of `length`
// rooted at `root` with unit outward `normal`, pursuing its fall toward the share `target` of the
// layer's depth (fall_from).
StyledPath fall_rest_path(const FallRegion& region, const Vec3& root, const Vec3& normal, const Vec3& direction,
                          double length, double target, int segments);

// κ̂·L at the N + 1 nodes of the rod clamped in `root_frame` (d3 the growth direction) whose
// unloaded shape follows its fall_rest_path.
std::vector<Vec3> fall_rest(const FallRegion& region, const Vec3& root, const Vec3& normal, const Mat3& root_frame,
                            double length, double target, int segments);

}  // namespace hairfit
