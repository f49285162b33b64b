// What signs a field robustly (docs/design.md §2): triangle soups and their generalized winding
// numbers (Jacobson, Kavan and Sorkine-Hornung 2013). A point is inside where any of the soups'
// winding numbers exceeds ½.
#pragma once
#include <functional>
#include <vector>

#include "core/fast_winding.h"
#include "core/mesh.h"

namespace hairfit {

// A mesh with a weight: the soup's winding number counts its own `weight` times (−1 reverses it).
struct SoupPart {
  const Mesh* mesh = nullptr;
  int weight = 1;
};

// A soup: its parts, the estimate of their weighted winding number with a rigorous bound on the
// estimate's error, and the decision w > ½ where no estimate decides; optionally estimates at
// many nearby points at once with accuracy parameter β (FastWindingNumber::estimate_box), one per
// point, each with its rigorous bound. The functions are called concurrently and must be pure functions of the points.
struct WindingSoup {
  std::vector<SoupPart> parts;
  std::function<WindingEstimate(const Vec3&)> estimate;
  std::function<bool(const Vec3&)> above_half;
  std::function<void(const std::vector<Vec3>&, double, std::vector<WindingEstimate>&)> estimate_box;
};

class DistanceField;

// Inside where any soup's winding number exceeds ½, or where `negative_in` (when given) reads
// negative; neither: the pseudo-normals' sign.
struct RobustInside {
  std::vector<WindingSoup> soups;
  const DistanceField* negative_in = nullptr;  // the volume takes the head's inside as its own
  bool empty() const { return soups.empty() && !negative_in; }
};

}  // namespace hairfit
