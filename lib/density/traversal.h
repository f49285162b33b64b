// Voxel traversal of a segment (Amanatides & Woo 1987, "A fast voxel traversal algorithm"): the
// cells a straight segment crosses and the length of the segment inside each, for the continuous
// density model (paper §3.5: each fibre adds length-in-cell / cell diagonal) and for the
// segments-per-cell histogram (Fig. 5).
#pragma once
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "density/grid.h"

namespace hairfit {

struct CellCrossing {
  Vec3i cell = Vec3i::Zero();  // (i, j, k), always inside the grid
  double length = 0.0;         // cm of the segment inside this cell, > 0
};

// The cells the segment a→b (cm) crosses, in order from a to b, each once, with the length inside
// each. Properties:
// - The lengths add up to the length of the part of the segment inside the grid box (to round-off,
//   ~1e-15 relative): a segment partly outside the grid is clipped to the box; outside parts
//   deposit nothing.
// - A segment lying exactly on a cell face or edge goes to the cell on the upper side of that
//   plane (the cell floor() picks), except at the grid's upper faces, where it stays in the last
//   cell; where it passes exactly through a cell corner or edge, cells touched only at that point
//   (zero length) are not listed.
// - A zero-length segment, one with a non-finite coordinate, or one entirely outside the grid
//   yields nothing.
// The result appends to `out` (cleared first) so callers can reuse its storage in a hot loop.
void traverse_segment(const GridGeometry& grid, const Vec3& a, const Vec3& b, std::vector<CellCrossing>& out);
std::vector<CellCrossing> traverse_segment(const GridGeometry& grid, const Vec3& a, const Vec3& b);

}  // namespace hairfit
