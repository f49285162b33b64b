// Closest-point transform within a narrow band (Mauch 2003, "Efficient algorithms for solving
// static Hamilton–Jacobi equations", ch. on the CPT): each mesh feature scan-converts a convex
// polyhedron that contains the part of its Voronoi region within distance r, and writes the exact
// distance to that feature into the voxels inside, keeping the smallest. Internal to lib/field.
#pragma once
#include <cstdint>
#include <vector>

#include "core/grid_geometry.h"
#include "field/mesh_features.h"

namespace hairfit::field {

// Feature keys: faces [0, F), edges [F, F+E), vertices [F+E, F+E+V). Among equal distances the
// smaller key wins, so the result never depends on the order features are scanned in.
struct BandScan {
  std::vector<double> value;  // signed distance (cm) where |d| ≤ r, +infinity elsewhere
  std::vector<int32_t> key;   // feature that gave value (−1 outside the band)
  int64_t band_voxels = 0;
};

// Exact signed distances for every node within distance r (cm) of the mesh. Deterministic for
// any thread count: work is split into fixed z-slabs and the minimum is order-independent.
BandScan scan_band(const MeshFeatures& features, const GridGeometry& grid, double r, int threads);

// The closest point of feature `key` to p, and the pseudo-normal that signs the distance there.
struct FeaturePoint {
  Vec3 point;
  Vec3 normal;
};
FeaturePoint closest_on_feature(const MeshFeatures& features, int key, const Vec3& p);

}  // namespace hairfit::field
