// The field beyond the band: a coarse grid of signed distances to mesh points found by
// propagating closest points outward from the exact band (a closest-point "dead reckoning" sweep,
// Grevera 2004). Internal to lib/field.
#pragma once
#include <vector>

#include "field/band_scan.h"

namespace hairfit::field {

struct FarField {
  Vec3i dims = Vec3i::Zero();  // coarse node (I,J,K) is fine node coarse_factor·(I,J,K)
  std::vector<double> values;  // signed distance (cm), x fastest
};

// Coarse nodes inside the band keep their exact value; every other node gets the distance to the
// closest point carried by its best neighbour over repeated 8-direction sweeps, signed by that
// point's pseudo-normal. Values are distances to actual mesh points, so never below the true
// distance; they are close to it where closest points vary smoothly.
FarField make_far_field(const MeshFeatures& features, const GridGeometry& grid, const BandScan& band,
                        int coarse_factor);

}  // namespace hairfit::field
