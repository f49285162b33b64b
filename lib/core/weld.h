// Welding points that lie within a tolerance of each other, as scans and exported meshes repeat
// vertices along seams at nearly (not exactly) the same position.
#pragma once
#include <vector>

#include "core/types.h"

namespace hairfit {

// Greedy in input order, so the result is deterministic: point i is kept when no kept point lies
// within `tolerance` of it (distance ≤ tolerance; 0 merges exact duplicates only), and otherwise
// merges into the lowest-indexed kept point within the tolerance. Returns, per point, the index
// of the kept point it belongs to (itself when kept); a merged point never keeps others.
// A spatial hash of cells four tolerances wide makes it O(n). Throws std::invalid_argument
// for a negative or NaN tolerance or a non-finite point.
std::vector<int> weld_points(const std::vector<Vec3>& points, double tolerance);

}  // namespace hairfit
