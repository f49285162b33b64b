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
  bool cut = false;
  double outside_length = 0.0;  // cm outside the volume in the stretch that caused the cut
};

// Walks the polyline root to tip. Boundary crossings are located on each segment by linear
// interpolation of the distance at its ends; the length outside is measured between crossings.
// At the first excursion longer than `threshold` cm the fibre ends at the crossing where it left.
// An excursion that runs to the tip counts its length up to the tip. A stretch outside that starts
// at the root is never cut (the root is where the scalp puts it).
CutResult cut_at_exit(const std::vector<Vec3>& points, const DistanceFunction& distance, double threshold);

}  // namespace hairfit
