// Weighted sample elimination (Yuksel 2015, "Sample Elimination for Generating Poisson Disk Sample
// Sets"): from M candidates keep exactly N with blue-noise spacing, by greedily removing the
// candidate with the largest crowding weight. Used for pores, pre-guide roots and guide centres.
#pragma once
#include <vector>

#include "core/types.h"

namespace hairfit {

// Keeps `target` of the `count` points (all of them when there are fewer) and returns their indices in
// ascending order. radius[i] is the Poisson-disk radius r_max at candidate i (length unit of the
// points; r_max = 1/sqrt(2√3·ρ) for a target density ρ per unit area of a surface); a pair
// interacts within 2·min(r_i, r_j) with weight (1 − d̂/(2r))⁸, d̂ = max(d, r_min) (Yuksel's weight
// limiting, r_min = r·0.65·(1 − (N/M)^1.5)). Deterministic for any thread count.
std::vector<int> eliminate_samples(const Vec3* points, const double* radius, int count, int target, int threads);
inline std::vector<int> eliminate_samples(const std::vector<Vec3>& points, const std::vector<double>& radius, int target,
                                          int threads) {
  return eliminate_samples(points.data(), radius.data(), static_cast<int>(points.size()), target, threads);
}

}  // namespace hairfit
