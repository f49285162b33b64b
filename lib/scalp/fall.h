// The fall from the hull (issue 47): the way a hair takes from its root when it falls under its
// weight through the hair's region, supported by the skin and held by the hull, and how much of
// that way lies below the scalp's rim. A hull that reaches the shoulders gives a long fall there;
// a cap that ends at the hairline gives none past the rim. The roots read the hair's fall and its
// length off it, per scalp vertex, instead of a global key (scalp/hull_hair.h).
//
// The bead: it leaves the root kHangStart off the skin and moves down in steps of `step`. Where a
// step would leave the region, through the skin into the head or through the hull out of the
// hair volume, it slides: down loses its part along that surface's normal, as a bead on a
// frictionless surface, and the step is pulled back to kFallClearance inside the surface. It
// stops where the slide is flatter than kFallSlope (it rests on a floor: the bottom of a curtain,
// the end of a braid), where it cannot keep inside, where it has not gone on down at the least
// slope over kFallStall (it ends where it last did), or at `cap`. At the top of the head down is
// normal to the skin and the slide vanishes, so within kCrownLean of the root the bead takes the
// tangent toward down (toward −front where down is normal to the skin) however flat: a hair on the
// crown leans over before it falls.
#pragma once
#include <functional>
#include <limits>
#include <vector>

#include "scalp/chart.h"

namespace hairfit {

// The slide's least slope along the skin: sin of the angle below horizontal under which the bead
// comes to rest on it. Along the hull, kHullWallSlope: a hull facing down more steeply than a
// wall is where the hair ends (the bottom of a curtain), not a slope it gathers down.
constexpr double kFallSlope = 0.15;
constexpr double kHullWallSlope = 0.5;
// How far inside a surface the bead is pulled back to (cm), well within a layer of a few mm.
constexpr double kFallClearance = 0.05;
// How far from the root the bead leans over however flat its way (cm).
constexpr double kCrownLean = 2.0;
// How far (cm) the bead may go on past its lowest point before it rests there.
constexpr double kFallStall = 2.0;

// The region as two signed fields with their gradients: the skin (its distance, negative in the
// head) and the hull (the volume field, negative inside the hair volume).
struct FallRegion {
  std::function<void(const Vec3& p, double& value, Vec3& gradient)> skin;
  std::function<void(const Vec3& p, double& value, Vec3& gradient)> hull;
  Vec3 down = Vec3(0.0, -1.0, 0.0);   // unit
  Vec3 front = Vec3(0.0, 0.0, 1.0);   // unit: where the crown leans when down is normal to the skin
  double step = 0.1;                  // cm
  // The skin past the hairline is the floor closing the head: below it the layer's depth runs up
  // to that floor, along the hair, and the depth pull lifts the bead only where its level part
  // alone would leave it resting (fall_from). False where the skin goes on under the hull as a
  // shell and the depth runs across the hair.
  bool floor_past_hairline = true;
};

// The scalp's rim seen from above: for each direction about the vertical axis through the
// hairline's centre, the height of the hairline's lowest point in that direction (cm, along up).
struct RimHeights {
  Vec3 centre = Vec3::Zero();  // the hairline's centroid
  Vec3 up = Vec3::UnitY(), e1 = Vec3::UnitX(), e2 = Vec3::UnitZ();  // up and a horizontal frame
  std::vector<double> heights;  // per angular bin, relative to centre

  // How far p lies below the rim in its direction (cm; negative above it).
  double below(const Vec3& p) const;
};

// The rim heights of the chart's hairline in kRimBins directions. Exact at the hairline's
// vertices' directions, linear in angle between them; a direction the hairline never passes
// takes its nearest neighbour's.
constexpr int kRimBins = 720;
RimHeights rim_heights(const ScalpChart& chart);

struct Fall {
  double length = 0.0;      // cm, along the bead's way
  double below_rim = 0.0;   // cm of that way below the rim (RimHeights::below > 0)
  std::vector<Vec3> nodes;  // the way, one node a step from the start, when asked for
};

// How far along the way (cm) the bead makes up a miss of its depth of 1 cm, and the least gain
// in depth (cm) a step that does not descend must make.
constexpr double kFallDepthReach = 2.0;
constexpr double kFallDepthProgress = 0.01;
// A target that says: no pull, straight down.
constexpr double kNoDepth = std::numeric_limits<double>::quiet_NaN();

// The fall from `root` with unit outward `normal`, at most `cap` long. With a finite `target`
// (a share of the layer's depth, 0 at the hull and 1 at the skin) the bead is also pulled toward
// that share of the layer, as the paper's pre-guides are immersed (roots high on the head near
// the hull, lower ones deeper): it heads down + clamp(miss/kFallDepthReach, −1, 1)·∇Φ_V/|∇Φ_V|,
// miss = −Φ_V − target·(Φ_S − Φ_V) (cm), so that in a thick volume the hair falls through it at
// its depth instead of straight down by the head, and in a thin one it keeps to its middle.
Fall fall_from(const FallRegion& region, const RimHeights& rim, const Vec3& root, const Vec3& normal, double cap,
               double target, bool keep_nodes = false);

// The fall from every vertex of the chart (without nodes), each toward the depth `target` gives
// at its position (null: none).
std::vector<Fall> vertex_falls(const ScalpChart& chart, const FallRegion& region, double cap,
                               const std::function<double(const Vec3&)>& target, int threads);

}  // namespace hairfit
