// The field beyond the band: a coarse grid of signed distances to mesh points found by
// propagating closest points outward from the exact band (a closest-point "dead reckoning" sweep,
// Grevera 2004). Internal to lib/field.
#pragma once
#include <vector>

#include "field/band_scan.h"
#include "field/distance_field.h"
#include "field/winding_signs.h"

namespace hairfit::field {

struct FarField {
  Vec3i dims = Vec3i::Zero();  // coarse node (I,J,K) is fine node coarse_factor·(I,J,K)
  std::vector<double> values;  // signed distance (cm), x fastest
  std::vector<int32_t> key;    // the feature (band_scan.h's keys) each value is the distance to
};

// Coarse nodes within r + √3·(coarse spacing) of the mesh get their exact signed distance (a CPT
// scan of the coarse grid), so every coarse cell touching the fine band interpolates exact values;
// nodes in the fine band take the fine sample itself. Every other node gets the distance to the
// closest point carried by its best neighbour over repeated 8-direction sweeps (dead reckoning),
// with that neighbour's sign: a distance to an actual mesh point, never below the true distance.
FarField make_far_field(const MeshFeatures& features, const ScanRegions& regions, const GridGeometry& grid,
                        const BandScan& band, double r, int coarse_factor, int threads);

// Every node of `values` beyond the band (+infinity there) gets its far-field sample: the trilinear
// interpolation of its coarse cell's magnitudes, or, where that is not above r (the band's width),
// the distance to the nearest of the features the cell's corners are closest to (never below the
// true distance, which exceeds r there), signed as distance_field.h states it
// (with `inside`: the robust inside's at the node, certified: from a far coarse corner along far
// samples where the rims' bound allows, by the inside's own decision elsewhere; without: the
// sign of the interpolated signed coarse values). Deterministic for any thread count.
// `in_band` marks the band's samples (1), whose values are final.
void fill_beyond_band(const MeshFeatures& features, const GridGeometry& grid, const FarField& far, int coarse_factor, double r,
                      const RobustSigns* inside, const std::vector<std::uint8_t>& in_band, std::vector<double>& values,
                      int threads);

}  // namespace hairfit::field
