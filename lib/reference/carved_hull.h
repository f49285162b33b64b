// Scan-like carved hulls with their intended flow known (issue 48): the scalp and the hull a user
// cuts from a 3-D scan of a sculpted bust, and the direction in which each groove was carved, so a
// flow can be scored against the truth and not only for coherence.
//
// The head is the fixtures' ellipsoid (x to the person's left, y up, z to the front, cm); the
// scalp is its cap within 78° of an axis tilted 25° back. The hull is an open sheet over the cap,
// a smooth offset of the skin that is 0.1 cm thick at the hairline and 2.6 cm on the crown, cut by
// families of grooves. A family is the level sets of a phase ψ on the head's directions: its
// grooves run along n × ∇ψ, one period of ψ apart, U-shaped (narrower than the ridges between).
//   locks   grooves from the crown that turn across the head: at φ_c + κ(φ_c)·θ_c = const around
//           the cap axis, κ from −0.2 to 0.8, 20 around the head (1–2.5 cm apart);
//   curls   the locks, with three curls on the sides and the back: rings 1.1 cm apart, 2.8 cm out;
//   bun     the locks, with a bun on the back of the crown (4.5 cm high) the hair is wound into;
//   braids  the locks, with a braid from each temple round to the back (a rope twisted 35°) and
//           two smooth ribbon bows standing off the back (no grain: not scored);
//   fringe  the locks, with a fringe lying on the forehead below the hairline, combed down;
//   scan    the locks and curls, coarse (about 8k triangles over the hair) with scan noise;
//   tilted  the fringe's hull, coarse and noisy, the head turned 30° off the axes.
// The locks and the curls are fine (about 33k triangles over the hair) and clean; the others have
// scan noise (0.04 cm normal to the skin) and the coarse triangulation.
#pragma once
#include <string>
#include <vector>

#include "core/curves.h"
#include "core/mesh.h"

namespace hairfit {

enum class CarvedStyle { locks, curls, bun, braids, fringe, scan, tilted };

const std::vector<CarvedStyle>& all_carved_styles();
std::string carved_style_name(CarvedStyle style);

struct CarvedHull {
  Mesh scalp, hull;  // cm, oriented outward
  Vec3 down = Vec3(0, -1, 0), front = Vec3(0, 0, 1);
};

CarvedHull make_carved_hull(CarvedStyle style);

// The carved direction at (or above or below) p: the unit tangent of the groove through the
// head's direction of p. `weight` is 1 where one family carves the hull alone and 0 where two
// blend, on the crown (the locks meet there), on a bow, or outside the hair; `root_to_tip` says
// whether the direction's sign is known (the locks and the fringe grow away from the crown; the
// rings of a curl, a bun and a rope have none).
struct CarvedDirection {
  Vec3 direction = Vec3::Zero();
  double weight = 0.0;
  bool root_to_tip = false;
};

CarvedDirection carved_direction(CarvedStyle style, const Vec3& p);

// How closely curves follow the carving: the median angle (degrees, as lines) of each curve's
// tangent, in the plane across the head's radial direction, to the carved line at the node, over
// the nodes past the first fifth of each curve (a root's own tilt comes first) where one family
// carves the hull alone; and of the nodes on grooves with a known sign, the share running tip to root.
struct CarvedFlowScore {
  double median_degrees = 0.0, against = 0.0;
  std::size_t nodes = 0, signed_nodes = 0;
};

CarvedFlowScore score_carved_flow(CarvedStyle style, const Curves& curves);

}  // namespace hairfit
