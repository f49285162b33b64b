// Closest-point transform within a narrow band (Mauch 2003, "Efficient algorithms for solving
// static Hamilton–Jacobi equations", ch. on the CPT): each mesh feature scan-converts a convex
// polyhedron that contains the part of its Voronoi region within distance r, and writes the exact
// distance to that feature into the voxels inside, keeping the smallest. Internal to lib/field.
#pragma once
#include <array>
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

// What every scan of a mesh shares (the band's and the far field's coarse one), computed once:
// each edge's unit direction and length, and how far each edge's and vertex's region reaches per
// unit radius, the largest u·(±x), u·(±y), u·(±z) over the unit vectors u of its cone of normals,
// in that order (a region of radius r spans its feature's box grown by r times these).
struct ScanRegions {
  std::vector<Vec3> edge_dirs;
  std::vector<double> edge_lengths;
  std::vector<std::array<double, 6>> edge_supports, vertex_supports;
};
ScanRegions scan_regions(const MeshFeatures& features, int threads);

// Exact signed distances for every node within distance r (cm) of the mesh. Deterministic for
// any thread count: work is split into fixed z-slabs and the minimum is order-independent.
BandScan scan_band(const MeshFeatures& features, const ScanRegions& regions, const GridGeometry& grid, double r,
                   int threads);

// The closest point of feature `key` to p, and the pseudo-normal that signs the distance there.
struct FeaturePoint {
  Vec3 point;
  Vec3 normal;
};
FeaturePoint closest_on_feature(const MeshFeatures& features, int key, const Vec3& p);

}  // namespace hairfit::field
