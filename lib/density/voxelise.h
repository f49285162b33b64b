// Voxelisation of a strand's generalised cylinder for the binary occupancy model (paper §3.5):
// each polyline segment with its two radii is a frustum (truncated cone); the voxels it
// intersects are found by the separating-axis test (Gottschalk et al. 1996, the paper's [6]).
#pragma once
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "density/grid.h"

namespace hairfit {

// A solid truncated cone: the convex hull of the disc of radius radius_a centred at a and the
// disc of radius radius_b centred at b, both perpendicular to b − a (cm).
struct Frustum {
  Vec3 a = Vec3::Zero();
  Vec3 b = Vec3::Zero();
  double radius_a = 0.0;
  double radius_b = 0.0;
};

// A generalised cylinder: a polyline (cm) with a radius (cm) at every point; segment i is the
// frustum (points[i], points[i+1], radii[i], radii[i+1]).
struct Tube {
  std::vector<Vec3> points;
  std::vector<double> radii;
};

// What counts as "the voxel is occupied by the segment".
enum class OccupancyShape {
  // The paper's test: the voxel intersects the frustum's oriented bounding box (15-axis SAT).
  // Conservative: also marks voxels near the OBB's corners, up to (√2 − 1)·r beyond the cone.
  obb,
  // Ours, the default: the voxel intersects the frustum itself (closed sets). Voxels whose centre
  // is clearly in or out are decided by the centre's distance; the rest by the OBB SAT (broad
  // phase), then GJK on box − frustum (exact: a separating support plane or an enclosing
  // simplex); the rare near-tangent cases GJK leaves open by closest-point iteration with a
  // separating-axis certificate, which keeps a voxel it cannot prove apart within 1e-6 voxel.
  frustum,
};

// The 15-axis separating-axis test between the axis-aligned box [lower, upper] and the frustum's
// OBB: centred at (a + b)/2, axes u = (b − a)/|b − a|, v = normalised u × e_m (e_m the world axis
// of u's smallest component), w = u × v; half-extents |b − a|/2, r, r with r = max(radius_a,
// radius_b).
bool box_intersects_obb(const Vec3& lower, const Vec3& upper, const Frustum& f);
// Whether the box [lower, upper] intersects the solid frustum, to within `tolerance` cm.
bool box_intersects_frustum(const Vec3& lower, const Vec3& upper, const Frustum& f, double tolerance);
// Euclidean distance (cm) from p to the solid frustum; 0 inside.
double distance_to_frustum(const Vec3& p, const Frustum& f);

// The cells of `grid` the frustum occupies, in index order, limited to cells with k in
// [k_begin, k_end) (the z-slab a thread owns; default: all). The frustum and the cells are
// closed sets: a cell that only touches the frustum counts (zero radii leave the segment's
// cells). A zero-length frustum (a == b, a flat disc) occupies nothing: the neighbouring segments
// cover it. Throws std::invalid_argument for a non-finite coordinate or a negative or non-finite
// radius.
std::vector<Vec3i> frustum_cells(const GridGeometry& grid, const Frustum& f, OccupancyShape shape,
                                 int k_begin = 0, int k_end = -1);
// frustum_cells without the cells `settled` marks (nonzero at the cell's grid index): those it
// neither tests nor returns. The binary model passes its occupancy, since a cell already occupied
// stays occupied whatever the frustum does; most cells of a crowded grid are skipped unasked.
std::vector<Vec3i> frustum_cells_unsettled(const GridGeometry& grid, const Frustum& f, OccupancyShape shape,
                                           const std::vector<double>& settled, int k_begin = 0, int k_end = -1);

// Every cell the tube occupies (union over its segments), distinct, sorted by grid index.
// Throws std::invalid_argument when points and radii differ in count.
std::vector<int64_t> tube_cells(const GridGeometry& grid, const Tube& tube, OccupancyShape shape);

// The paper's surcharge test (§3.5): the share of the cells the tube occupies that are already
// occupied (value ≥ ½) in `occupancy`, in [0, 1]; 0 when the tube occupies no cell. Compare it
// with the scene's threshold.
double occupied_share(const DensityGrid& occupancy, const Tube& tube, OccupancyShape shape = OccupancyShape::frustum);

// The paper's δ(s_i) of the BOM term: whether the segment a→b (cm) crosses a cell with value ≥ ½.
bool segment_hits_occupied(const DensityGrid& occupancy, const Vec3& a, const Vec3& b);

}  // namespace hairfit
