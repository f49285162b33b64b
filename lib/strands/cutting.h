// Final cutting (paper §3.6): a fibre that leaves the hair volume and stays outside for longer
// than a threshold before re-entering is cut where it first left.
#pragma once
#include <functional>
#include <vector>

#include "core/types.h"

namespace hairfit {

// Signed distance to the volume boundary in cm: negative inside, positive outside.
using DistanceFunction = std::function<double(const Vec3&)>;

struct CutResult {
  std::vector<Vec3> points;  // the kept part, root first; unchanged when not cut
  std::vector<double> distances;  // distance(p) at each kept point, so callers need not ask again
                                  // (or ±infinity where `quick` gave it: the sign is always exact)
  bool cut = false;
  double outside_length = 0.0;  // cm outside the volume in the stretch that caused the cut
};

// Walks the polyline root to tip. Boundary crossings are located on each segment by linear
// interpolation of the distance at its ends; the length outside is measured between crossings.
// At the first excursion longer than `threshold` cm the fibre ends at the crossing where it left.
// An excursion that runs to the tip counts its length up to the tip. A stretch outside that starts
// at the root is never cut (the root is where the scalp puts it). With `cut_tips`, a fibre whose
// tip lies outside (after it has been inside) is cut where that last excursion started, however
// short: it never re-enters.
// `quick` (optional) returns distance(p), or ±infinity with its sign where that sign is certain
// at less cost (DistanceField::side): the walk asks it first and asks `distance` only at the ends
// of segments that cross the boundary, with the same result as without it.
CutResult cut_at_exit(const std::vector<Vec3>& points, const DistanceFunction& distance, double threshold,
                      const DistanceFunction& quick = nullptr, bool cut_tips = false);

// The same on the n points in place (make_strands' fibres lie in one array): returns how many are
// kept (n when not cut), sets d[0..n) to the distances (those of the kept points are
// CutResult::distances; d is scratch beyond them), `cut` and `outside_length`.
std::size_t cut_in_place(Vec3* points, std::size_t n, double* d, const DistanceFunction& distance, double threshold,
                         bool cut_tips, const DistanceFunction& quick, bool& cut, double& outside_length);

}  // namespace hairfit
